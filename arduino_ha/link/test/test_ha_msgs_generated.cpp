// The generated device message code: md5sums equal the pinned ones (so the device and the host
// agree on every type), the rosserial protocol types match stock rosserial, and the bounded
// (de)serializers refuse what does not fit.
#include <gtest/gtest.h>

#include <string>

#include "ha_link_msgs.h"
#include "message_md5sums.h"

TEST(HaMsgsGenerated, DeviceMd5sumsEqualThePinnedOnes) {
  const auto sums = pinned_md5sums(MD5SUMS_FILE);
  ASSERT_FALSE(sums.empty());
  EXPECT_EQ(sums.at(DRONE_ROS_PWM_TYPE), DRONE_ROS_PWM_MD5);
  EXPECT_EQ(sums.at(DRONE_ROS_DECISIONSTATUS_TYPE), DRONE_ROS_DECISIONSTATUS_MD5);
  EXPECT_EQ(sums.at(DRONE_ROS_SERVOCOMMAND_TYPE), DRONE_ROS_SERVOCOMMAND_MD5);
  EXPECT_EQ(sums.at(DRONE_ROS_OPERATORCOMMAND_TYPE), DRONE_ROS_OPERATORCOMMAND_MD5);
}

TEST(HaMsgsGenerated, ProtocolTypesMatchStockRosserialAndStdMsgs) {
  EXPECT_STREQ(ROSSERIAL_MSGS_TOPICINFO_MD5, "0ad51f88fc44892f8c10684077646005");
  EXPECT_STREQ(ROSSERIAL_MSGS_LOG_MD5, "11abd731c25933261cd6183bd12d6295");
  EXPECT_STREQ(ROSSERIAL_MSGS_REQUESTPARAMREQUEST_MD5, "d7a0c2be00c9fd03cc69f2863de9c4d9");
  EXPECT_STREQ(STD_MSGS_TIME_MD5, "cd7166c74c552c311fbcc2fe5a7bc289");
  EXPECT_EQ(ROSSERIAL_MSGS_TOPICINFO_ID_TIME, 10);
  EXPECT_EQ(ROSSERIAL_MSGS_TOPICINFO_ID_TX_STOP, 11);
}

TEST(HaMsgsGenerated, DecisionStatusRoundTripKeepsEveryField) {
  drone_ros_DecisionStatus s{};
  s.stamp.sec = 12;
  s.controller = DRONE_ROS_DECISIONSTATUS_CONTROLLER_HA;
  s.reasons = DRONE_ROS_DECISIONSTATUS_REASON_FROZEN | DRONE_ROS_DECISIONSTATUS_REASON_INTEGRITY;
  s.last_seq = 99;
  s.rudder_deg = -4.5f;
  uint8_t buf[128];
  size_t n = 0, used = 0;
  ASSERT_TRUE(drone_ros_DecisionStatus_serialize(&s, buf, sizeof buf, &n));
  EXPECT_EQ(n, 68u);  // time 8, 1 + 4 + 4 + 2 + 1 + 4, eleven float32
  drone_ros_DecisionStatus back{};
  ASSERT_TRUE(drone_ros_DecisionStatus_deserialize(&back, buf, n, &used));
  EXPECT_EQ(used, n);
  EXPECT_EQ(back.reasons, 512u | 1024u);
  EXPECT_EQ(back.last_seq, 99u);
  EXPECT_FLOAT_EQ(back.rudder_deg, -4.5f);
}

TEST(HaMsgsGenerated, EveryTruncationIsRefusedAndEveryShortBufferToo) {
  drone_ros_pwm pwm{};
  pwm.header.frame_id = ha_ros_string("ha");
  uint8_t buf[128];
  size_t n = 0, used = 0;
  ASSERT_TRUE(drone_ros_pwm_serialize(&pwm, buf, sizeof buf, &n));
  for (size_t len = 0; len < n; ++len) {
    drone_ros_pwm back{};
    EXPECT_FALSE(drone_ros_pwm_deserialize(&back, buf, len, &used)) << len;
    size_t w = 0;
    EXPECT_FALSE(drone_ros_pwm_serialize(&pwm, buf, len, &w)) << len;
  }
}

TEST(HaMsgsGenerated, ArrayLongerThanTheDeviceCapacityIsRefused) {
  uint8_t wire[16] = {0};
  wire[0] = HA_MSGS_VAR_ARRAY_CAP + 1;  // ints count
  rosserial_msgs_RequestParamResponse r{};
  size_t used = 0;
  EXPECT_FALSE(rosserial_msgs_RequestParamResponse_deserialize(&r, wire, sizeof wire, &used));
  // A string claiming more bytes than remain is refused too.
  uint8_t log[] = {1, 200, 0, 0, 0, 'x'};
  rosserial_msgs_Log l{};
  EXPECT_FALSE(rosserial_msgs_Log_deserialize(&l, log, sizeof log, &used));
}

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
