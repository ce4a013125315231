/* The HA's own airspeed picture: what the pitot says, whether the INS agrees, and what the INS
 * says when it does not. The pitot reads indicated airspeed (IAS: the stall speed is one); the
 * INS sees the velocity over the ground, the true airspeed (TAS) plus the wind. A wind learnt
 * slowly from a believed pitot (bounded by max_wind_ftps) ties the two together, so the pitot is
 * judged from both sides (reading low: blocked, zeroed; reading high: stuck, iced) and, judged
 * wrong, replaced by the INS less the wind. An angle of attack from the INS (pitch less flight
 * path) and the bank's load factor let the stall check see an accelerated or a high-alpha stall
 * that the 1 g stall speed misses. */
#ifndef HA_AIRDATA_H
#define HA_AIRDATA_H

#include <stdint.h>

#include "ha_checks.h"
#include "ha_core.h"

/* Sea level, no wind known. */
void ha_airdata_init(HaAirdata *a);

/* Once per period, before the pitot's reading is used: returns 0 when the INS (fresh, its
 * velocity plausible) disagrees with the reading (read: inside [0, max_airspeed_ftps]; ias_ftps
 * is it clamped there), 1 otherwise. Also keeps the heading's unit vector, the INS's velocity and
 * the density for the period; learns the wind from a believed reading above stall speed, and
 * forgets that it knows it once the pitot has been doubted for wind_forget_us. */
int ha_airdata_track(HaAirdata *a, const HaAircraftConfig *cfg, const HaInputs *in, int ins_fresh,
                     int read, float ias_ftps, uint32_t dt_us);

/* The picture into the view, after ha_state_view: the speed from the believed pitot if there is
 * one, else from the INS less the wind (once known); what the angle of attack needs (the INS's
 * climb, alpha_ok); the bank's cosine; the heading's unit vector. */
void ha_airdata_view(const HaAirdata *a, const HaAircraftConfig *cfg, HaStateView *v);

#endif /* HA_AIRDATA_H */
