// What the HA tells the HP each period (src/link/ha_link_report.c), the one builder the Due
// and the host SIL both publish with (through src/firmware/ha_firmware.c). Before it the two
// derived pwm's PICCIC differently: the Due from the core's decision, the SIL from the switch's
// pulse alone (>= 1500 us), so a pilot switch at PIC with the receiver lost read "pilot in
// command" in the SIL while the HA flew.
#include <gtest/gtest.h>

#include "ha_link_report.h"
#include "ha_surfaces.h"
#include "ha_test_util.h"

namespace {

const double kRadPerDeg = 0.017453292519943295;
const HaRosTime kStamp = {1700000000u, 250000000u};

drone_ros_pwm Pwm(const Timeline& t) {
  drone_ros_pwm pwm;
  ha_report_pwm(&t.cfg, &t.app.inputs, &t.app.outputs, kStamp, &pwm);
  return pwm;
}

TEST(HaLinkReport, PilotSwitchAtPicWithTheReceiverLostReportsTheComputerInCommand) {
  Timeline t;
  t.Cruise();
  t.board.SetPilotInCommand(true);
  t.board.rc.valid = 0;
  t.Step();
  ASSERT_NE(t.controller(), HA_CONTROLLER_MANUAL);
  EXPECT_EQ(1, Pwm(t).PICCIC) << "the HA flies: the HP must not take the sticks as trim";
}

TEST(HaLinkReport, PilotInCommandReportsPicAndTheSticksAsTheCoreFliesThem) {
  Timeline t;
  t.Cruise();
  t.board.SetPilotInCommand(true);
  t.board.rc.pulse_us[HA_RC_THROTTLE] = 1600;
  t.board.rc.pulse_us[HA_RC_ELEVATOR] = 1700;
  t.board.rc.pulse_us[HA_RC_AILERON] = 1300;
  t.board.rc.pulse_us[HA_RC_RUDDER] = 1550;
  t.Step();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_MANUAL);
  HaSurfaces sticks;
  ha_surfaces_from_rc(&t.cfg, &t.app.inputs.rc, &sticks);
  const drone_ros_pwm pwm = Pwm(t);
  EXPECT_EQ(0, pwm.PICCIC);
  EXPECT_DOUBLE_EQ(sticks.throttle, pwm.Throttle);
  EXPECT_DOUBLE_EQ(sticks.elevator_deg * kRadPerDeg, pwm.Elevator);
  EXPECT_DOUBLE_EQ(sticks.aileron_deg * kRadPerDeg, pwm.Aileron);
  EXPECT_DOUBLE_EQ(sticks.rudder_deg * kRadPerDeg, pwm.Rudder);
  EXPECT_GT(pwm.Elevator, 0.0);
  EXPECT_LT(pwm.Aileron, 0.0);
  EXPECT_DOUBLE_EQ(t.out().airspeed_ftps, pwm.velocity) << "the checked airspeed, not the raw read";
  EXPECT_EQ(kStamp.sec, pwm.header.stamp.sec);
  EXPECT_EQ(1, pwm.usbstatus);
}

TEST(HaLinkReport, DecisionStatusIsTheCoresDecisionFieldForField) {
  Timeline t;
  t.Cruise();
  ASSERT_GT(t.ReachHp(), 0);
  t.refresh_state = false;  // the INS goes silent: the HA takes over and says why
  for (int k = 0; k < 100 && t.controller() == HA_CONTROLLER_HP; ++k) t.StepWithGood();
  ASSERT_NE(t.controller(), HA_CONTROLLER_HP);
  const HaOutputs& o = t.out();
  drone_ros_DecisionStatus st;
  ha_report_decision_status(&o, kStamp, &st);
  EXPECT_EQ(kStamp.nsec, st.stamp.nsec);
  EXPECT_EQ(o.controller, st.controller);
  EXPECT_NE(0u, st.reasons_at_switch);
  EXPECT_EQ(o.reasons, st.reasons);
  EXPECT_EQ(o.reasons_at_switch, st.reasons_at_switch);
  EXPECT_EQ(o.restart_count, st.restart_count);
  EXPECT_EQ(o.restart_requested, st.restart_requested);
  EXPECT_EQ(o.last_seq, st.last_seq);
  EXPECT_EQ(o.stable_for_s, st.stable_for_s);
  EXPECT_EQ(o.airspeed_ftps, st.airspeed_ftps);
  EXPECT_EQ(o.altitude_agl_ft, st.altitude_agl_ft);
  EXPECT_EQ(o.alpha_deg, st.alpha_deg);
  EXPECT_EQ(o.beta_deg, st.beta_deg);
  EXPECT_EQ(o.state_region_max, st.state_region_max);
  EXPECT_EQ(o.actuator_region_max, st.actuator_region_max);
  EXPECT_EQ(o.surfaces.throttle, st.throttle);
  EXPECT_EQ(o.surfaces.elevator_deg, st.elevator_deg);
  EXPECT_EQ(o.surfaces.aileron_deg, st.aileron_deg);
  EXPECT_EQ(o.surfaces.rudder_deg, st.rudder_deg);
}

TEST(HaLinkReport, HomeIsOnlySentOnceTheInsHasLatchedIt) {
  HaIns ins;
  ha_ins_init(&ins);
  drone_ros_HomePosition home;
  ha_report_home(&ins, kStamp, &home);
  EXPECT_EQ(0u, home.seq) << "seq 0: nothing to send";
  ins.home_latched = 1u;
  ins.home_seq = 3u;
  ins.home.lat_deg = 47.5;
  ins.home.lon_deg = 8.25;
  ins.home.alt_m = 412.0;
  ha_report_home(&ins, kStamp, &home);
  EXPECT_EQ(3u, home.seq);
  EXPECT_EQ(47.5, home.latitude);
  EXPECT_EQ(8.25, home.longitude);
  EXPECT_EQ(412.0, home.altitude);
}

}  // namespace
