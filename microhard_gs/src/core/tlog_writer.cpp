#include "tlog_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace microhard_gs {

void append_tlog_record(uint64_t unix_us, TlogDirection direction, const uint8_t* frame, size_t len,
                        uint64_t* last_us, std::vector<uint8_t>* out) {
  const uint64_t tag = static_cast<uint64_t>(direction);
  uint64_t t = (unix_us & ~uint64_t{3}) | tag;
  // Tagging moves a time by up to 3 us; keep the log in order all the same.
  while (t < *last_us) t += 4;
  *last_us = t;
  for (int shift = 56; shift >= 0; shift -= 8) out->push_back(static_cast<uint8_t>(t >> shift));
  out->insert(out->end(), frame, frame + len);
}

TlogWriter::TlogWriter(uint64_t flush_period_ms) : flush_period_ms_(flush_period_ms) {}

TlogWriter::~TlogWriter() {
  if (fd_ >= 0) {
    flush(last_flush_ms_);
    if (fd_ >= 0) ::close(fd_);
  }
}

void TlogWriter::fail(const std::string& what, int errno_value) {
  error_ = path_ + ": " + what + ": " + std::strerror(errno_value);
  records_lost_ += buffered_records_;
  buffered_records_ = 0;
  buffer_.clear();
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool TlogWriter::open(const std::string& path, uint64_t mono_ms) {
  path_ = path;
  last_flush_ms_ = mono_ms;
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (!folder.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) {
      fail("cannot create " + folder.string(), ec.value());
      return false;
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    fail("cannot open", errno);
    return false;
  }
  return true;
}

void TlogWriter::add(uint64_t unix_us, TlogDirection direction, const uint8_t* frame, size_t len) {
  if (fd_ < 0) {
    ++records_lost_;
    return;
  }
  append_tlog_record(unix_us, direction, frame, len, &last_us_, &buffer_);
  ++buffered_records_;
  if (buffer_.size() >= kMaxBufferBytes) flush(last_flush_ms_);
}

void TlogWriter::flush_if_due(uint64_t mono_ms) {
  if (fd_ >= 0 && mono_ms - last_flush_ms_ >= flush_period_ms_) flush(mono_ms);
}

bool TlogWriter::flush(uint64_t mono_ms) {
  if (fd_ < 0) return false;
  last_flush_ms_ = mono_ms;
  size_t done = 0;
  while (done < buffer_.size()) {
    const ssize_t n = ::write(fd_, buffer_.data() + done, buffer_.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      // A partial write leaves a cut record at the end; nothing follows it, so every reader
      // still gets every whole record before it.
      fail("write failed", n < 0 ? errno : ENOSPC);
      return false;
    }
    done += static_cast<size_t>(n);
  }
  bytes_written_ += buffer_.size();
  records_written_ += buffered_records_;
  buffered_records_ = 0;
  buffer_.clear();
  return true;
}

}  // namespace microhard_gs
