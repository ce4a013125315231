// The message interface is a wire contract with the Due and with code written for the thesis
// avionics: these tests catch an accidental change of a field, a type or an order.
#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <drone_ros/DecisionStatus.h>
#include <drone_ros/HilTruth.h>
#include <drone_ros/HomePosition.h>
#include <drone_ros/LockstepStep.h>
#include <drone_ros/OperatorCommand.h>
#include <drone_ros/ServoCommand.h>
#include <drone_ros/data.h>
#include <drone_ros/hil_data.h>
#include <drone_ros/ins.h>
#include <drone_ros/pwm.h>
#include <drone_ros/way.h>

#include "hp_command.h"
#include "message_md5sums.h"
#include "servo_command_as_ha.h"

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

template <typename M>
std::vector<uint8_t> serialize(const M& msg) {
  std::vector<uint8_t> buf(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(buf.data(), static_cast<uint32_t>(buf.size()));
  ros::serialization::serialize(out, msg);
  return buf;
}

template <typename M>
M deserialize(std::vector<uint8_t> buf) {
  M msg;
  ros::serialization::IStream in(buf.data(), static_cast<uint32_t>(buf.size()));
  ros::serialization::deserialize(in, msg);
  return msg;
}

// The message survives a round trip and re-serializes to the very same bytes.
template <typename M>
M roundTrip(const M& msg) {
  const auto bytes = serialize(msg);
  const M back = deserialize<M>(bytes);
  EXPECT_EQ(bytes, serialize(back));
  return back;
}

template <typename M>
void expectPinned(const std::map<std::string, std::string>& sums) {
  const std::string name = ros::message_traits::DataType<M>::value();
  ASSERT_EQ(1u, sums.count(name)) << name << " has no pinned md5sum in test/message_md5sums.txt";
  EXPECT_EQ(sums.at(name), ros::message_traits::MD5Sum<M>::value())
      << name << " changed: the Due firmware and every recorded bag depend on it. If the change is "
      << "deliberate, regenerate the device code and update the pinned sum.";
}

}  // namespace

TEST(Messages, ServoCommandRoundTripKeepsEveryField) {
  drone_ros::ServoCommand cmd;
  cmd.seq = 4000000123u;
  cmd.stamp = ros::Time(1700000000, 123456789);
  cmd.throttle = 0.62f;
  cmd.elevator_deg = -19.5f;
  cmd.aileron_deg = 14.25f;
  cmd.rudder_deg = -3.0f;
  cmd.alpha_est_deg = 4.5f;
  cmd.beta_est_deg = -1.25f;
  cmd.estimator_converged = true;
  cmd.sensor_links_healthy = false;
  cmd.crc32 = 0xDEADBEEFu;

  // 38 bytes of fields covered by the CRC, then the CRC itself.
  EXPECT_EQ(42u, ros::serialization::serializationLength(cmd));
  const auto back = roundTrip(cmd);
  EXPECT_EQ(cmd.seq, back.seq);
  EXPECT_EQ(cmd.stamp, back.stamp);
  EXPECT_FLOAT_EQ(cmd.throttle, back.throttle);
  EXPECT_FLOAT_EQ(cmd.elevator_deg, back.elevator_deg);
  EXPECT_FLOAT_EQ(cmd.aileron_deg, back.aileron_deg);
  EXPECT_FLOAT_EQ(cmd.rudder_deg, back.rudder_deg);
  EXPECT_FLOAT_EQ(cmd.alpha_est_deg, back.alpha_est_deg);
  EXPECT_FLOAT_EQ(cmd.beta_est_deg, back.beta_est_deg);
  EXPECT_TRUE(back.estimator_converged);
  EXPECT_FALSE(back.sensor_links_healthy);
  EXPECT_EQ(0xDEADBEEFu, back.crc32);
}

TEST(Messages, ServoCommandCrcCoversTheLittleEndianFieldBytes) {
  drone_ros::ServoCommand cmd;
  cmd.seq = 0x01020304u;
  const auto bytes = serialize(cmd);
  // The CRC contract in ServoCommand.msg relies on this layout: seq first, little endian.
  ASSERT_GE(bytes.size(), 4u);
  EXPECT_EQ(0x04, bytes[0]);
  EXPECT_EQ(0x01, bytes[3]);
}

TEST(ServoCommandCrc, MatchesTheStandardCheckValue) {
  const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(0xCBF43926u, ha_crc32(check, sizeof check));
}

TEST(ServoCommandCrc, HaPackingEqualsRosSerializationSoBothEndsAgree) {
  drone_ros::ServoCommand cmd;
  cmd.seq = 77;
  cmd.stamp = ros::Time(1700000001, 5000);
  cmd.throttle = 0.55f;
  cmd.elevator_deg = -2.5f;
  cmd.aileron_deg = 7.0f;
  cmd.rudder_deg = -0.75f;
  cmd.alpha_est_deg = 3.5f;
  cmd.beta_est_deg = 0.25f;
  cmd.estimator_converged = true;
  cmd.sensor_links_healthy = true;
  const auto ros_bytes = serialize(cmd);

  const HaHpCommand ha = servo_command_as_ha(cmd);
  uint8_t packed[HA_HP_COMMAND_FIELDS_LEN];
  ha_hp_command_pack_fields(&ha, packed);
  EXPECT_EQ(std::vector<uint8_t>(ros_bytes.begin(), ros_bytes.begin() + HA_HP_COMMAND_FIELDS_LEN),
            std::vector<uint8_t>(packed, packed + HA_HP_COMMAND_FIELDS_LEN));
  EXPECT_EQ(ha_crc32(ros_bytes.data(), HA_HP_COMMAND_FIELDS_LEN), ha_hp_command_compute_crc(&ha));
}

TEST(ServoCommandCrc, EveryFlippedBitOfTheCommandIsDetected) {
  HaHpCommand ha = {};
  ha.seq = 12;
  ha.aileron_deg = 4.0f;
  const uint32_t good = ha_hp_command_compute_crc(&ha);
  uint8_t packed[HA_HP_COMMAND_FIELDS_LEN];
  ha_hp_command_pack_fields(&ha, packed);
  for (unsigned bit = 0; bit < 8 * HA_HP_COMMAND_FIELDS_LEN; ++bit) {
    packed[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_NE(good, ha_crc32(packed, sizeof packed)) << "bit " << bit;
    packed[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
  }
}

TEST(Messages, DecisionStatusRoundTripKeepsReasonsAndCheckedValues) {
  drone_ros::DecisionStatus st;
  st.stamp = ros::Time(42, 7);
  st.controller = drone_ros::DecisionStatus::CONTROLLER_RECOVERING;
  st.reasons = drone_ros::DecisionStatus::REASON_STALL | drone_ros::DecisionStatus::REASON_CEILING;
  st.reasons_at_switch = drone_ros::DecisionStatus::REASON_NO_COMMAND;
  st.restart_count = 2;
  st.restart_requested = true;
  st.last_seq = 99;
  st.stable_for_s = 1.5f;
  st.airspeed_ftps = 55.0f;
  st.altitude_agl_ft = 399.0f;
  st.alpha_deg = 3.0f;
  st.beta_deg = -2.0f;
  st.state_region_max = 0.8f;
  st.actuator_region_max = 1.2f;
  st.throttle = 0.5f;
  st.elevator_deg = 1.0f;
  st.aileron_deg = -2.0f;
  st.rudder_deg = 0.5f;

  EXPECT_EQ(st, roundTrip(st));  // every field
}

// The Due decodes this from the wire by position (its generated code), so the layout is part of
// the contract: stamp, command, request id, then SET_HOME's position, 38 bytes, then the CRC.
TEST(Messages, OperatorCommandRoundTripKeepsTheRequestAndItsId) {
  drone_ros::OperatorCommand cmd;
  cmd.stamp = ros::Time(1700000000, 5);
  cmd.command = drone_ros::OperatorCommand::SELF_TEST;
  cmd.request_id = 4000000001u;
  cmd.use_current = true;
  cmd.latitude = 40.4237054;
  cmd.longitude = -86.9211946;
  cmd.altitude = 185.25;
  cmd.crc32 = 0xCAFEF00Du;
  EXPECT_EQ(HA_OPERATOR_COMMAND_FIELDS_LEN + 4u, serialize(cmd).size());
  EXPECT_EQ(cmd, roundTrip(cmd));  // every field
}

// The HA's link checks crc32 over the serialization before it (HA_OPERATOR_COMMAND_FIELDS_LEN
// bytes), and it must see any change there, however rosserial's 8-bit sum saw it.
TEST(OperatorCommandCrc, CoversEveryFieldByteBeforeItAndCatchesEveryFlippedBit) {
  drone_ros::OperatorCommand cmd;
  cmd.stamp = ros::Time(1700000000, 5);
  cmd.command = drone_ros::OperatorCommand::SET_HOME;
  cmd.request_id = 9;
  cmd.latitude = 40.4237054;
  cmd.longitude = -86.9211946;
  cmd.altitude = 185.25;
  auto bytes = serialize(cmd);
  ASSERT_EQ(HA_OPERATOR_COMMAND_FIELDS_LEN + 4u, bytes.size());
  const uint32_t good = ha_crc32(bytes.data(), HA_OPERATOR_COMMAND_FIELDS_LEN);
  for (unsigned bit = 0; bit < 8 * HA_OPERATOR_COMMAND_FIELDS_LEN; ++bit) {
    bytes[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_NE(good, ha_crc32(bytes.data(), HA_OPERATOR_COMMAND_FIELDS_LEN)) << "bit " << bit;
    bytes[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
  }
}

// The Due sends home in doubles: a float would put it a metre off.
TEST(Messages, HomePositionRoundTripKeepsFullDoublePrecision) {
  drone_ros::HomePosition home;
  home.stamp = ros::Time(1700000000, 7);
  home.seq = 3;
  home.latitude = 40.4237054;
  home.longitude = -86.9211946;
  home.altitude = 185.25;
  EXPECT_EQ(36u, serialize(home).size());
  EXPECT_EQ(home, roundTrip(home));  // every field
}

TEST(Messages, ReasonBitsAreDistinctSingleBits) {
  using S = drone_ros::DecisionStatus;
  const uint32_t bits[] = {
      S::REASON_NO_COMMAND,      S::REASON_DEADLINE_MISS, S::REASON_NOT_FINITE,
      S::REASON_ACTUATOR_REGION, S::REASON_ALPHA_BETA,    S::REASON_SENSOR_LINK,
      S::REASON_STALL,           S::REASON_CEILING,       S::REASON_STATE_REGION,
      S::REASON_FROZEN,          S::REASON_INTEGRITY,     S::REASON_ESTIMATOR,
      S::REASON_GROUND_COMMAND,  S::REASON_NO_HA_STATE,   S::REASON_PULL};
  uint32_t seen = 0;
  for (uint32_t b : bits) {
    EXPECT_EQ(0u, b & (b - 1)) << b << " is not a single bit";
    EXPECT_EQ(0u, seen & b) << b << " is used twice";
    seen |= b;
  }
}

TEST(Messages, OriginalThesisFieldsStillCompileAndRoundTrip) {
  // Written the way the thesis's controller node uses these messages; each comes back equal in
  // every field.
  drone_ros::pwm pwm;
  pwm.PICCIC = 1;
  pwm.Throttle = 0.4;
  pwm.Elevator = 0.1;
  pwm.Aileron = -0.2;
  pwm.Rudder = 0.05;
  pwm.velocity = 60.0;
  pwm.tach = 5200.0;
  pwm.usbstatus = 1;
  EXPECT_EQ(pwm, roundTrip(pwm));

  drone_ros::way way;
  ASSERT_EQ(32u, way.north.size());
  for (int w = 0; w < 32; ++w) {
    way.north[w] = 100.0 * w;
    way.east[w] = -50.0 * w;
    way.height[w] = 200.0;
    way.velocity[w] = 60.0;
  }
  way.fp = 32;
  EXPECT_EQ(way, roundTrip(way));

  drone_ros::ins ins;
  ins.time = 345600.25;
  ins.week = 2345;
  ins.usbstatus = 1;
  EXPECT_EQ(ins, roundTrip(ins));

  drone_ros::hil_data hil;
  hil.controller_elevator_output = 0.03;
  hil.waypoint_index = 7;
  hil.h_op = 250.0;
  EXPECT_EQ(hil, roundTrip(hil));

  drone_ros::data data;
  data.angle.x = 0.1;
  data.lla.y = -97.1;
  data.alphaest = 0.05;
  data.a_usbstatus = 1;
  data.v_usbstatus = 0;
  data.wind_est[2] = 1.5;
  data.mw_velocity[5] = 61.0;
  data.waypoint_index = 3;
  EXPECT_EQ(data, roundTrip(data));
}

TEST(Messages, Md5sumsArePinned) {
  const auto sums = pinned_md5sums(MD5SUMS_FILE);
  expectPinned<drone_ros::ins>(sums);
  expectPinned<drone_ros::pwm>(sums);
  expectPinned<drone_ros::way>(sums);
  expectPinned<drone_ros::data>(sums);
  expectPinned<drone_ros::hil_data>(sums);
  expectPinned<drone_ros::ServoCommand>(sums);
  expectPinned<drone_ros::DecisionStatus>(sums);
  expectPinned<drone_ros::HilTruth>(sums);
  expectPinned<drone_ros::OperatorCommand>(sums);
  expectPinned<drone_ros::HomePosition>(sums);
  expectPinned<drone_ros::LockstepStep>(sums);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
