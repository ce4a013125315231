/* THE VN-200 SEAM: where the INS solution enters the HA.
 *
 * The VN-200's port 1 is wired to the Due's Serial1, so the HA senses attitude, rates, altitude
 * and position without the HP. Its bytes are read here every loop and handed to
 * src/vn200/ha_vn200_feed.c, the one rule (shared with the host SIL) that splits them into
 * packets with the VN-200 protocol core (vn200_driver/core, put beside it when the sketch is
 * assembled, `make sketch-ha`), decodes them and passes each solution to the core's INS adapter
 * (core/ha_ins.c): the only place INS data enters HaInputs. ASCII sentences (register responses)
 * are counted and ignored; bad packets are counted by the framer and dropped.
 * README.md, "VN-200", says how to wire and configure the sensor. */
#ifndef DUE_INS_SEAM_H
#define DUE_INS_SEAM_H

#include <stddef.h>
#include <stdint.h>

#include "../core/ha_config.h"
#include "../core/ha_core.h"
#include "../core/ha_ins.h"
#include "../vn200/ha_vn200_feed.h"

typedef struct {
  uint32_t bytes_read;
  uint32_t binary_packets; /* intact binary packets (CRC good) */
  uint32_t ascii_frames;   /* ignored */
  uint32_t decode_errors;  /* intact packets vn_bin_decode refused (incl. non-finite values) */
  uint32_t bad_packets;    /* framer: corrupt or truncated packets */
  uint32_t solutions_used; /* solutions that made the state valid */
  uint32_t solutions_rejected;
} DueInsStats;

/* Opens Serial1 at DUE_VN200_BAUD and resets the framer and the adapter (home not latched).
 * cfg is the aircraft configuration the adapter reads (stall speed, airborne altitude). */
void due_ins_begin(const HaAircraftConfig *cfg);

/* Reads what Serial1 has buffered (bounded per call) and applies it with due_ins_feed().
 * ha_on_ground: the core's latest verdict (HaOutputs.on_ground), on which alone home latches. */
void due_ins_poll(HaInputs *inputs, uint8_t ha_on_ground, uint32_t now_us);

/* Frames, decodes and applies bytes from the VN-200 stream, received at now_us. Partial packets
 * are kept for the next call. A packet with a non-finite value makes the state invalid. */
void due_ins_feed(const uint8_t *bytes, size_t len, HaInputs *inputs, uint8_t ha_on_ground,
                  uint32_t now_us);

DueInsStats due_ins_stats(void);

/* The INS adapter's state: home (latched from this INS) for the link to publish. */
const HaIns *due_ins_state(void);

/* The adapter itself, for ha_app_restore: home kept across a reset of the Due. */
HaIns *due_ins_adapter(void);

/* The operator's SET_HOME, judged by the INS adapter (ha_ins_set_home) on the core's latest
 * on-the-ground verdict (HaOutputs.on_ground). */
int due_ins_set_home(uint8_t ha_on_ground, uint8_t use_current, double lat_deg, double lon_deg,
                     double alt_m);

#endif /* DUE_INS_SEAM_H */
