// libFuzzer harness for the host framer: arbitrary bytes in arbitrary splits. Every frame it
// returns must be within the payload limit and must come back identical when re-encoded and
// parsed again; what it holds between calls stays within one frame; until a timeout drops held
// bytes, every byte is accounted for once (in a frame, skipped, a failure's sync byte, or held);
// nothing may crash, leak or hit UB (ASan + UBSan).
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "rosserial_framer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  constexpr std::size_t kMaxPayload = 1024;
  arduino_link::RosserialFramer framer(kMaxPayload, 0.05);
  std::vector<arduino_link::Frame> frames;
  double now_s = 0.0;
  std::size_t pos = 0;
  while (pos < size) {
    const std::size_t chunk = 1 + data[pos] % 97;
    const std::size_t n = chunk < size - pos ? chunk : size - pos;
    framer.feed(data + pos, n, now_s, &frames);
    if (framer.bytes_held() > kMaxPayload + 7) std::abort();
    std::size_t in_frames = 0;
    for (const auto &f : frames) in_frames += f.payload.size() + 8;
    const auto &c = framer.counters();
    if (c.timeouts == 0 &&
        in_frames + c.bytes_skipped + c.dropped() + framer.bytes_held() != pos + n)
      std::abort();
    now_s += data[pos] * 0.001;
    framer.poll(now_s);
    pos += n;
  }
  for (const auto &f : frames) {
    if (f.payload.size() > kMaxPayload) std::abort();
    const auto again = arduino_link::encode_frame(f.topic_id, f.payload.data(), f.payload.size());
    arduino_link::RosserialFramer check(kMaxPayload, 0.05);
    std::vector<arduino_link::Frame> back;
    check.feed(again.data(), again.size(), 0.0, &back);
    if (back.size() != 1 || back[0].topic_id != f.topic_id || back[0].payload != f.payload)
      std::abort();
  }
  const auto &c = framer.counters();
  if (c.frames_ok != frames.size()) std::abort();
  return 0;
}
