// The HA's input paths end to end: the bytes the HP's `arduino` node writes to the Due (a ROS
// message serialized by roscpp and framed by the node's own encoder, arduino_link's
// encode_frame), on the board's HP port, through the firmware loop every board runs
// (src/firmware/: the link decoder and session, the routing) into the core, period by period.
#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <drone_ros/OperatorCommand.h>
#include <drone_ros/ServoCommand.h>

#include <vector>

#include "firmware_on_fake_board.h"
#include "ha_link.h"
#include "rosserial_framer.h"

namespace {

using link_test::Bytes;

// What the arduino node does with a message it forwards (ArduinoLinkNode::on_ros_message, send).
template <typename M>
Bytes node_frame(uint16_t topic_id, const M& msg) {
  Bytes payload(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(payload.data(), static_cast<uint32_t>(payload.size()));
  ros::serialization::serialize(out, msg);
  return arduino_link::encode_frame(topic_id, payload.data(), payload.size());
}

// The HP's command as controller_DG808 publishes it: fields and the CRC over them.
drone_ros::ServoCommand servo_msg(const HaHpCommand& c) {
  drone_ros::ServoCommand m;
  m.seq = c.seq;
  m.stamp.sec = c.stamp_sec;
  m.stamp.nsec = c.stamp_nsec;
  m.throttle = c.throttle;
  m.elevator_deg = c.elevator_deg;
  m.aileron_deg = c.aileron_deg;
  m.rudder_deg = c.rudder_deg;
  m.alpha_est_deg = c.alpha_est_deg;
  m.beta_est_deg = c.beta_est_deg;
  m.estimator_converged = c.estimator_converged;
  m.sensor_links_healthy = c.sensor_links_healthy;
  m.crc32 = c.crc32;
  return m;
}

// Sealed as microhard_gs seals it: crc32 over the serialization of every field before it.
drone_ros::OperatorCommand sealed(drone_ros::OperatorCommand m) {
  m.crc32 = 0;
  Bytes raw(ros::serialization::serializationLength(m));
  ros::serialization::OStream out(raw.data(), static_cast<uint32_t>(raw.size()));
  ros::serialization::serialize(out, m);
  m.crc32 = ha_crc32(raw.data(), HA_OPERATOR_COMMAND_FIELDS_LEN);
  return m;
}

drone_ros::OperatorCommand operator_msg(uint8_t command, uint32_t request_id) {
  drone_ros::OperatorCommand m;
  m.stamp = ros::Time(1700000000, 0);
  m.command = command;
  m.request_id = request_id;
  return sealed(m);
}

Bytes servo_frame(const HaHpCommand& c) { return node_frame(HA_LINK_TOPIC_SERVO_OP, servo_msg(c)); }

// The HA as every board runs it; the bytes arrive between two periods.
struct LinkedHa {
  FirmwareOnFakeBoard t;
  HaLink& link = t.fw.link;

  LinkedHa() { t.Period(); }  // the first period, at power-up
  const HaOutputs& Period(const Bytes& bytes) {
    t.Hp(bytes);
    return t.Period();
  }
  Bytes NextCommandFrame() { return servo_frame(t.NextCommand()); }
  const HaOutputs& PeriodWithCommand(const Bytes& extra = {}) {
    return t.PeriodWithCommand(servo_frame, extra);
  }
  bool ReachHp() { return t.ReachHp(servo_frame); }
  // Operator requests the link handed over (their CRC-32 matched).
  uint32_t operator_handed_over() const { return link.counters.operator_commands; }
  const HaOutputs& out() const { return t.fw.app.outputs; }
  // The operator's requests as the firmware queues and answers them (ha_app.h).
  const HaOperatorQueue& requests() const { return t.fw.app.requests; }
};

Bytes operator_frame(uint8_t command, uint32_t request_id) {
  return node_frame(HA_LINK_TOPIC_OPERATOR_COMMAND, operator_msg(command, request_id));
}

}  // namespace

// K5: a ServoCommand frame that lost one byte on the wire took the next frame's sync byte as its
// checksum. The decoder searches again from inside the failed frame, so the next, intact frame
// arrives: one command is missing (one late period, tolerated), not two (a takeover and a
// restart of a healthy HP).
TEST(HaLinkStories, OneByteLostFromAServoCommandLosesOnlyThatCommandAndTheHpKeepsControl) {
  LinkedHa ha;
  ASSERT_TRUE(ha.ReachHp());
  const uint32_t delivered = ha.link.counters.commands;
  Bytes damaged = ha.NextCommandFrame();
  damaged.erase(damaged.begin() + 20);  // a payload byte (the throttle's) lost
  EXPECT_EQ(ha.Period(damaged).controller, HA_CONTROLLER_HP);
  for (int i = 0; i < 20; ++i) {
    const HaOutputs& out = ha.PeriodWithCommand();
    EXPECT_EQ(out.controller, HA_CONTROLLER_HP) << "period " << i << " after the lost byte";
    EXPECT_EQ(out.reasons, 0u) << "period " << i << " after the lost byte";
  }
  EXPECT_EQ(ha.link.counters.commands, delivered + 20u);  // every intact frame
  EXPECT_EQ(ha.link.decoder.counters.bad_checksum, 1u);
  EXPECT_EQ(ha.out().restart_count, 0u);
  EXPECT_EQ(ha.t.board.hp_reset_assertions, 0);
}

// K6: the ground station sends queued requests back to back, so two can arrive within one
// period. Each is executed, in order, in a period of its own, and acknowledged only then.
TEST(HaLinkStories, TwoOperatorRequestsInOnePeriodAreBothExecutedInOrderAndEachAcknowledged) {
  LinkedHa ha;
  ASSERT_TRUE(ha.ReachHp());
  Bytes two = operator_frame(HA_OP_SELECT_HA, 41u);
  const Bytes restart = operator_frame(HA_OP_RESTART_HP, 42u);
  two.insert(two.end(), restart.begin(), restart.end());
  const HaOutputs& first = ha.PeriodWithCommand(two);
  EXPECT_EQ(ha.operator_handed_over(), 2u);
  EXPECT_EQ(first.controller, HA_CONTROLLER_HA);  // SELECT_HA, executed
  EXPECT_EQ(first.reasons & HA_REASON_GROUND_COMMAND, HA_REASON_GROUND_COMMAND);
  EXPECT_EQ(ha.requests().ack_id, 41u);
  EXPECT_EQ(ha.requests().ack_accepted, 1u);
  EXPECT_EQ(ha.requests().ack_count, 1u);  // the restart has not run yet: not acknowledged
  EXPECT_EQ(first.restart_count, 0u);
  const HaOutputs& second = ha.PeriodWithCommand();
  EXPECT_EQ(ha.requests().ack_id, 42u);  // RESTART_HP, with the HA now in control: executed
  EXPECT_EQ(ha.requests().ack_accepted, 1u);
  EXPECT_EQ(ha.requests().ack_count, 2u);
  EXPECT_EQ(second.restart_count, 1u);
  EXPECT_TRUE(ha.t.board.hp_reset);
  EXPECT_EQ(ha.requests().lost, 0u);
}

// K7: a sender that hears no answer sends its request again, and a link may deliver one twice.
// A RESTART_HP delivered three times restarts the HP once (three would fill the restart cap, so
// the next single HP fault would latch the HA for good), and each delivery is acknowledged, so a
// retrying sender stops. request_id 0 is an id like any other, and ids wrap.
TEST(HaLinkStories, RestartRequestDeliveredThreeTimesRestartsTheHpOnceAndIsAcknowledgedEachTime) {
  LinkedHa ha;
  ASSERT_TRUE(ha.ReachHp());
  ha.PeriodWithCommand(operator_frame(HA_OP_SELECT_HA, 7u));  // the HA flies: restarts allowed
  ASSERT_EQ(ha.out().controller, HA_CONTROLLER_HA);
  for (int delivery = 1; delivery <= 3; ++delivery) {
    const HaOutputs& out = ha.PeriodWithCommand(operator_frame(HA_OP_RESTART_HP, 0u));
    EXPECT_EQ(ha.requests().ack_id, 0u) << "delivery " << delivery;
    EXPECT_EQ(ha.requests().ack_accepted, 1u) << "delivery " << delivery;
    EXPECT_EQ(ha.requests().ack_count, 1u + static_cast<uint32_t>(delivery));
    EXPECT_EQ(out.restart_count, 1u) << "delivery " << delivery;
    for (int i = 0; i < 100; ++i) ha.PeriodWithCommand();  // a retry a second later
  }
  EXPECT_EQ(ha.t.board.hp_reset_assertions, 1);
  // The next request, even one whose id wrapped around to 0 again after 2^32 - 1, is new.
  ha.Period(operator_frame(HA_OP_SELECT_HA, 0xFFFFFFFFu));
  ha.Period(operator_frame(HA_OP_RESTART_HP, 0u));
  EXPECT_EQ(ha.requests().ack_id, 0u);
  EXPECT_EQ(ha.out().restart_count, 2u);
}

// K3: rosserial's 8-bit sum cannot see a byte that went up by one while another went down by
// one. Such a pair turned SELECT_HA into SELECT_HP, and moved a SET_HOME by hundreds of metres.
// The request's own CRC-32 sees it: the request is counted and dropped, never acted on, and the
// requests after it are.
TEST(HaLinkStories, OperatorRequestChangedByABytePairTheFrameSumCannotSeeIsNeverActedOn) {
  LinkedHa ha;
  ASSERT_TRUE(ha.ReachHp());
  ha.PeriodWithCommand(operator_frame(HA_OP_SELECT_HA, 50u));
  ASSERT_EQ(ha.out().controller, HA_CONTROLLER_HA);
  // An intact SELECT_HA (51) on the way: its command byte one down (SELECT_HP), its
  // request_id's low byte one up.
  Bytes pair = operator_frame(HA_OP_SELECT_HA, 51u);
  const size_t command_at = 7u + 8u;  // frame header, then the stamp
  ASSERT_EQ(pair[command_at], HA_OP_SELECT_HA);
  pair[command_at] -= 1;      // SELECT_HP
  pair[command_at + 1] += 1;  // request_id 52: the frame's checksum still matches
  for (int i = 0; i < 50; ++i) ha.PeriodWithCommand(i == 0 ? pair : Bytes{});
  EXPECT_EQ(ha.link.decoder.counters.bad_checksum, 0u);  // the frame passed rosserial's check
  EXPECT_EQ(ha.link.counters.operator_bad_crc, 1u);
  EXPECT_EQ(ha.operator_handed_over(), 1u);  // only SELECT_HA (50)
  EXPECT_EQ(ha.out().controller, HA_CONTROLLER_HA);
  EXPECT_EQ(ha.requests().ack_id, 50u);

  // A SET_HOME whose latitude's bytes took a +1/-1 pair (40.4237054 -> 40.4315179 deg: 867 m
  // north) likewise.
  drone_ros::OperatorCommand home;
  home.stamp = ros::Time(1700000000, 0);
  home.command = HA_OP_SET_HOME;
  home.request_id = 53u;
  home.latitude = 40.4237054;
  home.longitude = -86.9211946;
  home.altitude = 185.25;
  Bytes moved = node_frame(HA_LINK_TOPIC_OPERATOR_COMMAND, sealed(home));
  const size_t latitude_at = 7u + 8u + 1u + 4u + 1u;
  moved[latitude_at + 5] += 1;  // 0x36 -> 0x37
  moved[latitude_at] -= 1;      // 0xbe -> 0xbd
  ha.PeriodWithCommand(moved);
  EXPECT_EQ(ha.link.counters.operator_bad_crc, 2u);
  EXPECT_EQ(ha.operator_handed_over(), 1u);

  // Intact requests still go through.
  ha.PeriodWithCommand(operator_frame(HA_OP_SELECT_HP, 54u));
  EXPECT_EQ(ha.operator_handed_over(), 2u);
  EXPECT_EQ(ha.requests().ack_id, 54u);
  EXPECT_EQ(ha.requests().ack_accepted, 1u);
}
