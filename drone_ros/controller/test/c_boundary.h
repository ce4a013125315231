#ifndef CONTROLLER_C_BOUNDARY_H
#define CONTROLLER_C_BOUNDARY_H

#ifdef __cplusplus
extern "C" {
#endif

/* Steps a terminated GNC from C: returns command_valid, writes the throttle. */
int c_boundary_step_uninitialized(double *throttle_out);
/* gnc_initialize(NULL) from C. */
int c_boundary_initialize_null(void);

#ifdef __cplusplus
}
#endif

#endif
