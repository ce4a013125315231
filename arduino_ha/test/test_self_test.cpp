// Pre-flight surface self-test: only on the ground and only on command.
#include <gtest/gtest.h>

#include <cmath>

#include "ha_test_util.h"

namespace {

TEST(HaSelfTest, SelfTestRefusedInFlight) {
  Timeline t;
  t.Cruise();
  t.app.inputs.on_ground = 1;  // a wrong ground flag is not enough: altitude and speed say flying
  for (int i = 0; i < 10; ++i) t.Step();
  t.Operator(HA_OP_SELF_TEST);
  const size_t from = t.board.servo_writes.size();
  for (int i = 0; i < 300; ++i) t.Step();
  EXPECT_EQ(t.app.requests.ack_count, 1u);
  EXPECT_EQ(t.app.requests.ack_accepted, 0u);
  EXPECT_EQ(t.out().self_test_active, 0u);
  for (size_t i = from; i < t.board.servo_writes.size(); ++i) {
    ASSERT_LT(std::fabs(t.board.servo_writes[i].elevator_deg), 0.9f * t.cfg.elevator_limit_deg);
  }
}

TEST(HaSelfTest, OnGroundSweepsEachSurfaceToBothLimitsThenThrottle) {
  Timeline t;
  t.Parked();
  for (int i = 0; i < 10; ++i) t.Step();
  t.Operator(HA_OP_SELF_TEST);
  t.Step();
  EXPECT_EQ(t.app.requests.ack_accepted, 1u);
  EXPECT_EQ(t.out().self_test_active, 1u);
  HaSurfaces lo{}, hi{};
  int periods = 0;
  while (t.out().self_test_active && periods < 100000) {
    t.Step();
    const HaSurfaces s = t.servos();
    lo = {std::min(lo.throttle, s.throttle), std::min(lo.elevator_deg, s.elevator_deg),
          std::min(lo.aileron_deg, s.aileron_deg), std::min(lo.rudder_deg, s.rudder_deg)};
    hi = {std::max(hi.throttle, s.throttle), std::max(hi.elevator_deg, s.elevator_deg),
          std::max(hi.aileron_deg, s.aileron_deg), std::max(hi.rudder_deg, s.rudder_deg)};
    ++periods;
  }
  EXPECT_FLOAT_EQ(hi.elevator_deg, t.cfg.elevator_limit_deg);
  EXPECT_FLOAT_EQ(lo.elevator_deg, -t.cfg.elevator_limit_deg);
  EXPECT_FLOAT_EQ(hi.aileron_deg, t.cfg.aileron_limit_deg);
  EXPECT_FLOAT_EQ(lo.aileron_deg, -t.cfg.aileron_limit_deg);
  EXPECT_FLOAT_EQ(hi.rudder_deg, t.cfg.rudder_limit_deg);
  EXPECT_FLOAT_EQ(lo.rudder_deg, -t.cfg.rudder_limit_deg);
  EXPECT_FLOAT_EQ(hi.throttle, t.cfg.self_test_throttle_max);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_HA);
}

TEST(HaSelfTest, PilotSwitchAbortsSelfTest) {
  Timeline t;
  t.Parked();
  t.Step();
  t.Operator(HA_OP_SELF_TEST);
  for (int i = 0; i < 50; ++i) t.Step();
  ASSERT_EQ(t.out().self_test_active, 1u);
  t.board.SetPilotInCommand(true);
  t.Step();
  EXPECT_EQ(t.out().self_test_active, 0u);
  EXPECT_EQ(t.controller(), HA_CONTROLLER_MANUAL);
}

// The answer to a SELF_TEST that must be refused: acknowledged once, not accepted, not started,
// and whoever had the servos keeps them.
void ExpectSelfTestRefusedAndServosKept(const Timeline& t, uint8_t controller) {
  EXPECT_EQ(t.app.requests.ack_count, 1u);
  EXPECT_EQ(t.app.requests.ack_accepted, 0u);
  EXPECT_EQ(t.out().self_test_active, 0u);
  EXPECT_EQ(t.controller(), controller);
}

// The pilot on the sticks of a parked aircraft (taxiing it, checking the surfaces by hand): a
// SELF_TEST request sweeping them under the pilot's hands is refused, and the sticks stay on the
// servos.
TEST(HaSelfTest, SelfTestRefusedWhileThePilotHasTheSticks) {
  Timeline t;
  t.Parked();
  t.board.SetPilotInCommand(true);
  for (int i = 0; i < 10; ++i) t.Step();
  ASSERT_EQ(t.controller(), HA_CONTROLLER_MANUAL);
  t.Operator(HA_OP_SELF_TEST);
  t.Step();
  ExpectSelfTestRefusedAndServosKept(t, HA_CONTROLLER_MANUAL);
}

// On the ground with the HP's commands on the servos (taxiing, a pre-flight check of the HP's
// loop): a SELF_TEST would sweep the surfaces out from under the HP. Refused; the HP keeps them.
TEST(HaSelfTest, SelfTestRefusedWhileTheHpHasTheServosOnTheGround) {
  Timeline t;
  t.Parked();
  ASSERT_GT(t.ReachHp(), 0);
  t.Operator(HA_OP_SELF_TEST);
  t.StepWithGood();
  ExpectSelfTestRefusedAndServosKept(t, HA_CONTROLLER_HP);
}

// A ground station sending queued requests back to back, faster than one a period: what the
// queue cannot hold is counted lost, never run and never acknowledged, so the acknowledgements
// and the losses add up to what was sent and the sender knows which to send again.
TEST(HaSelfTest, MoreOperatorRequestsInOnePeriodThanTheQueueHoldsAreCountedLostNotRun) {
  Timeline t;
  t.Parked();
  for (int i = 0; i < 10; ++i) t.Step();
  const uint32_t sent = HA_OPERATOR_QUEUE_LEN + 2u;
  for (uint32_t k = 0; k < sent; ++k) t.Operator(k == 0 ? HA_OP_SELF_TEST : HA_OP_SELECT_HA);
  for (int i = 0; i < 10; ++i) t.Step();
  EXPECT_EQ(t.app.requests.lost, 2u);
  EXPECT_EQ(t.app.requests.ack_count + t.app.requests.lost, sent);
  EXPECT_EQ(t.app.requests.ack_id, t.operator_id);  // the last one sent was answered
  EXPECT_EQ(t.out().self_test_active, 0u) << "the overwritten SELF_TEST ran";
}

// A request id is the sender's, and it may reuse one for another command (a restarted ground
// station counting from 1 again): only the same id with the same command is a repeat.
TEST(HaSelfTest, ARequestIdReusedForAnotherCommandIsANewRequest) {
  Timeline t;
  t.Parked();
  for (int i = 0; i < 10; ++i) t.Step();
  ha_app_put_operator(&t.app, HA_OP_SELECT_HA, 7u);
  t.Step();
  ASSERT_EQ(t.app.requests.ack_accepted, 1u);
  ha_app_put_operator(&t.app, HA_OP_SELF_TEST, 7u);
  t.Step();
  EXPECT_EQ(t.app.requests.ack_count, 2u);
  EXPECT_EQ(t.app.requests.ack_accepted, 1u);
  EXPECT_EQ(t.out().self_test_active, 1u) << "taken for a repeat of SELECT_HA";
}

// Parked means level, still and stopped: a tilted, turning or rolling aircraft that reports
// itself on the ground (a wrong INS flag, a failed pitot reading zero) never runs the self-test.
TEST(HaSelfTest, SelfTestRefusedUnlessLevelStillAndStopped) {
  struct Case {
    const char* name;
    float roll_deg, pitch_deg, q_deg_s, r_deg_s, groundspeed_ftps;
  };
  const Case cases[] = {
      {"banked", 30.0f, 0.0f, 0.0f, 0.0f, 0.0f},
      {"nose high", 0.0f, 25.0f, 0.0f, 0.0f, 0.0f},
      {"pitching", 0.0f, 0.0f, 20.0f, 0.0f, 0.0f},
      {"turning", 0.0f, 0.0f, 0.0f, 15.0f, 0.0f},
      // Flying slowly into a headwind over the ground, the pitot failed and reading zero.
      {"moving over the ground", 0.0f, 0.0f, 0.0f, 0.0f, 20.0f},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Timeline t;
    t.Parked();
    t.app.inputs.roll_deg = c.roll_deg;
    t.app.inputs.pitch_deg = c.pitch_deg;
    t.app.inputs.q_deg_s = c.q_deg_s;
    t.app.inputs.r_deg_s = c.r_deg_s;
    t.app.inputs.groundspeed_ftps = c.groundspeed_ftps;
    for (int i = 0; i < 10; ++i) t.Step();
    t.Operator(HA_OP_SELF_TEST);
    t.Step();
    EXPECT_EQ(t.app.requests.ack_accepted, 0u);
    EXPECT_EQ(t.out().self_test_active, 0u);
  }
}

}  // namespace
