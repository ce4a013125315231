// The vehicle side's MAVLink telemetry log (.tlog), in the format MAVProxy and QGroundControl
// write and MAVExplorer, pymavlink and QGroundControl's replay read: for each frame, its time
// (8 bytes, big-endian, microseconds since the Unix epoch) followed by the frame's bytes as they
// went over the link. No ROS here: bytes and time in, a file out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace microhard_gs {

// The low two bits of a record's time say which way the frame went, the way MAVProxy marks them
// (pymavlink reads them as the record's link number): 3 for what the logger itself sent, the
// link number (0, the one link) for what it received. MAVExplorer tells directions apart so.
enum class TlogDirection : uint8_t { kReceived = 0, kSent = 3 };

// One record: the tagged time and the frame, appended to `out`. Times never go backwards in the
// log (a wall clock stepped back by NTP would otherwise reorder MAVExplorer's time axis):
// `last_us` is the last record's time, updated.
void append_tlog_record(uint64_t unix_us, TlogDirection direction, const uint8_t* frame, size_t len,
                        uint64_t* last_us, std::vector<uint8_t>* out);

class TlogWriter {
 public:
  // Records are buffered and written together every flush_period_ms (and when the buffer
  // grows past kMaxBufferBytes): one write(2) of whole records, so a crash of the process
  // loses at most that period, and a log cut short ends on a record boundary.
  explicit TlogWriter(uint64_t flush_period_ms);
  ~TlogWriter();  // writes what is buffered
  TlogWriter(const TlogWriter&) = delete;
  TlogWriter& operator=(const TlogWriter&) = delete;

  // Opens `path` for appending, creating missing folders: a node respawned in flight continues
  // the same log, and a tlog is a plain sequence of records. False (see error()) on failure.
  bool open(const std::string& path, uint64_t mono_ms);
  // Buffers one frame. After a failure nothing more is written; the frame is counted lost.
  void add(uint64_t unix_us, TlogDirection direction, const uint8_t* frame, size_t len);
  // Writes the buffer if flush_period_ms has passed since the last write.
  void flush_if_due(uint64_t mono_ms);
  // Writes the buffer now. False on a failed write (disk full, device gone): the file is closed,
  // error() says why, and the buffered records are counted lost.
  bool flush(uint64_t mono_ms);

  bool is_open() const { return fd_ >= 0; }
  bool failed() const { return !error_.empty(); }
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }
  uint64_t records_written() const { return records_written_; }
  uint64_t records_lost() const { return records_lost_; }
  uint64_t bytes_written() const { return bytes_written_; }

  static constexpr size_t kMaxBufferBytes = 64 * 1024;

 private:
  void fail(const std::string& what, int errno_value);

  const uint64_t flush_period_ms_;
  int fd_ = -1;
  std::string path_;
  std::string error_;
  std::vector<uint8_t> buffer_;
  uint64_t buffered_records_ = 0;
  uint64_t last_us_ = 0;
  uint64_t last_flush_ms_ = 0;
  uint64_t records_written_ = 0;
  uint64_t records_lost_ = 0;
  uint64_t bytes_written_ = 0;
};

}  // namespace microhard_gs
