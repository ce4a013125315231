/* Binds the aircraft-neutral names controller nodes use to this aircraft's generated entry
 * points. A lab's own controller for aircraft <name> provides the same names. */
#ifndef GNC_BINDING_H
#define GNC_BINDING_H

#include "dg808_gnc.h"
#include "dg808_gnc_data.h"

#define GNC_AIRCRAFT_NAME "DG808"
#define GNC_MAX_WAYPOINTS DG808_GNC_MAX_WAYPOINTS
#define GNC_PREVIEW_WAYPOINTS DG808_GNC_PREVIEW_WAYPOINTS
#define GNC_DESIGN_Q_WEIGHT DG808_DESIGN_Q_WEIGHT
typedef DG808_GNC_Params GncParams;
typedef DG808_GNC_Input GncInput;
typedef DG808_GNC_Output GncOutput;
#define gnc_initialize DG808_GNC_initialize
#define gnc_step DG808_GNC_step
#define gnc_terminate DG808_GNC_terminate

#endif
