// The core's CONTROLLER_*, REASON_* and operator command numbers are the message contract's
// (msg/DecisionStatus.msg, msg/OperatorCommand.msg): the link copies them across unchanged.
#include <gtest/gtest.h>

#include <drone_ros/DecisionStatus.h>
#include <drone_ros/OperatorCommand.h>
#include <ros/serialization.h>

#include <vector>

#include "ha_core.h"

namespace {

using drone_ros::DecisionStatus;
using drone_ros::OperatorCommand;

TEST(HaMessageContract, ControllerAndReasonNumbersMatchDecisionStatus) {
  EXPECT_EQ(HA_CONTROLLER_HP, DecisionStatus::CONTROLLER_HP);
  EXPECT_EQ(HA_CONTROLLER_HA, DecisionStatus::CONTROLLER_HA);
  EXPECT_EQ(HA_CONTROLLER_RECOVERING, DecisionStatus::CONTROLLER_RECOVERING);
  EXPECT_EQ(HA_CONTROLLER_HA_LATCHED, DecisionStatus::CONTROLLER_HA_LATCHED);
  EXPECT_EQ(HA_CONTROLLER_MANUAL, DecisionStatus::CONTROLLER_MANUAL);
  EXPECT_EQ(HA_REASON_NO_COMMAND, DecisionStatus::REASON_NO_COMMAND);
  EXPECT_EQ(HA_REASON_DEADLINE_MISS, DecisionStatus::REASON_DEADLINE_MISS);
  EXPECT_EQ(HA_REASON_NOT_FINITE, DecisionStatus::REASON_NOT_FINITE);
  EXPECT_EQ(HA_REASON_ACTUATOR_REGION, DecisionStatus::REASON_ACTUATOR_REGION);
  EXPECT_EQ(HA_REASON_ALPHA_BETA, DecisionStatus::REASON_ALPHA_BETA);
  EXPECT_EQ(HA_REASON_SENSOR_LINK, DecisionStatus::REASON_SENSOR_LINK);
  EXPECT_EQ(HA_REASON_STALL, DecisionStatus::REASON_STALL);
  EXPECT_EQ(HA_REASON_CEILING, DecisionStatus::REASON_CEILING);
  EXPECT_EQ(HA_REASON_STATE_REGION, DecisionStatus::REASON_STATE_REGION);
  EXPECT_EQ(HA_REASON_FROZEN, DecisionStatus::REASON_FROZEN);
  EXPECT_EQ(HA_REASON_INTEGRITY, DecisionStatus::REASON_INTEGRITY);
  EXPECT_EQ(HA_REASON_ESTIMATOR, DecisionStatus::REASON_ESTIMATOR);
  EXPECT_EQ(HA_REASON_GROUND_COMMAND, DecisionStatus::REASON_GROUND_COMMAND);
  EXPECT_EQ(HA_REASON_NO_HA_STATE, DecisionStatus::REASON_NO_HA_STATE);
  EXPECT_EQ(HA_REASON_PULL, DecisionStatus::REASON_PULL);
}

TEST(HaMessageContract, OperatorCommandNumbersMatch) {
  EXPECT_EQ(HA_OP_SELECT_HP, OperatorCommand::SELECT_HP);
  EXPECT_EQ(HA_OP_SELECT_HA, OperatorCommand::SELECT_HA);
  EXPECT_EQ(HA_OP_RESTART_HP, OperatorCommand::RESTART_HP);
  EXPECT_EQ(HA_OP_SELF_TEST, OperatorCommand::SELF_TEST);
  EXPECT_EQ(HA_OP_SET_HOME, OperatorCommand::SET_HOME);
}

// The link checks an operator request's crc32 over the HA_OPERATOR_COMMAND_FIELDS_LEN bytes
// before it: every field of the message but the CRC, which comes last.
TEST(HaMessageContract, OperatorCommandCrcCoversEveryFieldBeforeIt) {
  OperatorCommand cmd;
  EXPECT_EQ(ros::serialization::serializationLength(cmd), HA_OPERATOR_COMMAND_FIELDS_LEN + 4u);
  cmd.crc32 = 0x01020304u;
  std::vector<uint8_t> raw(ros::serialization::serializationLength(cmd));
  ros::serialization::OStream out(raw.data(), static_cast<uint32_t>(raw.size()));
  ros::serialization::serialize(out, cmd);
  EXPECT_EQ(raw[HA_OPERATOR_COMMAND_FIELDS_LEN], 0x04);  // crc32 last, little endian
  EXPECT_EQ(raw[HA_OPERATOR_COMMAND_FIELDS_LEN + 3u], 0x01);
}

}  // namespace
