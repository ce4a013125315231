/* Plain value types shared by the HA core, the Board interface and the link. C99, no heap. */
#ifndef HA_TYPES_H
#define HA_TYPES_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* What goes to (or comes from) the four actuators, in physical units. */
typedef struct {
  float throttle;     /* [0..1] fraction of full power */
  float elevator_deg; /* trailing edge down positive */
  float aileron_deg;  /* roll right positive */
  float rudder_deg;   /* yaw left positive */
} HaSurfaces;

/* RC receiver channels as captured pulse widths. The PIC/CIC channel selects who flies:
 * pulse at or above the configured threshold = pilot in command (manual). */
enum {
  HA_RC_THROTTLE = 0,
  HA_RC_ELEVATOR = 1,
  HA_RC_AILERON = 2,
  HA_RC_RUDDER = 3,
  HA_RC_PIC = 4,
  HA_RC_CHANNELS = 5
};

typedef struct {
  uint16_t pulse_us[HA_RC_CHANNELS];
  /* 1 when every channel was captured recently (receiver alive); 0 means RC lost, and then the
   * PIC switch cannot be read and manual mode is not entered. */
  uint8_t valid;
} HaRcInputs;

#ifdef __cplusplus
}
#endif

#endif /* HA_TYPES_H */
