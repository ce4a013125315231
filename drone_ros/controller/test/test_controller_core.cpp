// The node's ROS-free parts: parameter validation, sensor bookkeeping and the command it puts
// on the wire (sequence, CRC, health flags, never a NaN).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "command_builder.h"
#include "controller_params.h"
#include "home_vectors.h"
#include "hp_command.h"
#include "lockstep_gate.h"
#include "packet_pacer.h"
#include "param_tree.h"
#include "sensor_board.h"
#include "servo_command_as_ha.h"
#include "tunables_table.h"
#include "yaml_lookup.h"

namespace {

controller::ControllerParams aircraft(const std::map<std::string, double> &overrides = {}) {
  const auto values = controller_test::aircraft_params(AIRCRAFT_DIR, overrides);
  controller::ControllerParams p;
  std::string error;
  EXPECT_TRUE(controller::build_controller_params(controller_test::lookup_in(values), &p, &error))
      << error;
  return p;
}

std::string refusal(const std::map<std::string, double> &overrides,
                    const std::string &remove = "") {
  auto values = controller_test::aircraft_params(AIRCRAFT_DIR, overrides);
  if (!remove.empty()) {
    values.erase(remove);
  }
  controller::ControllerParams p;
  std::string error;
  EXPECT_FALSE(controller::build_controller_params(controller_test::lookup_in(values), &p, &error));
  return error;
}

void feed_all(controller::SensorBoard &board, double now_s, uint8_t piccic = 1) {
  drone_ros::pwm pwm;
  pwm.PICCIC = piccic;
  pwm.Throttle = 0.4;
  pwm.Elevator = 0.02;
  pwm.Aileron = -0.01;
  pwm.Rudder = 0.005;
  pwm.velocity = 60.0;
  pwm.usbstatus = 1;
  board.on_pwm(pwm, now_s);
  drone_ros::ins ins;
  ins.usbstatus = 1;
  board.on_ins(ins, now_s);
  sensor_msgs::NavSatFix fix;
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  fix.latitude = 40.0;
  fix.longitude = -83.0;
  fix.altitude = 250.0;
  board.on_gps_position(fix, now_s);
  board.on_gps_velocity(geometry_msgs::Twist(), now_s);
  board.on_imu(sensor_msgs::Imu(), now_s);
  board.on_attitude(geometry_msgs::Point(), now_s);
  board.on_home(40.0, -83.0, 250.0);  // the HA's home, from /home
}

TEST(ControllerParams, AircraftFilesAreAcceptedAndRateFollowsDt) {
  const auto p = aircraft();
  EXPECT_DOUBLE_EQ(p.rate_hz, 1.0 / p.gnc.dt_s);
  EXPECT_DOUBLE_EQ(aircraft({{"dt", 0.01}}).rate_hz, 100.0);
}

TEST(ControllerParams, OutOfRangeOrMissingValuesAreRefusedByName) {
  EXPECT_NE(refusal({{"dt", 0.005}}).find("dt"), std::string::npos);
  EXPECT_NE(refusal({{"mpf_radius", std::numeric_limits<double>::quiet_NaN()}}).find("mpf_radius"),
            std::string::npos);
  EXPECT_NE(refusal({{"path_select", 0.5}}).find("path_select"), std::string::npos);
  EXPECT_NE(refusal({}, "limits/state/stall_speed_ftps").find("stall_speed_ftps"),
            std::string::npos);
  EXPECT_NE(refusal({{"Q_weight", 2.0}}).find("design_gains.py"), std::string::npos);
  EXPECT_NE(refusal({{"max_bank_deg", 70.0}}).find("max_bank_deg"), std::string::npos);
}

// The node fetches its namespace once, as the master returns it: a struct of structs.
XmlRpc::XmlRpcValue as_master_tree(const std::map<std::string, double> &flat) {
  XmlRpc::XmlRpcValue tree;
  for (const auto &kv : flat) {
    XmlRpc::XmlRpcValue *node = &tree;
    std::string rest = kv.first;
    for (std::string::size_type slash; (slash = rest.find('/')) != std::string::npos;) {
      node = &(*node)[rest.substr(0, slash)];
      rest = rest.substr(slash + 1);
    }
    (*node)[rest] = kv.second;
  }
  return tree;
}

TEST(ParamTree, TheNamespaceFetchedWholeGivesEachValueItsKeyGaveOneByOne) {
  const auto flat = controller_test::aircraft_params(AIRCRAFT_DIR);
  XmlRpc::XmlRpcValue tree = as_master_tree(flat);
  for (const auto &kv : flat) {
    double v = -1.0;
    ASSERT_TRUE(controller::number_at(tree, kv.first, &v)) << kv.first;
    EXPECT_EQ(v, kv.second) << kv.first;
  }
  controller::ControllerParams p;
  std::string error;
  ASSERT_TRUE(controller::build_controller_params(
      [&tree](const std::string &k, double *v) { return controller::number_at(tree, k, v); }, &p,
      &error, nullptr))
      << error;
  EXPECT_DOUBLE_EQ(p.rate_hz, aircraft().rate_hz);
}

TEST(ParamTree, IntsAndBoolsAreNumbersAndOtherLeavesAreNot) {
  XmlRpc::XmlRpcValue tree;
  tree["hmcmd"] = 3;
  tree["limits"]["decision"]["latch"] = true;
  tree["frame_id"] = std::string("DG808");
  double v = 0.0;
  EXPECT_TRUE(controller::number_at(tree, "hmcmd", &v));
  EXPECT_EQ(v, 3.0);
  EXPECT_TRUE(controller::number_at(tree, "limits/decision/latch", &v));
  EXPECT_EQ(v, 1.0);
  EXPECT_FALSE(controller::number_at(tree, "frame_id", &v));
  EXPECT_FALSE(controller::number_at(tree, "limits/decision", &v));  // a struct, not a number
}

// A typo'd or absent key is refused by name (build_controller_params), never read as 0, and the
// lookup leaves the tree as it was (XmlRpcValue's operator[] would add the member).
TEST(ParamTree, AMissingKeyIsMissingAndStaysOutOfTheTree) {
  XmlRpc::XmlRpcValue tree;
  tree["limits"]["state"]["stall_speed_ftps"] = 40.0;
  double v = 0.0;
  for (const char *key : {"dt", "limits/state/ceiling_ft", "limits/stat/stall_speed_ftps",
                          "limits/state/stall_speed_ftps/x", "/limits/state/stall_speed_ftps",
                          "limits//state/stall_speed_ftps", ""}) {
    EXPECT_FALSE(controller::number_at(tree, key, &v)) << key;
  }
  EXPECT_FALSE(tree.hasMember("dt"));
  EXPECT_FALSE(tree["limits"].hasMember("stat"));
  EXPECT_EQ(tree["limits"]["state"].size(), 1);
  XmlRpc::XmlRpcValue nothing;  // the master had no namespace: every value is missing
  EXPECT_FALSE(controller::number_at(nothing, "dt", &v));
}

// controller_param.yaml's dt was the thesis's 20 Hz while the HA decides at 100 Hz: the HA found
// four periods in five without a new command, took over at every hand-back for DEADLINE_MISS and
// latched after its restart cap, and the HP never flew (real time, 2026-12-06).
TEST(ControllerParams, AControllerSlowerThanTheHaIsRefusedBeforeItFlies) {
  const std::string why = refusal({{"dt", 0.05}});
  EXPECT_NE(why.find("dt = 0.05 s is longer than the HA's period"), std::string::npos) << why;
  EXPECT_NE(why.find("decision.rate_hz = 100 Hz"), std::string::npos) << why;
  EXPECT_DOUBLE_EQ(aircraft({{"dt", 0.05}, {"limits/decision/rate_hz", 20.0}}).rate_hz, 20.0);
  EXPECT_DOUBLE_EQ(aircraft({{"dt", 0.02}, {"limits/decision/rate_hz", 50.0}}).rate_hz, 50.0);
  EXPECT_FALSE(refusal({{"dt", 0.02}, {"limits/decision/rate_hz", 51.0}}).empty());
}

// The set in force after loading the aircraft's files, as the node holds it.
struct InForce {
  controller::ControllerParams params;
  controller::ParamValues values;
  InForce() {
    const auto files = controller_test::aircraft_params(AIRCRAFT_DIR);
    std::string error;
    EXPECT_TRUE(controller::build_controller_params(controller_test::lookup_in(files), &params,
                                                    &error, &values))
        << error;
  }
  controller::TunableResult set(const std::string &name, double value, bool hp_in_command = false) {
    return controller::change_tunable(values, name, value, hp_in_command, &params, &values);
  }
};

TEST(Tunables, ValidGainFromTheGroundIsInForceAndReInitializesTheGnc) {
  InForce f;
  const auto r = f.set("mpf_radius", 300.0);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_TRUE(r.changed);
  EXPECT_TRUE(r.restart_gnc);
  EXPECT_DOUBLE_EQ(r.value_in_force, 300.0);
  EXPECT_DOUBLE_EQ(f.params.gnc.mpf_radius_ft, 300.0);
  EXPECT_DOUBLE_EQ(f.values.at("mpf_radius"), 300.0);
}

TEST(Tunables, OutOfRangeValueIsRefusedWithTheFileCheckAndTheOldSetStays) {
  InForce f;
  const double before = f.params.gnc.mpf_radius_ft;
  const auto r = f.set("mpf_radius", -5.0);
  EXPECT_FALSE(r.accepted);
  EXPECT_DOUBLE_EQ(r.value_in_force, before);
  EXPECT_NE(r.reason.find("mpf_radius = -5 is outside"), std::string::npos) << r.reason;
  EXPECT_DOUBLE_EQ(f.params.gnc.mpf_radius_ft, before);
  EXPECT_DOUBLE_EQ(f.values.at("mpf_radius"), before);
  // Cross-checks hold too: the commanded airspeed may not drop to the stall speed.
  EXPECT_FALSE(f.set("min_airspeed_cmd_ftps", 40.0).accepted);
  EXPECT_FALSE(f.set("path_select", 0.5).accepted);
  EXPECT_FALSE(f.set("KpLon", std::numeric_limits<double>::quiet_NaN()).accepted);
}

TEST(Tunables, RateAndLqrWeightAreFixedWhileRunningAndSaySo) {
  InForce f;
  auto r = f.set("dt", 0.02);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("launch"), std::string::npos) << r.reason;
  EXPECT_DOUBLE_EQ(f.params.gnc.dt_s, 0.01);
  r = f.set("Q_weight", 99.0);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("LQR"), std::string::npos) << r.reason;
  EXPECT_TRUE(f.set("dt", 0.01).accepted);  // the value in force again: a GCS repeating itself
}

TEST(Tunables, LimitsAndCommandsAreNotTunables) {
  InForce f;
  auto r = f.set("limits/state/stall_speed_ftps", 30.0);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("not a tunable"), std::string::npos);
  EXPECT_FALSE(f.set("hmcmd", 1.0).accepted);
  EXPECT_FALSE(f.set("gamma_flag", 1.0).accepted);  // a thesis name today's controller does not use
}

TEST(Tunables, GncChangeWaitsForTheHaToFlyButATrimGoesLive) {
  InForce f;
  auto r = f.set("KpLon", 0.005, /*hp_in_command=*/true);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.reason.find("select the HA"), std::string::npos) << r.reason;
  r = f.set("elevator_trim", 0.01, /*hp_in_command=*/true);
  EXPECT_TRUE(r.accepted) << r.reason;
  EXPECT_FALSE(r.restart_gnc);
  controller::SensorBoard board(InForce().params);
  feed_all(board, 1.0, /*piccic=*/1);  // the computer flies: RC positions are not trims
  board.apply_params(f.params);
  EXPECT_DOUBLE_EQ(board.elevator_trim_rad(), 0.01);
  EXPECT_DOUBLE_EQ(board.throttle_trim(), f.params.throttle_trim);  // untouched
}

TEST(Tunables, EachIsRefusedJustPastItsRangeInTunablesYamlNamingTheUnits) {
  for (const tunables::Tunable &t : tunables::kTunables) {
    const double step = t.is_integer ? 1.0 : (t.max - t.min) * 1e-3;
    for (const double outside : {t.min - step, t.max + step}) {
      const auto files = controller_test::aircraft_params(AIRCRAFT_DIR, {{t.name, outside}});
      controller::ControllerParams p;
      std::string error;
      EXPECT_FALSE(
          controller::build_controller_params(controller_test::lookup_in(files), &p, &error))
          << t.name << " = " << outside;
      EXPECT_EQ(error.find(std::string(t.name) + " = "), 0u) << error;
      EXPECT_NE(error.find(" is outside ["), std::string::npos) << error;
      if (std::string(t.units) != "1") {
        EXPECT_EQ(error.substr(error.size() - std::strlen(t.units) - 1), std::string(" ") + t.units)
            << error;
      }
    }
  }
}

TEST(Tunables, ARangeIsNarrowedWhereAnotherValueBoundsIt) {
  InForce f;
  // tunables.yaml lets the bank reach 89 deg; limits.yaml's roll limit is the tighter bound.
  const double roll_limit_deg = f.values.at("limits/state/roll_limit_deg");
  const auto r = f.set("max_bank_deg", roll_limit_deg + 1.0);
  EXPECT_FALSE(r.accepted);
  std::ostringstream want;
  want << "max_bank_deg = " << roll_limit_deg + 1.0 << " is outside [1, " << roll_limit_deg
       << "] deg";
  EXPECT_EQ(r.reason, want.str());
}

TEST(Tunables, EveryTunableIsAValueTheControllerReads) {
  InForce f;
  for (const char *name : {"dt",
                           "Q_weight",
                           "throttle_trim",
                           "elevator_trim",
                           "aileron_trim",
                           "rudder_trim",
                           "sensor_timeout_s",
                           "VTtrim",
                           "alpha",
                           "beta",
                           "guidance_selection",
                           "mpf_switch",
                           "mpf_radius",
                           "path_select",
                           "max_allow_error",
                           "dist2b",
                           "KpLon",
                           "KiLon",
                           "max_bank_deg",
                           "max_pitch_cmd_deg",
                           "attitude_cmd_rate_deg_s",
                           "min_airspeed_cmd_ftps",
                           "airspeed_valid_min_ftps",
                           "converged_sigma_deg"}) {
    EXPECT_NE(controller::tunable_kind(name), controller::TunableKind::kNone) << name;
    EXPECT_TRUE(f.set(name, f.values.at(name)).accepted) << name;
  }
}

TEST(SensorBoard, MissingSensorsAreReportedUnhealthyUntilTheyArrive) {
  controller::SensorBoard board(aircraft());
  EXPECT_EQ(board.unhealthy_links(0.0), (1u << controller::kLinkCount) - 1);
  feed_all(board, 10.0);
  EXPECT_EQ(board.unhealthy_links(10.1), 0u);
}

TEST(SensorBoard, StaleAttitudeMakesTheLinksUnhealthy) {
  const auto p = aircraft();
  controller::SensorBoard board(p);
  feed_all(board, 10.0);
  const double later = 10.0 + p.sensor_timeout_s + 0.01;
  feed_all(board, later);
  board.on_attitude(geometry_msgs::Point(), 10.0);  // the attitude's last arrival is old
  EXPECT_EQ(board.unhealthy_links(later), 1u << controller::kLinkAttitude);
}

TEST(SensorBoard, LinkReportedDownByItsNodeIsUnhealthyEvenWhenFresh) {
  controller::SensorBoard board(aircraft());
  feed_all(board, 1.0);
  drone_ros::ins ins;
  ins.usbstatus = 0;
  board.on_ins(ins, 1.0);
  EXPECT_EQ(board.unhealthy_links(1.0), 1u << controller::kLinkIns);
}

TEST(SensorBoard, NanMessagesAreCountedAndDropped) {
  controller::SensorBoard board(aircraft());
  feed_all(board, 1.0);
  geometry_msgs::Point bad;
  bad.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(board.on_attitude(bad, 2.0));
  EXPECT_EQ(board.dropped_messages(), 1u);
  GncInput in{};
  board.fill_input(&in);
  EXPECT_TRUE(std::isfinite(in.phi_rad));
  drone_ros::way plan;
  plan.fp = 33;
  EXPECT_FALSE(board.on_way(plan));
  EXPECT_EQ(board.dropped_waypoint_plans(), 1u);
}

TEST(SensorBoard, PilotInCommandCapturesRcTrimsAndComputerKeepsThem) {
  const auto p = aircraft();
  controller::SensorBoard board(p);
  EXPECT_DOUBLE_EQ(board.elevator_trim_rad(), p.elevator_trim_rad);
  feed_all(board, 1.0, 0);  // pilot flying with elevator 0.02 rad
  EXPECT_DOUBLE_EQ(board.elevator_trim_rad(), 0.02);
  EXPECT_DOUBLE_EQ(board.throttle_trim(), 0.4);
  drone_ros::pwm cic;
  cic.PICCIC = 1;
  cic.Elevator = -0.1;  // computer in command: RC no longer moves the trims
  cic.usbstatus = 1;
  board.on_pwm(cic, 2.0);
  EXPECT_DOUBLE_EQ(board.elevator_trim_rad(), 0.02);
  GncInput in{};
  board.fill_input(&in);
  EXPECT_DOUBLE_EQ(in.elevator_trim_rad, 0.02);
  EXPECT_EQ(in.home_valid, 1);
}

TEST(SensorBoard, HomeComesFromItsOwnerNeverFromTheFirstFix) {
  const auto p = aircraft();
  controller::SensorBoard board(p);
  sensor_msgs::NavSatFix fix;
  fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
  fix.latitude = 41.0;
  fix.longitude = -84.0;
  fix.altitude = 300.0;
  board.on_gps_position(fix, 1.0);
  EXPECT_FALSE(board.home_valid());  // a fix is where the aircraft is, not home
  ASSERT_TRUE(board.on_home(40.0, -83.0, 250.0));
  EXPECT_TRUE(board.home_valid());
  EXPECT_DOUBLE_EQ(board.home().lat_deg, 40.0);
  board.on_gps_position(fix, 2.0);
  EXPECT_DOUBLE_EQ(board.home().lat_deg, 40.0);
  // A SET_HOME the HA accepted on the ground moves it.
  ASSERT_TRUE(board.on_home(40.001, -83.002, 251.0));
  EXPECT_DOUBLE_EQ(board.home().lon_deg, -83.002);
  // A corrupt home is dropped and the old one kept.
  const uint32_t dropped = board.dropped_messages();
  EXPECT_FALSE(board.on_home(std::nan(""), -83.0, 250.0));
  EXPECT_FALSE(board.on_home(91.0, -83.0, 250.0));
  EXPECT_EQ(board.dropped_messages(), dropped + 2);
  EXPECT_DOUBLE_EQ(board.home().lat_deg, 40.001);
  GncInput in{};
  board.fill_input(&in);
  EXPECT_EQ(in.home_valid, 1);
  EXPECT_DOUBLE_EQ(in.home_alt_m, 251.0);
}

// What the GNC outputs when all is well: converged, a valid command, from finite inputs.
GncOutput healthy_output() {
  GncOutput out{};
  out.estimator_converged = 1;
  out.command_valid = 1;
  out.inputs_finite = 1;
  return out;
}

TEST(ServoCommand, CarriesDegreesAndAValidCrc) {
  GncOutput out = healthy_output();
  out.throttle = 0.3;
  out.elevator_rad = 0.1;
  out.alpha_est_rad = 0.05;
  const auto cmd = controller::build_servo_command(7, ros::Time(12, 34), out, true, 0.0);
  EXPECT_EQ(cmd.seq, 7u);
  EXPECT_NEAR(cmd.elevator_deg, 0.1 * 180.0 / M_PI, 1e-4);
  EXPECT_TRUE(cmd.estimator_converged);
  EXPECT_TRUE(cmd.sensor_links_healthy);
  EXPECT_EQ(cmd.crc32, controller::servo_command_crc(cmd));
  auto corrupted = cmd;
  corrupted.rudder_deg += 1.0f;
  EXPECT_NE(corrupted.crc32, controller::servo_command_crc(corrupted));
}

TEST(ServoCommand, TheHaFindsTheCrcTheControllerSent) {
  GncOutput out = healthy_output();
  out.throttle = 0.62;
  out.aileron_rad = -0.07;
  out.rudder_rad = 0.02;
  out.beta_est_rad = 0.01;
  const auto cmd = controller::build_servo_command(4242, ros::Time(77, 5000), out, true, 0.0);
  const HaHpCommand ha = servo_command_as_ha(cmd);  // as the Due decodes it
  EXPECT_EQ(cmd.crc32, ha_hp_command_compute_crc(&ha));
}

TEST(ServoCommand, NanFromTheGncNeverReachesTheWire) {
  GncOutput out = healthy_output();
  out.aileron_rad = std::numeric_limits<double>::quiet_NaN();
  const auto cmd = controller::build_servo_command(1, ros::Time(1, 0), out, true, 0.0);
  EXPECT_TRUE(std::isfinite(cmd.aileron_deg));
  EXPECT_FALSE(cmd.estimator_converged);
  EXPECT_EQ(cmd.crc32, controller::servo_command_crc(cmd));
}

TEST(ServoCommand, InvalidGncOutputOrBadLinksAreFlaggedNotHidden) {
  GncOutput out = healthy_output();
  out.command_valid = 0;
  EXPECT_FALSE(
      controller::build_servo_command(1, ros::Time(1, 0), out, true, 0.0).estimator_converged);
  out.command_valid = 1;
  EXPECT_FALSE(
      controller::build_servo_command(1, ros::Time(1, 0), out, false, 0.0).sensor_links_healthy);
  out.inputs_finite = 0;
  EXPECT_FALSE(
      controller::build_servo_command(1, ros::Time(1, 0), out, true, 0.0).sensor_links_healthy);
}

}  // namespace

// Lockstep: the step waits for every message the simulator declares, however late its
// connection brings it.
controller::LockstepCounts one_packet_and_one_report() { return {1, 1, 1, 1, 1, 1, 1}; }

void receive_all(controller::LockstepGate *gate) {
  for (uint32_t i = 0; i < controller::kLockstepInputCount; ++i) {
    gate->received(static_cast<controller::LockstepInput>(i));
  }
}

TEST(LockstepGate, AStepWhoseAttitudeIsStillOnItsWayWaitsForIt) {
  controller::LockstepGate gate;
  gate.declare(one_packet_and_one_report());
  receive_all(&gate);
  ASSERT_TRUE(gate.complete());
  gate.declare(one_packet_and_one_report());
  for (uint32_t i = 0; i < controller::kLockstepInputCount; ++i) {
    if (i != controller::kInAttitude) {
      gate.received(static_cast<controller::LockstepInput>(i));
    }
  }
  EXPECT_FALSE(gate.complete());
  EXPECT_EQ("/attitude 1", gate.missing());
  gate.received(controller::kInAttitude);
  EXPECT_TRUE(gate.complete());
  EXPECT_EQ("", gate.missing());
}

TEST(LockstepGate, MessagesThatArriveBeforeTheirStepCountForIt) {
  controller::LockstepGate gate;
  gate.declare(one_packet_and_one_report());
  receive_all(&gate);
  receive_all(&gate);  // the next step's inputs, here before its declaration
  gate.declare(one_packet_and_one_report());
  EXPECT_TRUE(gate.complete());
}

TEST(LockstepGate, AStepWithoutSensorPacketsStepsAtOnce) {
  controller::LockstepGate gate;
  gate.declare({0, 0, 0, 0, 0, 0, 0});
  EXPECT_TRUE(gate.complete());
}

TEST(LockstepGate, LinkDownPwmBeforeTheFirstStepDoesNotStandInForALaterReport) {
  controller::LockstepGate gate;
  for (int i = 0; i < 3; ++i) {
    gate.received(controller::kInPwm);  // published before the flight's first step
  }
  const auto all_but_pwm = [&gate]() {
    for (uint32_t i = 0; i < controller::kLockstepInputCount; ++i) {
      if (i != controller::kInPwm) {
        gate.received(static_cast<controller::LockstepInput>(i));
      }
    }
  };
  gate.declare(one_packet_and_one_report());
  all_but_pwm();
  ASSERT_TRUE(gate.complete());
  gate.declare(one_packet_and_one_report());
  all_but_pwm();
  EXPECT_FALSE(gate.complete()) << "a /pwm from before the first step was counted for a later one";
  EXPECT_EQ("/pwm 1", gate.missing());
}

TEST(LockstepGate, AStepThatDeclaresHomeWaitsForIt) {
  controller::LockstepGate gate;
  gate.declare({0, 0, 0, 0, 0, 0, 0, 1, 0});
  EXPECT_FALSE(gate.complete());
  EXPECT_EQ("/home 1", gate.missing());
  gate.received(controller::kInHome);
  EXPECT_TRUE(gate.complete());
}

// Latched state in lockstep: home and the plan are taken at the step that declares them.
struct Home {
  int seq;
};

// The seq of what a step with `declared` in total hands over, or 0 for nothing.
int released_seq(controller::HeldInput<Home> *held, uint64_t declared) {
  const Home *h = held->release(declared);
  return h == nullptr ? 0 : h->seq;
}

TEST(HeldInput, AHomeThatArrivesBeforeItsStepIsTakenAtThatStepNotBefore) {
  controller::HeldInput<Home> home;
  home.declared(0);
  home.hold({1});  // the HA latched home in this step; its /home beat the next /hil/lockstep
  EXPECT_EQ(0, released_seq(&home, 0)) << "taken at a step that did not declare it";
  home.declared(1);
  EXPECT_EQ(1, released_seq(&home, 1));
  EXPECT_EQ(0, released_seq(&home, 1)) << "handed over twice";
}

TEST(HeldInput, ARestartedControllerTakesTheLatchedHomeAtItsFirstStep) {
  controller::HeldInput<Home> home;
  home.hold({4});  // the latched /home, delivered as the connection came up
  home.declared(1);
  EXPECT_EQ(4, released_seq(&home, 1));
}

TEST(HeldInput, ARestartedControllerWhoseHomeIsStillOnItsWayWaitsForIt) {
  controller::HeldInput<Home> home;
  home.declared(1);
  EXPECT_EQ(0, released_seq(&home, 1));  // the gate would not have let this step run
  home.hold({4});
  EXPECT_EQ(4, released_seq(&home, 1));
}

TEST(HeldInput, OfWhatWentOutBeforeTheFirstStepOnlyTheNewestCounts) {
  controller::HeldInput<Home> plan;
  plan.hold({1});
  plan.hold({2});  // two plans before the first step; the simulator saw only the latched one
  plan.declared(1);
  EXPECT_EQ(2, released_seq(&plan, 1));
}

TEST(HeldInput, ANewPlanHereEarlyWaitsForTheStepThatDeclaresIt) {
  controller::HeldInput<Home> plan;
  plan.declared(1);
  plan.hold({1});
  plan.hold({2});  // the next step's, here before its declaration
  EXPECT_EQ(1, released_seq(&plan, 1));
  plan.declared(2);
  EXPECT_EQ(2, released_seq(&plan, 2));
}

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

// /home from the HA: the sensor board keeps what the HA's own judge (geo_ref_init) takes, and
// drops (counted) what it refuses, an altitude the flat earth cannot use included.
TEST(SensorBoard, TakesAHomeExactlyWhenTheHasJudgeDoes) {
  const auto p = aircraft();
  for (const HomeVector &v : kHomeVectors) {
    controller::SensorBoard board(p);
    EXPECT_EQ(board.on_home(v.lat_deg, v.lon_deg, v.alt_m), v.valid) << v.what;
    EXPECT_EQ(board.home_valid(), v.valid) << v.what;
    EXPECT_EQ(board.dropped_messages(), v.valid ? 0u : 1u) << v.what;
  }
}

// Real time on the VN-200's packets (packet_pacer.h): the five topics of one packet, in the
// order the vn200 node publishes them, the last arriving at t_s.
bool packet(controller::PacketPacer &pacer, double t_s) {
  using controller::LockstepInput;
  bool due = false;
  for (LockstepInput in : {controller::kInIns, controller::kInAttitude, controller::kInGpsPosition,
                           controller::kInGpsVelocity, controller::kInImu}) {
    EXPECT_FALSE(due) << "a step before the packet's last message";
    due = pacer.on_sensor(in, t_s);
  }
  return due;
}

TEST(PacketPacer, TheStepRunsWhenThePacketsLastMessageArrivesNotOnATimer) {
  controller::PacketPacer pacer(0.01, 1);
  EXPECT_TRUE(packet(pacer, 1.0000));
  pacer.stepped(1.0000);
  EXPECT_DOUBLE_EQ(pacer.fallback_at_s(), 1.0125);
  EXPECT_TRUE(packet(pacer, 1.0102));  // a little late: stepped on arrival all the same
  pacer.stepped(1.0102);
  EXPECT_FALSE(pacer.on_sensor(controller::kInPwm, 1.0150));  // the HA's report is no packet
}

TEST(PacketPacer, MessagesOfTwoPacketsInterleavedOverTheirConnectionsCountAsTwo) {
  controller::PacketPacer pacer(0.01, 1);
  for (auto in : {controller::kInIns, controller::kInAttitude, controller::kInGpsPosition,
                  controller::kInGpsVelocity}) {
    EXPECT_FALSE(pacer.on_sensor(in, 1.0));
  }
  EXPECT_FALSE(pacer.on_sensor(controller::kInIns, 1.0));  // packet 2's /ins before 1's IMU
  EXPECT_TRUE(pacer.on_sensor(controller::kInImu, 1.0));
  pacer.stepped(1.0);
  EXPECT_EQ(pacer.complete_packets(), 1u);
}

TEST(PacketPacer, ATwentyHertzControllerStepsOnEveryFifthPacketOfAHundredHertzSensor) {
  controller::PacketPacer pacer(0.05, 5);
  int steps = 0;
  for (int k = 0; k < 20; ++k) {
    const double t = 1.0 + 0.01 * k;
    if (packet(pacer, t)) {
      pacer.stepped(t);
      ++steps;
      EXPECT_EQ(k % 5, 4) << "stepped on packet " << k;
    }
  }
  EXPECT_EQ(steps, 4);
}

TEST(PacketPacer, ALostPacketLeavesTheStepToTheFallbackAndTheLateOneWaitsForTheNext) {
  controller::PacketPacer pacer(0.01, 1);
  ASSERT_TRUE(packet(pacer, 1.000));
  pacer.stepped(1.000);
  // Packet 2 lost: the node's fallback steps at 1.0125, within 1.25 periods, never two.
  EXPECT_DOUBLE_EQ(pacer.fallback_at_s(), 1.0125);
  pacer.stepped(1.0125);
  // Packet 3 comes 1 ms after that step: not a second step in a millisecond ...
  EXPECT_FALSE(packet(pacer, 1.0135));
  // ... the next packet steps, on its own last message.
  EXPECT_TRUE(packet(pacer, 1.0230));
  pacer.stepped(1.0230);
  EXPECT_TRUE(packet(pacer, 1.0330));
}
