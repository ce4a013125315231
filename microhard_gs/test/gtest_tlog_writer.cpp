// The telemetry log writer on real files: the record format pymavlink reads, the flush cadence,
// a respawned node continuing the log, and a disk that fills up or a path that cannot exist.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tlog_writer.h"

using namespace microhard_gs;

namespace {

std::string temp_dir() {
  char pattern[] = "/tmp/gtest_tlog_XXXXXX";
  const char* dir = mkdtemp(pattern);
  return dir ? dir : "";
}

std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

uint64_t be64(const std::vector<uint8_t>& b, size_t at) {
  uint64_t v = 0;
  for (size_t i = 0; i < 8; ++i) v = (v << 8) | b[at + i];
  return v;
}

const std::vector<uint8_t> kFrame{0xFD, 0x01, 0x00, 0x00, 0x07, 0x01, 0x01,
                                  0x00, 0x00, 0x00, 0x2A, 0x12, 0x34};

}  // namespace

TEST(TlogRecord, TimeIsBigEndianMicrosecondsTaggedWithTheDirectionThenTheFrame) {
  std::vector<uint8_t> out;
  uint64_t last = 0;
  const uint64_t t_us = 1795000000123456ULL;
  append_tlog_record(t_us, TlogDirection::kSent, kFrame.data(), kFrame.size(), &last, &out);
  append_tlog_record(t_us + 1000, TlogDirection::kReceived, kFrame.data(), 2, &last, &out);
  ASSERT_EQ(out.size(), 8 + kFrame.size() + 8 + 2);
  EXPECT_EQ(out[0], 0x00);  // big-endian: the most significant byte first
  EXPECT_EQ(be64(out, 0), (t_us & ~3ULL) | 3u);
  EXPECT_EQ(std::vector<uint8_t>(out.begin() + 8, out.begin() + 8 + kFrame.size()), kFrame);
  EXPECT_EQ(be64(out, 8 + kFrame.size()), (t_us + 1000) & ~3ULL);
}

TEST(TlogRecord, TimeNeverGoesBackwardsWhenTheClockIsSetBack) {
  std::vector<uint8_t> out;
  uint64_t last = 0;
  append_tlog_record(2000003, TlogDirection::kSent, kFrame.data(), 1, &last, &out);
  append_tlog_record(2000001, TlogDirection::kReceived, kFrame.data(), 1, &last, &out);  // tag 0
  append_tlog_record(1000000, TlogDirection::kReceived, kFrame.data(), 1, &last, &out);  // stepped
  const uint64_t a = be64(out, 0), b = be64(out, 9), c = be64(out, 18);
  EXPECT_EQ(a, 2000003u);
  EXPECT_GE(b, a);
  EXPECT_EQ(b & 3u, 0u);  // still a received frame
  EXPECT_GE(c, b);
}

TEST(TlogWriter, RecordsReachTheFileOnlyOnceTheFlushPeriodHasPassed) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/new/folder/flight.tlog";  // folders made on open
  {
    TlogWriter w(500);
    ASSERT_TRUE(w.open(path, 1000)) << w.error();
    w.add(1795000000000000ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
    w.flush_if_due(1499);
    EXPECT_TRUE(read_file(path).empty());  // within the period: buffered
    w.flush_if_due(1500);
    EXPECT_EQ(read_file(path).size(), 8 + kFrame.size());
    EXPECT_EQ(w.records_written(), 1u);
    w.add(1795000000100000ULL, TlogDirection::kReceived, kFrame.data(), kFrame.size());
  }  // closing writes the rest
  EXPECT_EQ(read_file(path).size(), 2 * (8 + kFrame.size()));
  {
    TlogWriter respawned(500);
    ASSERT_TRUE(respawned.open(path, 0));
    respawned.add(1795000000200000ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
  }
  const auto bytes = read_file(path);
  ASSERT_EQ(bytes.size(), 3 * (8 + kFrame.size()));  // appended, not overwritten
  EXPECT_EQ(be64(bytes, 2 * (8 + kFrame.size())), 1795000000200000ULL | 3u);
  std::filesystem::remove_all(dir);
}

TEST(TlogWriter, ABufferGrownPastItsBoundIsWrittenAtOnce) {
  const std::string dir = temp_dir();
  const std::string path = dir + "/flight.tlog";
  TlogWriter w(1000000);
  ASSERT_TRUE(w.open(path, 0));
  std::vector<uint8_t> big(280, 0xAB);
  size_t added = 0;
  while (added < TlogWriter::kMaxBufferBytes) {
    w.add(1795000000000000ULL, TlogDirection::kSent, big.data(), big.size());
    added += 8 + big.size();
  }
  EXPECT_EQ(read_file(path).size(), added);
  std::filesystem::remove_all(dir);
}

TEST(TlogWriter, AFullDiskStopsTheLogWithTheReasonAndCountsWhatIsLost) {
  TlogWriter w(500);
  ASSERT_TRUE(w.open("/dev/full", 0));  // every write: ENOSPC
  w.add(1795000000000000ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
  w.add(1795000000000001ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
  EXPECT_FALSE(w.failed());
  w.flush_if_due(600);
  EXPECT_TRUE(w.failed());
  EXPECT_FALSE(w.is_open());
  EXPECT_NE(w.error().find("/dev/full: write failed: No space left on device"), std::string::npos)
      << w.error();
  w.add(1795000000000002ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
  w.flush_if_due(2000);
  EXPECT_EQ(w.records_written(), 0u);
  EXPECT_EQ(w.records_lost(), 3u);
}

TEST(TlogWriter, APathThatCannotBeCreatedFailsToOpenWithTheReason) {
  const std::string dir = temp_dir();
  const std::string file = dir + "/a_file";
  std::ofstream(file) << "x";
  TlogWriter w(500);
  EXPECT_FALSE(w.open(file + "/flight.tlog", 0));  // under a regular file
  EXPECT_TRUE(w.failed());
  EXPECT_NE(w.error().find("flight.tlog"), std::string::npos) << w.error();
  EXPECT_NE(w.error().find("Not a directory"), std::string::npos) << w.error();
  w.add(1795000000000000ULL, TlogDirection::kSent, kFrame.data(), kFrame.size());
  EXPECT_EQ(w.records_lost(), 1u);
  std::filesystem::remove_all(dir);
}
