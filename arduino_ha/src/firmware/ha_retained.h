/* What the HA keeps across a reset of its own (watchdog, brown-out of the core supply, software):
 * a few words of memory the board retains (ha_board.h, read_retained / write_retained; on the
 * Due the SAM3X's general-purpose backup registers), lost only when the power goes. Without them
 * a reset in flight would wake the HA on the ground: no home (home latches only on the ground),
 * so every solution refused, the healthy HP locked out and the airborne latch clear.
 *
 * The record: home (where, and its sequence number, so the link republishes the same home), the
 * airborne latch, the restart cap's latch and the operator's HA selection, with a magic, a
 * version and a CRC-32 over the rest: anything else (a power-up's random bits, an old layout)
 * is no record, and the HA starts as from power-up. Pure C99, no board access. */
#ifndef HA_RETAINED_H
#define HA_RETAINED_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The SAM3X8E has 8 general-purpose backup registers of 32 bits. */
#define HA_RETAINED_WORDS 8u

typedef struct {
  uint8_t airborne;        /* the core's airborne latch */
  uint8_t restart_latched; /* the restart cap was reached: HA for good */
  uint8_t ground_command;  /* the operator selected the HA */
  uint8_t home_latched;
  double home_lat_deg, home_lon_deg, home_alt_m; /* valid when home_latched */
  uint32_t home_seq;
} HaRetained;

/* Fills words[] with r, its magic and version, and the CRC of both. Home is kept in integers
 * (latitude and longitude in 1e-7 deg, 1.1 cm; height in mm), so no bit pattern read back can be
 * a NaN: it comes back within 0.6 cm of where it was. */
void ha_retained_pack(const HaRetained *r, uint32_t words[HA_RETAINED_WORDS]);

/* Returns 1 and fills *r when words[] hold a record of this version with a good CRC; else 0 and
 * *r is all zero (no home, on the ground). The values still need their range checks (home:
 * ha_ins_restore_home). */
int ha_retained_unpack(const uint32_t words[HA_RETAINED_WORDS], HaRetained *r);

#ifdef __cplusplus
}
#endif

#endif /* HA_RETAINED_H */
