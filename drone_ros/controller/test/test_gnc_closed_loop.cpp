// Closed-loop tests of the GNC (for the build's aircraft) without ROS: the generated controller
// flies the nonlinear 6-DOF model built from the same airframe data (test/sim). Bands are stated
// with each test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>

#include "c_boundary.h"
#include "gnc_flight.h"

namespace {

using controller_test::all_finite;
using controller_test::Flight;
using controller_test::kPi;
using controller_test::kRadToDeg;

double segment_distance(double pn, double pe, const double *a, const double *b) {
  const double dn = b[0] - a[0], de = b[1] - a[1];
  const double len2 = dn * dn + de * de;
  const double t = std::clamp(((pn - a[0]) * dn + (pe - a[1]) * de) / len2, 0.0, 1.0);
  return std::hypot(pn - (a[0] + t * dn), pe - (a[1] + t * de));
}

// One waypoint far north at the trim height: straight and level flight for minutes.
constexpr double kFarNorthFt[1][3] = {{30000.0, 0.0, 200.0}};
// A 2000 ft square at 200 ft AGL (north, east, height ft).
constexpr double kSquareFt[4][3] = {
    {1000.0, 0.0, 200.0}, {1000.0, 2000.0, 200.0}, {-1000.0, 2000.0, 200.0}, {-1000.0, 0.0, 200.0}};

// The worst height and airspeed errors (from height_ft and the trim airspeed) from settle_s on,
// flying the plan until until_s, with a valid command all the while.
struct Bands {
  double worst_alt_ft = 0.0;
  double worst_vt_ftps = 0.0;
};

Bands fly_and_measure_bands(Flight *f, double until_s, double settle_s, double height_ft) {
  Bands b;
  const double trim_ftps = f->params().gnc.vt_trim_ftps;
  while (f->t() < until_s) {
    f->step();
    EXPECT_TRUE(all_finite(f->out())) << "at t=" << f->t();
    if (!all_finite(f->out())) {
      break;
    }
    if (f->t() > settle_s) {
      EXPECT_TRUE(f->out().command_valid) << "at t=" << f->t();
      b.worst_alt_ft = std::max(b.worst_alt_ft, std::fabs(f->sim().height_ft() - height_ft));
      b.worst_vt_ftps = std::max(b.worst_vt_ftps, std::fabs(f->sim().airspeed_ftps() - trim_ftps));
    }
  }
  testing::Test::RecordProperty("worst_altitude_error_ft", std::to_string(b.worst_alt_ft));
  testing::Test::RecordProperty("worst_airspeed_error_ftps", std::to_string(b.worst_vt_ftps));
  return b;
}

// The bands flying plan from trim at 200 ft in the sim cfg describes.
Bands bands_from_trim(const airframe_sim::SimConfig &cfg, const double (*plan)[3], int count,
                      double until_s, double settle_s) {
  Flight f({}, cfg);
  f.start_trimmed(200.0);
  f.set_plan(plan, count);
  return fly_and_measure_bands(&f, until_s, settle_s, 200.0);
}

// Altitude band +/-10 ft and airspeed band +/-2 ft/s, after 5 s, over 60 s of straight flight
// towards a far waypoint at the trim height, in a 3 m/s crosswind with sensor noise.
TEST(GncClosedLoop, FromTrimHoldsAltitudeAndAirspeedWithinBands) {
  airframe_sim::SimConfig cfg;
  cfg.wind_ned_mps = Eigen::Vector3d(0.0, 3.0, 0.0);
  const Bands b = bands_from_trim(cfg, kFarNorthFt, 1, 60.0, 5.0);
  EXPECT_LT(b.worst_alt_ft, 10.0);
  EXPECT_LT(b.worst_vt_ftps, 2.0);
}

// The real aircraft is not the design model: 15 % heavier (and its inertia), 25 % more drag,
// 20 % less control power. Flying the square from trim it still holds altitude within 15 ft and
// airspeed within 4 ft/s after the first 10 s.
TEST(GncClosedLoop, HoldsAltitudeAndAirspeedWithModelErrors) {
  airframe_sim::SimConfig cfg;
  cfg.mass_scale = 1.15;
  cfg.drag_scale = 1.25;
  cfg.control_power_scale = 0.8;
  cfg.wind_ned_mps = Eigen::Vector3d(0.0, 3.0, 0.0);
  const Bands b = bands_from_trim(cfg, kSquareFt, 4, 150.0, 10.0);
  EXPECT_LT(b.worst_alt_ft, 15.0);
  EXPECT_LT(b.worst_vt_ftps, 4.0);
}

// A 2000 ft square at 200 ft AGL in a 2.8 m/s wind: from reaching waypoint 0 on, through all
// four corners, the aircraft stays within 80 ft of the square's edges (RMS within 25 ft) and
// within 15 ft of its height through the 35 deg banked turns.
TEST(GncClosedLoop, FliesFourWaypointSquareWithinCrossTrackBand) {
  airframe_sim::SimConfig cfg;
  cfg.wind_ned_mps = Eigen::Vector3d(-2.0, 2.0, 0.0);
  Flight f({}, cfg);
  f.start_trimmed(200.0);
  const auto &square = kSquareFt;
  f.set_plan(square, 4);
  bool captured = false;
  int laps_wp = 0, last_index = 0;
  double worst_ft = 0.0, sum_sq = 0.0, worst_alt_ft = 0.0;
  long samples = 0;
  while (laps_wp < 5 && f.t() < 400.0) {
    f.step();
    ASSERT_TRUE(all_finite(f.out()));
    if (f.out().waypoint_index != last_index) {
      last_index = f.out().waypoint_index;
      ++laps_wp;
      captured = true;  // reached waypoint 0: on the square from here
    }
    if (captured) {
      double d = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 4; ++i) {
        d = std::min(d, segment_distance(f.sim().north_ft(), f.sim().east_ft(), square[i],
                                         square[(i + 1) % 4]));
      }
      worst_ft = std::max(worst_ft, d);
      worst_alt_ft = std::max(worst_alt_ft, std::fabs(f.sim().height_ft() - 200.0));
      sum_sq += d * d;
      ++samples;
    }
  }
  ASSERT_EQ(laps_wp, 5) << "did not fly the whole square in " << f.t() << " s";
  const double rms_ft = std::sqrt(sum_sq / samples);
  EXPECT_LT(worst_ft, 80.0);
  EXPECT_LT(rms_ft, 25.0);
  EXPECT_LT(worst_alt_ft, 15.0);
  RecordProperty("worst_altitude_error_ft", std::to_string(worst_alt_ft));
  // Flying all four headings makes the wind observable: estimated within 2 ft/s per axis.
  EXPECT_NEAR(f.out().wind_north_ftps, cfg.wind_ned_mps.x() / 0.3048, 2.0);
  EXPECT_NEAR(f.out().wind_east_ftps, cfg.wind_ned_mps.y() / 0.3048, 2.0);
  EXPECT_NEAR(f.out().wind_up_ftps, 0.0, 2.0);
  RecordProperty("worst_cross_track_ft", std::to_string(worst_ft));
  RecordProperty("rms_cross_track_ft", std::to_string(rms_ft));
}

// Return home (hmcmd): from 30 s on the aircraft circles home at mpf_radius within +/-30 ft and
// holds its height within +/-10 ft, in a 2.8 m/s wind.
TEST(GncClosedLoop, ReturnHomeCommandCirclesHomeAtTheMpfRadius) {
  airframe_sim::SimConfig cfg;
  cfg.wind_ned_mps = Eigen::Vector3d(-2.0, 2.0, 0.0);
  Flight f({}, cfg);
  f.start_trimmed(200.0);
  f.in().home_cmd = 1;
  const double radius_ft = f.params().gnc.mpf_radius_ft;
  double worst_radius_ft = 0.0, worst_alt_ft = 0.0;
  while (f.t() < 150.0) {
    f.step();
    ASSERT_TRUE(all_finite(f.out()));
    EXPECT_EQ(f.out().guidance_mode, GNC_MODE_CIRCLE_HOME);
    if (f.t() > 30.0) {
      const double r = std::hypot(f.sim().north_ft(), f.sim().east_ft());
      worst_radius_ft = std::max(worst_radius_ft, std::fabs(r - radius_ft));
      worst_alt_ft = std::max(worst_alt_ft, std::fabs(f.sim().height_ft() - 200.0));
    }
  }
  EXPECT_LT(worst_radius_ft, 30.0);
  EXPECT_LT(worst_alt_ft, 10.0);
}

// Releasing the return-home command resumes the flight plan where it was left.
TEST(GncClosedLoop, ReleasingReturnHomeResumesThePlan) {
  Flight f;
  f.start_trimmed(200.0);
  const double plan[2][3] = {{3000.0, 0.0, 200.0}, {3000.0, 3000.0, 200.0}};
  f.set_plan(plan, 2);
  f.in().home_cmd = 1;
  f.fly_until(20.0);
  EXPECT_EQ(f.out().guidance_mode, GNC_MODE_CIRCLE_HOME);
  f.in().home_cmd = 0;
  f.step();
  EXPECT_NE(f.out().guidance_mode, GNC_MODE_CIRCLE_HOME);
  EXPECT_EQ(f.out().waypoint_index, 0);
  f.fly_until(100.0);
  EXPECT_EQ(f.out().guidance_mode, GNC_MODE_FLIGHT_PLAN);
  EXPECT_LT(std::fabs(f.out().cross_track_ft), 30.0);
}

// path_select 1: after the last waypoint the aircraft circles home instead of starting over.
TEST(GncClosedLoop, PathSelectOneCirclesHomeAfterTheLastWaypoint) {
  Flight f({{"path_select", 1.0}});
  f.start_trimmed(200.0);
  const double plan[2][3] = {{800.0, 0.0, 200.0}, {800.0, 800.0, 220.0}};
  f.set_plan(plan, 2);
  bool circled = false;
  while (f.t() < 120.0 && !circled) {
    f.step();
    circled = f.out().guidance_mode == GNC_MODE_CIRCLE_HOME;
  }
  EXPECT_TRUE(circled);
  EXPECT_EQ(f.out().waypoint_index, 1);
  EXPECT_NEAR(f.sim().north_ft(), 800.0, 150.0);
  EXPECT_NEAR(f.sim().east_ft(), 800.0, 150.0);
  EXPECT_NEAR(f.out().h_op_ft, 220.0, 1e-9);  // circles at the last waypoint's height
}

// Started with alpha 10 deg and beta -8 deg off, the estimator reports not converged at first,
// then within 5 s reports converged with alpha and beta within 1 deg of the truth.
TEST(GncClosedLoop, EstimatorConvergesFromWrongInitialAlphaBeta) {
  airframe_sim::SimConfig cfg;
  cfg.wind_ned_mps = Eigen::Vector3d(2.0, -3.0, 0.0);
  Flight f({{"alpha", 10.0 / kRadToDeg}, {"beta", -8.0 / kRadToDeg}}, cfg);
  f.start_trimmed(200.0, 0.5);
  const double plan[1][3] = {{30000.0, 20000.0, 200.0}};
  f.set_plan(plan, 1);
  f.step();
  EXPECT_FALSE(f.out().estimator_converged);
  EXPECT_GT(std::fabs(f.out().alpha_est_rad - f.sim().alpha_rad()) * kRadToDeg, 5.0);
  f.fly_until(5.0);
  for (int i = 0; i < 100; ++i) {  // and it stays there
    f.step();
    EXPECT_TRUE(f.out().estimator_converged);
    EXPECT_NEAR(f.out().alpha_est_rad * kRadToDeg, f.sim().alpha_rad() * kRadToDeg, 1.0);
    EXPECT_NEAR(f.out().beta_est_rad * kRadToDeg, f.sim().beta_rad() * kRadToDeg, 1.0);
    EXPECT_NEAR(f.out().vt_est_ftps, f.sim().airspeed_ftps(), 2.0);
  }
}

// Waypoints come from the ground station and the HA judges position, both with WGS84 radii of
// curvature: the GNC must put a latitude/longitude at the same north/east. Reference: one
// degree at 45 deg latitude spans 111,132.95 m of latitude and 78,846.80 m of longitude (WGS84);
// a sphere of the equatorial radius would be 0.6 ft and 0.4 ft off over these 0.001 deg.
TEST(GncFrame, NorthAndEastFromLatLonUseTheWgs84RadiiAtHome) {
  Flight f;
  f.step();
  GncInput in = f.in();
  in.home_valid = 1;
  in.home_lat_deg = 45.0;
  in.home_lon_deg = 7.0;
  in.home_alt_m = 300.0;
  in.lat_deg = 45.001;
  in.lon_deg = 7.001;
  in.alt_m = 330.48;
  GncOutput out{};
  gnc_step(&in, &out);
  EXPECT_NEAR(111.13295 / 0.3048, out.north_ft, 0.05);
  EXPECT_NEAR(78.84680 / 0.3048, out.east_ft, 0.05);
  EXPECT_NEAR(100.0, out.height_ft, 1e-6);
}

// Standing on the ground the pitot reads zero: the thesis's EKF produced NaN here. The command
// stays finite and is flagged invalid, step after step.
TEST(GncClosedLoop, ZeroAirspeedOnTheGroundGivesFiniteCommandFlaggedInvalid) {
  Flight f;
  f.sim().set_on_ground();
  for (int i = 0; i < 400; ++i) {
    f.step();
    ASSERT_TRUE(all_finite(f.out())) << "step " << i;
    EXPECT_FALSE(f.out().command_valid);
    EXPECT_FALSE(f.out().estimator_converged);
    EXPECT_GE(f.out().throttle, f.params().gnc.throttle_min);
    EXPECT_LE(f.out().throttle, f.params().gnc.throttle_max);
  }
  EXPECT_NEAR(f.out().vt_est_ftps, 0.0, 3.0);
}

// A NaN, infinite or impossible value in any input is dropped and counted: the step returns the
// last finite command flagged invalid, and the GNC flies on normally with the next good input.
TEST(GncClosedLoop, NanInputGivesFiniteCommandFlaggedInvalidAndIsCounted) {
  Flight f;
  f.start_trimmed(200.0);
  f.set_plan(kFarNorthFt, 1);
  f.fly_until(3.0);
  ASSERT_TRUE(f.out().command_valid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // NaN, infinity, or a finite value no sensor can produce (a corrupted message).
  struct Corruption {
    double *field;
    double value;
  };
  const Corruption corruptions[] = {{&f.in().airspeed_ftps, nan},
                                    {&f.in().phi_rad, nan},
                                    {&f.in().lat_deg, std::numeric_limits<double>::infinity()},
                                    {&f.in().fz_mps2, nan},
                                    {&f.in().wp_height_ft[0], nan},
                                    {&f.in().airspeed_ftps, 1e12},
                                    {&f.in().q_radps, -1e9}};
  uint32_t expected_rejects = 0;
  for (const Corruption &c : corruptions) {
    double *field = c.field;
    f.sim().sense(f.in());
    const double saved = *field;
    *field = c.value;
    GncOutput out{};
    gnc_step(&f.in(), &out);
    ++expected_rejects;
    EXPECT_TRUE(all_finite(out));
    EXPECT_FALSE(out.command_valid);
    EXPECT_FALSE(out.inputs_finite);
    EXPECT_FALSE(out.estimator_converged);
    EXPECT_EQ(out.rejected_inputs, expected_rejects);
    *field = saved;
    f.step();
    EXPECT_TRUE(f.out().command_valid);
    EXPECT_TRUE(f.out().inputs_finite);
  }
}

// The HP restart: initialize() mid-flight starts the estimator again (not converged on its
// first step), and it converges and flies on from there.
TEST(GncClosedLoop, RestartMidFlightReinitializesAndRecovers) {
  Flight f;
  f.start_trimmed(200.0);
  f.set_plan(kFarNorthFt, 1);
  f.fly_until(3.0);
  ASSERT_TRUE(f.out().estimator_converged);
  ASSERT_EQ(gnc_initialize(&f.params().gnc), 0);
  f.step();
  EXPECT_FALSE(f.out().estimator_converged);
  f.fly_until(20.0);
  EXPECT_TRUE(f.out().command_valid);
  EXPECT_NEAR(f.sim().height_ft(), 200.0, 15.0);
}

// Bad parameters are refused: the GNC stays uninitialized and answers with a neutral command
// flagged invalid.
TEST(GncClosedLoop, InvalidParametersAreRefusedAndCommandStaysInvalid) {
  Flight f;
  GncParams bad = f.params().gnc;
  bad.mpf_radius_ft = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(gnc_initialize(&bad), -1);
  f.start_trimmed(200.0);
  f.step();
  EXPECT_FALSE(f.out().command_valid);
  EXPECT_TRUE(all_finite(f.out()));
}

// The entry points are callable from C99 (c_boundary.c): a terminated or unconfigured GNC
// answers with a finite neutral command flagged invalid, and refuses a NULL configuration.
TEST(GncClosedLoop, CBoundaryStepsATerminatedGncToANeutralInvalidCommand) {
  double throttle = -1.0;
  EXPECT_EQ(c_boundary_step_uninitialized(&throttle), 0);
  EXPECT_EQ(throttle, 0.0);
  EXPECT_EQ(c_boundary_initialize_null(), -1);
}

}  // namespace

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// The HP's side of a hand-back, PX4-style timeline: the HA flies its own command for 20 s,
// holding a 30 deg right bank, while the guidance wants a hard left turn towards a waypoint in
// the west. Handed back, the loops start from the 30 deg the HA hands over and reverse the bank
// at attitude_cmd_rate_deg_s: the aileron never reaches full travel and the roll rate stays
// inside the HA's switching region (switch_region_fraction x roll_rate_limit_deg_per_s). A 65 deg
// step of bank command, as before, is answered with full aileron (HiL: a tip stall and 148 deg/s,
// taken over by the HA).
double peak_after_hand_back(double attitude_cmd_rate_deg_s, double *peak_aileron_deg) {
  Flight f({{"attitude_cmd_rate_deg_s", attitude_cmd_rate_deg_s}});
  const double aileron_limit_rad = f.value("limits/actuators/aileron_limit_deg") / kRadToDeg;
  f.start_trimmed(200.0);
  const double west[1][3] = {{0.0, -30000.0, 200.0}};
  f.set_plan(west, 1);
  f.in().ha_in_control = 1;
  const double bank_rad = 30.0 / kRadToDeg;
  while (f.t() < 20.0) {  // the HA: bank and pitch holds of its own on the same sim
    f.sim().sense(f.in());
    GncOutput hp{};
    gnc_step(&f.in(), &hp);
    GncOutput ha = hp;
    ha.aileron_rad = std::clamp(0.8 * (bank_rad - f.sim().phi_rad()) - 0.15 * f.sim().p_radps(),
                                -aileron_limit_rad, aileron_limit_rad);
    ha.elevator_rad = f.params().elevator_trim_rad - 0.8 * (0.05 - f.sim().theta_rad());
    ha.rudder_rad = f.params().rudder_trim_rad;
    ha.throttle = 0.5;
    f.sim().advance(ha, f.dt());
    f.advance_clock();
  }
  f.in().ha_in_control = 0;
  double peak_p = 0.0;
  *peak_aileron_deg = 0.0;
  while (f.t() < 30.0) {
    f.step();
    EXPECT_TRUE(all_finite(f.out()));
    peak_p = std::max(peak_p, std::fabs(f.sim().p_radps()) * kRadToDeg);
    *peak_aileron_deg = std::max(*peak_aileron_deg, std::fabs(f.out().aileron_rad) * kRadToDeg);
  }
  return peak_p;
}

TEST(GncClosedLoop, AHandBackIntoTheOppositeBankReversesItWithoutAFullAileronSnap) {
  const auto limits = controller_test::aircraft_params(AIRCRAFT_DIR);
  const double aileron_limit_deg = limits.at("limits/actuators/aileron_limit_deg");
  const double switch_rate_deg_s = limits.at("limits/state/switch_region_fraction") *
                                   limits.at("limits/state/roll_rate_limit_deg_per_s");
  double aileron_deg = 0.0, step_aileron_deg = 0.0;
  const double p_deg_s = peak_after_hand_back(20.0, &aileron_deg);
  const double step_p_deg_s = peak_after_hand_back(360.0, &step_aileron_deg);
  RecordProperty("peak_roll_rate_deg_s", std::to_string(p_deg_s));
  RecordProperty("peak_aileron_deg", std::to_string(aileron_deg));
  EXPECT_GE(step_aileron_deg, aileron_limit_deg - 1e-6)
      << "the scenario no longer asks for a hard reversal";
  EXPECT_LT(aileron_deg, 0.6 * aileron_limit_deg);
  EXPECT_LT(p_deg_s, 0.6 * step_p_deg_s);
  EXPECT_LT(p_deg_s, switch_rate_deg_s);
  std::printf("hand-back: slewed peak p %.1f deg/s aileron %.1f deg; stepped %.1f deg/s %.1f deg\n",
              p_deg_s, aileron_deg, step_p_deg_s, step_aileron_deg);
}

namespace {

// Stall prevention (issue 22): the HA judges the stall by the load factor, so the HP may not bank
// further than its speed pays for. Asked to fly the slowest it may (a waypoint's speed of
// min_airspeed_cmd) towards a waypoint behind it, the HP banks no further than
// V^2 cos(bank) = min_airspeed_cmd^2 allows (never below stall_prevention_min_bank_deg), and asks
// for the airspeed a level turn at that bank needs. Returns the largest bank commanded.
// Before, it rolled to max_bank_deg (35) at once: at 52 ft/s that is 1.22 g, past the lift the
// HA's stall switch allows in moderate turbulence (HiL: the HP lost the servos for STALL).
double slow_turn_max_bank_deg(Flight *f) {
  f->sim().set_trimmed_flight(52.0, 200.0, 0.0);  // heading north
  const double behind[1][3] = {{-1500.0, 300.0, 200.0}};
  f->set_plan(behind, 1);
  f->in().wp_velocity_ftps[0] = f->params().gnc.min_airspeed_cmd_ftps;  // asked to fly slow
  const double min_ftps = f->params().gnc.min_airspeed_cmd_ftps;
  const double floor_deg = f->params().gnc.stall_prevention_min_bank_deg;
  double worst_excess_deg = -90.0, max_bank_deg = 0.0;
  int checked = 0;
  while (f->t() < 6.0) {
    f->step();
    EXPECT_TRUE(all_finite(f->out()));
    if (!f->out().estimator_converged) continue;
    const double v = f->out().vt_est_ftps;
    const double allowed_deg =
        std::max(floor_deg, std::acos(std::min(1.0, min_ftps * min_ftps / (v * v))) * kRadToDeg);
    const double bank_deg = std::fabs(f->out().phi_cmd_rad) * kRadToDeg;
    worst_excess_deg = std::max(worst_excess_deg, bank_deg - allowed_deg);
    max_bank_deg = std::max(max_bank_deg, bank_deg);
    EXPECT_GE(f->out().vt_cmd_ftps, min_ftps / std::sqrt(std::cos(f->out().phi_cmd_rad)) - 0.5)
        << "at t=" << f->t();
    ++checked;
  }
  EXPECT_GT(checked, 50);  // 20 Hz, once the estimator has converged
  EXPECT_LT(worst_excess_deg, 2.0) << "banked past what the speed pays for";
  return max_bank_deg;
}

}  // namespace

TEST(GncClosedLoop, SlowInATurnTheHpBanksOnlyAsFarAsItsSpeedPays) {
  Flight f;
  const double max_bank_deg = slow_turn_max_bank_deg(&f);
  EXPECT_GT(max_bank_deg, f.params().gnc.stall_prevention_min_bank_deg - 0.5)
      << "it must still turn";
  RecordProperty("max_bank_deg", std::to_string(max_bank_deg));
}

// The floor is controller_param.yaml's, not a literal: raised to 20 deg, the slow HP turns at 20.
TEST(GncClosedLoop, StallPreventionsBankFloorIsTheAircraftsParameter) {
  Flight f({{"stall_prevention_min_bank_deg", 20.0}});
  ASSERT_DOUBLE_EQ(f.params().gnc.stall_prevention_min_bank_deg, 20.0);
  EXPECT_GT(slow_turn_max_bank_deg(&f), 19.5);
}

namespace {

// The elevator the GNC commands over 2 s in a 30 deg dive at the trim airspeed (the INS's
// attitude and velocity overwritten on the trimmed sim's): the loops ask for a hard pull-out.
double most_nose_up_in_a_dive_deg(Flight *f) {
  f->start_trimmed(200.0);
  f->set_plan(kFarNorthFt, 1);
  f->fly_until(3.0);
  const double dive_rad = -30.0 / kRadToDeg;
  const double v_mps = f->params().gnc.vt_trim_ftps * 0.3048;
  double most_nose_up_deg = 0.0;
  for (int i = 0; i < 200; ++i) {
    f->sim().sense(f->in());
    f->in().theta_rad = dive_rad;
    f->in().vel_north_mps = v_mps * std::cos(dive_rad);
    f->in().vel_down_mps = -v_mps * std::sin(dive_rad);
    GncOutput out{};
    gnc_step(&f->in(), &out);
    most_nose_up_deg = std::max(most_nose_up_deg, -out.elevator_rad * kRadToDeg);
  }
  return most_nose_up_deg;
}

}  // namespace

// Issue 22: the HA refuses, airborne, an elevator more nose-up than elevator_pull_limit_deg
// (REASON_PULL: 7 deg trims the wing at 1.5 x its stall). The HP's loops saturate their pull
// there, so a healthy HP pulling out of a dive is never taken over for it; they saturated at
// elevator_limit_deg (20 deg).
TEST(GncLimits, PullingOutOfADiveStopsAtTheHasPullLimit) {
  Flight f;
  const double pull_limit_deg = f.value("limits/actuators/elevator_pull_limit_deg");
  const double most_deg = most_nose_up_in_a_dive_deg(&f);
  std::printf("30 deg dive: most nose-up elevator %.2f deg (pull limit %.1f)\n", most_deg,
              pull_limit_deg);
  EXPECT_LE(most_deg, pull_limit_deg + 1e-9);
  EXPECT_GE(most_deg, pull_limit_deg - 1e-9) << "the dive did not ask for the limit";
}

// A pull limit past the elevator's own travel is a typo in limits.yaml: the controller refuses
// to start, naming the key.
TEST(GncLimits, PullLimitPastTheElevatorsTravelIsRefused) {
  controller::ControllerParams p{};
  std::string error;
  auto values = controller_test::aircraft_params(AIRCRAFT_DIR, {});
  values["limits/actuators/elevator_pull_limit_deg"] =
      values["limits/actuators/elevator_limit_deg"] + 1.0;
  EXPECT_FALSE(controller::build_controller_params(controller_test::lookup_in(values), &p, &error));
  EXPECT_NE(error.find("elevator_pull_limit_deg"), std::string::npos) << error;
}
