/* The control channel's records (ha_sil_channel.h) as bytes: fixed little-endian layouts whatever
 * the compiler's padding, so the host SIL (ha_sil.c, on its unix socket) and the QEMU board
 * (arduino_ha/pil/, on its third UART) put and take exactly the bytes hil/ha_channel.py packs.
 * C99, no heap; builds for the host and for the Cortex-M3. */
#ifndef HA_SIL_RECORDS_H
#define HA_SIL_RECORDS_H

#include <stddef.h>
#include <stdint.h>

#include "../firmware/ha_firmware.h"
#include "ha_sil_channel.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HA_SIL_STEP_RECORD_LEN 52u
#define HA_SIL_REPLY_RECORD_LEN 100u

/* Takes a step, poll or reset record of exactly HA_SIL_STEP_RECORD_LEN bytes; returns 1 when its
 * length, magic and version are one of those, else 0 (and *st is not to be used). */
int ha_sil_decode_step(const uint8_t *bytes, size_t len, HaSilStep *st);

/* What the board itself counts, beside what the firmware holds. */
typedef struct {
  uint16_t flags;    /* HA_SIL_R_* the board decided (stepped, timeouts) */
  uint64_t t_us;     /* the period's clock */
  uint32_t commands; /* HP commands the link delivered since the start */
  uint64_t vn_bytes; /* VN-200 bytes taken since the start */
  int hp_reset;      /* the HP reset line as the board drives it */
  uint32_t wait_us;  /* wall time the period waited for its inputs */
} HaSilReplyBoard;

/* The reply record of the firmware's latest period (HA_SIL_REPLY_RECORD_LEN bytes into out). */
void ha_sil_encode_reply(const HaFirmware *fw, const HaSilReplyBoard *board,
                         uint8_t out[HA_SIL_REPLY_RECORD_LEN]);

/* Little-endian field access, for a board that frames the records further. */
void ha_sil_put_u32(uint8_t *b, size_t *at, uint32_t v);
uint32_t ha_sil_get_u32(const uint8_t *b, size_t *at);

#ifdef __cplusplus
}
#endif

#endif /* HA_SIL_RECORDS_H */
