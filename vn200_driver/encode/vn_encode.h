/* VN-200 binary output packets built from a navigation solution: the sensor's side of
 * vn_binary.h, for the HiL simulator (hil/sensors.py, through vn200_sim/vn200_encode.py)
 * and tests. Host only: it needs libm for the quaternion, and the Due never builds packets, so
 * it lives outside core/ (which the HA firmware is assembled from).
 *
 * The bytes are those vn200_emulation.binary_packet() lays out: the fields the solution carries
 * in their documented places, zeros for every other documented field, each double rounded to
 * the packet's float as a C cast rounds it (Python's struct module does the same), the
 * quaternion from yaw, pitch, roll as vn200_emulation.quat_ned() computes it. */
#ifndef VN_ENCODE_H
#define VN_ENCODE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One output of the sensor in its units (deg, rad/s, m/s^2, gauss, kPa, degC, WGS84 ellipsoid
 * height in m, NED m/s). Doubles, as the simulator holds them: the encoder does the rounding.
 * vn200_encode.py packs the same layout (pinned by vn_encode_solution_size()). */
typedef struct {
  uint64_t time_startup_ns;
  uint64_t time_gps_ns; /* since the GPS epoch; the time group's week and time of week from it */
  double ypr_deg[3];
  double angular_rate_radps[3];
  double lla[3]; /* latitude deg, longitude deg, height m: INS and Common position alike */
  double vel_ned_mps[3];
  double accel_mps2[3];
  double mag_gauss[3];
  double temp_c;
  double pressure_kpa;
  double gps_pos_unc_m[3];
  double gps_vel_unc_mps;
  double ypr_unc_deg[3];
  double ins_pos_unc_m;
  double ins_vel_unc_mps;
  uint16_t ins_status;
  uint8_t num_sats;
  uint8_t gps_fix;
} VnSolution;

size_t vn_encode_solution_size(void);

/* Writes the packet for `groups` (bit n = group n+1) and `masks` (indexed by group, 6 entries)
 * into out[0..cap). Returns its length, or 0 when nothing was written: a NULL pointer, out too
 * small (VN_BIN_MAX_PACKET always suffices), a finite value too large for the float its field
 * is, or an infinite yaw, pitch or roll when the quaternion is asked for (the cases in which the
 * Python encoder raises). A mask bit the manual leaves undefined adds no
 * bytes, as in the Python encoder; the decoder rejects such a packet. */
size_t vn_bin_encode(uint8_t groups, const uint16_t *masks, const VnSolution *s, uint8_t *out,
                     size_t cap);

#ifdef __cplusplus
}
#endif
#endif
