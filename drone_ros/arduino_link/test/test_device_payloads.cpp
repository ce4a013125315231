// The reserved topics' payloads alone (no ROS): what a device announces, logs and asks for, built
// byte by byte from the message definitions (rosserial_msgs/TopicInfo, Log, RequestParam), and
// everything ROS would refuse refused here with a reason instead of thrown at the node.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "device_payloads.h"

using arduino_link::decode_device_log;
using arduino_link::decode_param_request;
using arduino_link::decode_topic_announcement;
using arduino_link::DeviceLog;
using arduino_link::encode_param_reply;
using arduino_link::ParamValues;
using arduino_link::TopicAnnouncement;
using Bytes = std::vector<uint8_t>;

namespace {

void put_u32(Bytes *b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b->push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void put_string(Bytes *b, const std::string &s) {
  put_u32(b, static_cast<uint32_t>(s.size()));
  b->insert(b->end(), s.begin(), s.end());
}
// uint16 topic_id, string topic_name, string message_type, string md5sum, int32 buffer_size.
Bytes topic_info(uint16_t id, const std::string &name, const std::string &type,
                 const std::string &md5, int32_t buffer_size = 512) {
  Bytes b{static_cast<uint8_t>(id & 0xFF), static_cast<uint8_t>(id >> 8)};
  put_string(&b, name);
  put_string(&b, type);
  put_string(&b, md5);
  put_u32(&b, static_cast<uint32_t>(buffer_size));
  return b;
}

const char kStringMd5[] = "992ce8a1687cec8c8bd883ec73ca41d1";  // std_msgs/String

bool refused(const Bytes &payload, std::string *why) {
  TopicAnnouncement a;
  return !decode_topic_announcement(payload, &a, why);
}

}  // namespace

TEST(DevicePayloads, AStockSketchsPublisherAnnouncementIsTakenWhole) {
  // ros_lib numbers the first publisher 125 (100 + 25 subscriber slots), buffer 512 on a Due.
  TopicAnnouncement a;
  std::string why;
  ASSERT_TRUE(decode_topic_announcement(topic_info(125, "chatter", "std_msgs/String", kStringMd5),
                                        &a, &why))
      << why;
  EXPECT_EQ(a.topic_id, 125);
  EXPECT_EQ(a.name, "chatter");
  EXPECT_EQ(a.type, "std_msgs/String");
  EXPECT_EQ(a.md5, kStringMd5);
  EXPECT_EQ(a.buffer_size, 512);
}

TEST(DevicePayloads, AnnouncementsRosWouldThrowOnAreRefusedWithAReason) {
  std::string why;
  EXPECT_TRUE(refused(topic_info(125, "", "std_msgs/String", kStringMd5), &why));
  EXPECT_EQ(why, "empty topic name");
  EXPECT_TRUE(refused(topic_info(125, "t", "*", "*"), &why));  // roscpp refuses '*' to advertise
  EXPECT_TRUE(refused(topic_info(125, "t", "", kStringMd5), &why));
  EXPECT_TRUE(refused(topic_info(125, "t", "std_msgs/String", ""), &why));
  EXPECT_TRUE(refused(topic_info(125, "t", "std_msgs/String", "*"), &why));
  EXPECT_TRUE(refused(topic_info(125, "t", "std_msgs/String", std::string(31, 'a') + "g"), &why));
  EXPECT_EQ(why, "md5sum is not 32 hex digits");
}

TEST(DevicePayloads, ReservedTopicIdsCannotBeAnnounced) {
  // Frames on 0..99 are rosserial's own; a topic there would never see its data.
  std::string why;
  for (uint16_t id : {0, 1, 6, 7, 10, 11, 99}) {
    EXPECT_TRUE(refused(topic_info(id, "t", "std_msgs/String", kStringMd5), &why)) << id;
  }
  TopicAnnouncement a;
  EXPECT_TRUE(
      decode_topic_announcement(topic_info(100, "t", "std_msgs/String", kStringMd5), &a, &why));
}

TEST(DevicePayloads, MessageTypesArePackageSlashMessage) {
  EXPECT_TRUE(arduino_link::is_message_type("std_msgs/String"));
  EXPECT_TRUE(arduino_link::is_message_type("drone_ros/pwm"));
  EXPECT_TRUE(arduino_link::is_message_type("a1/B_2"));
  for (const char *bad : {"", "/", "String", "std_msgs/", "/String", "std_msgs/String/x", "1pkg/M",
                          "pkg/1M", "pkg/M sg", "pkg/M!", "std msgs/String"}) {
    EXPECT_FALSE(arduino_link::is_message_type(bad)) << bad;
  }
}

TEST(DevicePayloads, EveryCutOrPaddedAnnouncementIsRefused) {
  const Bytes good = topic_info(126, "status", "std_msgs/String", kStringMd5);
  std::string why;
  for (std::size_t n = 0; n < good.size(); ++n) {
    EXPECT_TRUE(refused(Bytes(good.begin(), good.begin() + static_cast<long>(n)), &why)) << n;
  }
  Bytes padded = good;
  padded.push_back(0);
  EXPECT_TRUE(refused(padded, &why));
  EXPECT_EQ(why, "not a rosserial_msgs/TopicInfo");
  Bytes huge_len = good;
  huge_len[2] = 0xFF;  // topic_name's length far past the end
  huge_len[5] = 0x7F;
  EXPECT_TRUE(refused(huge_len, &why));
}

TEST(DevicePayloads, DeviceLogsDecodeAtEveryLevelAndTruncationsAreRefused) {
  for (uint8_t level = 0; level <= 4; ++level) {  // ROSDEBUG, INFO, WARN, ERROR, FATAL
    Bytes b{level};
    put_string(&b, "battery low");
    DeviceLog log;
    ASSERT_TRUE(decode_device_log(b, &log));
    EXPECT_EQ(log.level, level);
    EXPECT_EQ(log.text, "battery low");
    for (std::size_t n = 0; n < b.size(); ++n) {
      EXPECT_FALSE(decode_device_log(Bytes(b.begin(), b.begin() + static_cast<long>(n)), &log))
          << n;
    }
  }
}

TEST(DevicePayloads, ParameterRequestsCarryOneName) {
  Bytes b;
  put_string(&b, "/rate_hz");
  std::string name;
  ASSERT_TRUE(decode_param_request(b, &name));
  EXPECT_EQ(name, "/rate_hz");
  b.push_back(1);
  EXPECT_FALSE(decode_param_request(b, &name));
  EXPECT_FALSE(decode_param_request(Bytes{3, 0, 0}, &name));
}

TEST(DevicePayloads, ParameterRepliesHaveRosserialsLayout) {
  // int32[] ints, float32[] floats, string[] strings: each a uint32 count, then the items.
  ParamValues v;
  v.ints = {-2, 7};
  v.floats = {0.5f};
  v.strings = {"ab", ""};
  Bytes expected;
  put_u32(&expected, 2);
  put_u32(&expected, static_cast<uint32_t>(-2));
  put_u32(&expected, 7);
  put_u32(&expected, 1);
  uint32_t half;
  const float f = 0.5f;
  std::memcpy(&half, &f, 4);
  put_u32(&expected, half);
  put_u32(&expected, 2);
  put_string(&expected, "ab");
  put_string(&expected, "");
  Bytes payload;
  std::string why;
  ASSERT_TRUE(encode_param_reply(v, 1024, &payload, &why)) << why;
  EXPECT_EQ(payload, expected);
  // Not set (or not sendable): three empty arrays, which ros_lib reads as "length mismatch".
  ASSERT_TRUE(encode_param_reply(ParamValues{}, 1024, &payload, &why));
  EXPECT_EQ(payload, Bytes(12, 0));
}

TEST(DevicePayloads, ParameterRepliesTooBigForTheDeviceAreRefused) {
  ParamValues many;
  many.ints.assign(arduino_link::max_param_values_per_type() + 1, 1);
  Bytes payload;
  std::string why;
  EXPECT_FALSE(encode_param_reply(many, 1024, &payload, &why));
  ParamValues long_text;
  long_text.strings = {std::string(100, 'x')};
  EXPECT_FALSE(encode_param_reply(long_text, 64, &payload, &why));
  EXPECT_TRUE(encode_param_reply(long_text, 128, &payload, &why)) << why;
}
