/* Compiled as C99: proves the GNC's entry points and structs are a C boundary a generated
 * controller (Simulink Coder, a lab's own) can sit behind. */
#include "c_boundary.h"

#include <string.h>

#include "gnc.h"

int c_boundary_step_uninitialized(double *throttle_out) {
  GncInput in;
  GncOutput out;
  memset(&in, 0, sizeof(in));
  memset(&out, 0, sizeof(out));
  gnc_terminate();
  gnc_step(&in, &out);
  *throttle_out = out.throttle;
  return out.command_valid;
}

int c_boundary_initialize_null(void) { return gnc_initialize(NULL); }
