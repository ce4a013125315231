// Waypoint guidance over the /way flight plan: moving-point (L1) path following on each leg,
// direct-to-waypoint when far off track, circling home at the end of the plan or on command.
// Local frame: North-East-Up from home, ft, as /way is.
#ifndef GNC_GUIDANCE_H
#define GNC_GUIDANCE_H

#include <cstdint>

#include "gnc.h"

namespace gnc {

struct GuidanceState {
  double north_ft, east_ft, height_ft;
  double vel_north_ftps, vel_east_ftps;
  double psi_rad;
};

struct GuidanceCommand {
  int32_t mode = GNC_MODE_CIRCLE_HOME;
  int32_t waypoint_index = 0;
  double dist_to_waypoint_ft = 0.0;
  double cross_track_ft = 0.0;
  double vt_cmd_ftps = 0.0;
  double phi_cmd_rad = 0.0;
  double theta_cmd_rad = 0.0;
  double eta_lat_rad = 0.0;
  double eta_lon_rad = 0.0;
  double delta_psi_rad = 0.0;
  double n_op_ft = 0.0, e_op_ft = 0.0, h_op_ft = 0.0;
};

class Guidance {
 public:
  void reset(const GncParams &params, double theta_trim_rad);
  // integrate: false while the command is not flown (holds the altitude integrator).
  GuidanceCommand step(const GncInput &in, const GuidanceState &s, bool integrate);

 private:
  // The waypoint after index, or -1 when the plan ends there (path_select 1).
  int32_t next_index(int32_t index, int32_t count) const;
  void start_leg(const GncInput &in, const GuidanceState &s, int32_t index, bool from_here);
  // The steps of step(), in its order.
  void advance_plan(const GncInput &in, const GuidanceState &s, int32_t count, GuidanceCommand &c);
  void follow_leg(const GncInput &in, const GuidanceState &s, int32_t count, GuidanceCommand &c);
  void circle_home(const GuidanceState &s, GuidanceCommand &c);
  void altitude_cmd(const GuidanceState &s, bool integrate, GuidanceCommand &c);
  double lateral_accel_cmd(const GuidanceState &s, double n_op, double e_op,
                           GuidanceCommand &c) const;

  GncParams params_{};
  double theta_trim_rad_ = 0.0;
  bool have_plan_ = false;
  uint32_t plan_revision_ = 0;
  int32_t index_ = 0;
  bool plan_done_ = false;  // path_select 1 reached the last waypoint
  bool circling_ = false;   // circled last step (the circle height is captured on entry)
  double circle_height_ft_ = 0.0;
  double leg_start_n_ft_ = 0.0, leg_start_e_ft_ = 0.0, leg_start_h_ft_ = 0.0;
  double alt_integral_ft_s_ = 0.0;
};

}  // namespace gnc

#endif
