/* The VN-200 stream into the HA core: bytes from the sensor's port 1 are split into packets by the
 * VN-200 protocol core (vn_framer_next), binary packets decoded (vn_bin_decode), copied into the
 * core's plain HaInsSample and handed to the core's INS adapter (core/ha_ins.c), the only place
 * INS data enters HaInputs. Plain C99 with no byte source of its own: the firmware loop
 * (firmware/ha_firmware.c) reads the Board's INS port into it, so the Due (Serial1), the host SIL
 * (a pty) and the fake board run this one rule.
 *
 * The protocol core's headers are included by name: in the sketch they sit beside this file
 * (`make sketch-ha` puts common/vn200 here), host builds link CMake's vn200_core. */
#ifndef HA_VN200_FEED_H
#define HA_VN200_FEED_H

#include <stddef.h>
#include <stdint.h>

#include "../core/ha_core.h"
#include "../core/ha_ins.h"
#include "../generated/ha_config.h"
#include "vn_binary.h"
#include "vn_framer.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  uint64_t bytes_read;
  uint32_t binary_packets; /* intact binary packets (CRC good) */
  uint32_t ascii_frames;   /* register responses: ignored */
  uint32_t decode_errors;  /* intact packets vn_bin_decode refused (incl. non-finite values) */
} HaVn200FeedCounts;

typedef struct {
  const HaAircraftConfig *cfg; /* NULL until ha_vn200_feed_init: bytes are then ignored */
  VnFramer framer;
  HaIns ins;            /* the INS adapter: home and the solutions used or rejected */
  VnBinaryData scratch; /* one decoded packet; some 200 bytes kept off the loop's stack */
  HaVn200FeedCounts counts;
} HaVn200Feed;

/* Resets the framer, the counts and the adapter (home not latched). cfg is the aircraft
 * configuration the adapter reads (stall speed, airborne altitude). */
void ha_vn200_feed_init(HaVn200Feed *feed, const HaAircraftConfig *cfg);

/* Frames, decodes and applies bytes received at now_us. Partial packets are kept for the next
 * call. A packet with a non-finite value makes the state invalid. ha_on_ground: the core's latest
 * verdict (HaOutputs.on_ground), on which alone home latches (ha_ins_update). */
void ha_vn200_feed_bytes(HaVn200Feed *feed, const uint8_t *bytes, size_t len, HaInputs *inputs,
                         uint8_t ha_on_ground, uint32_t now_us);

/* The copy from the VN-200 decoder's struct into the core's (units unchanged). */
void ha_vn200_sample_from_vn(const VnBinaryData *vn, HaInsSample *sample);

#ifdef __cplusplus
}
#endif

#endif /* HA_VN200_FEED_H */
