/* The narrow Board interface between the portable HA firmware and the hardware. The Due layer
 * (arduino_ha/src/board_due/), the host SIL (arduino_ha/sil/) and the host fake board
 * (arduino_ha/test/) implement it; the core never calls it directly: ha_app.c reads it once per
 * period, hands plain values to ha_core_step and writes the outputs back, and the firmware loop
 * (src/firmware/ha_firmware.h) moves the two byte ports' bytes. Every function gets the
 * implementation's context pointer first. */
#ifndef HA_BOARD_H
#define HA_BOARD_H

#include <stddef.h>
#include <stdint.h>

#include "../core/ha_types.h"
#include "../generated/ha_config.h"
#include "ha_retained.h"

#ifdef __cplusplus
extern "C" {
#endif

/* LED bits (Board.set_leds; ha_app_leds says which from the core's outputs). */
enum {
  HA_LED_HP = 1u,     /* HP drives the servos */
  HA_LED_HA = 2u,     /* HA safety controller drives (incl. recovering, latched) */
  HA_LED_MANUAL = 4u, /* pilot in command */
  HA_LED_FAULT = 8u   /* some check is failing this period */
};

/* A serial port, as rosflight's board offers one: what has arrived is read without waiting. */
typedef struct {
  /* Copies up to max_len of the bytes that have arrived into bytes[] and returns how many: 0 when
   * none, never more than max_len, never waiting for more. */
  size_t (*read)(void *ctx, uint8_t *bytes, size_t max_len);
  /* Sends len bytes: the Due's UART waits for room in its ring, the SIL's pty drops what a host
   * that is not reading cannot take (the link is built to lose bytes). May be NULL on a port the
   * firmware never writes to (the INS: its output is configured in the sensor's own flash). */
  void (*write)(void *ctx, const uint8_t *bytes, size_t len);
} HaBytePort;

typedef struct {
  void *ctx;
  /* Free-running microsecond clock; wraps at 2^32 (about 71 min), the core handles the wrap. */
  uint32_t (*micros)(void *ctx);
  /* Drive the four servos/ESC. Values are already checked, finite and inside S_u. */
  void (*write_servos)(void *ctx, const HaSurfaces *surfaces);
  /* Latest captured RC pulses incl. the PIC/CIC channel; sets rc->valid. */
  void (*read_rc)(void *ctx, HaRcInputs *rc);
  /* HA's own pitot (AMS5812). Returns 1 and writes *airspeed_ftps on a good reading, else 0. */
  int (*read_airspeed_ftps)(void *ctx, float *airspeed_ftps);
  /* Battery voltage. Returns 1 and writes *battery_v on a good reading, else 0. */
  int (*read_battery_v)(void *ctx, float *battery_v);
  /* Level of the HP reset line: 1 = hold the HP computer in reset, 0 = release. */
  void (*set_hp_reset)(void *ctx, int asserted);
  /* HA_LED_* bits (ha_app_leds). */
  void (*set_leds)(void *ctx, uint8_t leds);
  /* Called once per completed period; a hung loop stops kicking and the watchdog resets. */
  void (*kick_watchdog)(void *ctx);
  /* HA_RETAINED_WORDS (ha_retained.h) words of memory kept across a reset of the HA (watchdog,
   * brown-out of the core, software) and lost only with the power: the Due's SAM3X backup
   * registers. read_retained returns 1 and fills words[] (whatever they hold: the core checks
   * them), or 0 when the board keeps none; either pointer may be NULL for such a board. */
  int (*read_retained)(void *ctx, uint32_t words[HA_RETAINED_WORDS]);
  void (*write_retained)(void *ctx, const uint32_t words[HA_RETAINED_WORDS]);
  /* The rosserial link to the HP (the Due's programming or native USB port; a pty on the host).
   * A NULL read is a board without the port: the firmware then reads nothing from it. */
  HaBytePort hp_link;
  /* The VN-200's port 1 (the Due's Serial1; a pty the simulator writes on the host). */
  HaBytePort ins;
} HaBoard;

/* The servo pulse widths for surfaces the core output (inside S_u), in HA_U_* order, by the
 * aircraft's servo calibration: what a board's write_servos puts on its pins (ha_app.c). */
void ha_surfaces_to_pulses_us(const HaAircraftConfig *cfg, const HaSurfaces *s,
                              uint16_t pulses_us[HA_U_DIM]);

#ifdef __cplusplus
}
#endif

#endif /* HA_BOARD_H */
