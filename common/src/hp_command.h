/* The HP computer's command to the HA for one control period, as the HA core sees it, and the
 * end-to-end integrity check that ties it to the controller's computation (msg/ServoCommand.msg).
 * Shared verbatim by the Due firmware, the host link, the controller, the ground station and,
 * through libstack_common.so, the HiL's Python, so every end computes the CRC from one
 * implementation. Part of the HA's trusted code (checked with the core). C99, no heap. */
#ifndef HA_HP_COMMAND_H
#define HA_HP_COMMAND_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bytes of the little-endian ROS serialization covered by the CRC: every field before crc32. */
#define HA_HP_COMMAND_FIELDS_LEN 38u

typedef struct {
  uint32_t seq;
  uint32_t stamp_sec;
  uint32_t stamp_nsec;
  float throttle;
  float elevator_deg;
  float aileron_deg;
  float rudder_deg;
  float alpha_est_deg;
  float beta_est_deg;
  uint8_t estimator_converged;  /* 0 or 1 */
  uint8_t sensor_links_healthy; /* 0 or 1 */
  uint32_t crc32;
} HaHpCommand;

/* msg/OperatorCommand.msg carries the same CRC-32 over the little-endian ROS serialization of
 * every field before its crc32 (stamp, command, request_id, use_current, latitude, longitude,
 * altitude), which the sender (microhard_gs) computes and the HA's link checks. */
#define HA_OPERATOR_COMMAND_FIELDS_LEN 38u

/* CRC-32/ISO-HDLC (zlib's crc32): reflected polynomial 0xEDB88320, init and xorout 0xFFFFFFFF.
 * Detects all burst errors up to 32 bits, which rosserial's 8-bit sum does not. */
uint32_t ha_crc32(const uint8_t *data, size_t len);

/* Writes the ROS serialization of every field before crc32, in msg order, little endian. */
void ha_hp_command_pack_fields(const HaHpCommand *cmd, uint8_t out[HA_HP_COMMAND_FIELDS_LEN]);

/* The CRC the sender must put in crc32, and the receiver must find there. */
uint32_t ha_hp_command_compute_crc(const HaHpCommand *cmd);

#ifdef __cplusplus
}
#endif

#endif /* HA_HP_COMMAND_H */
