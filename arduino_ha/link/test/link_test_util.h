// Helpers for the link tests of both ends (the device's here, the host framer's in
// drone_ros/arduino_link): frames built byte by byte from the rosserial protocol description
// (not with the code under test), and a capture of what the device writes.
#ifndef HA_LINK_TEST_UTIL_H
#define HA_LINK_TEST_UTIL_H

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ha_link_frame.h"
#include "hp_command.h"

namespace link_test {

using Bytes = std::vector<uint8_t>;

inline void put_u16(Bytes &b, uint16_t v) {
  b.push_back(static_cast<uint8_t>(v & 0xFF));
  b.push_back(static_cast<uint8_t>(v >> 8));
}
inline void put_u32(Bytes &b, uint32_t v) {
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<uint8_t>((v >> (8 * k)) & 0xFF));
}
inline void put_f32(Bytes &b, float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  put_u32(b, u);
}
inline void put_str(Bytes &b, const std::string &s) {
  put_u32(b, static_cast<uint32_t>(s.size()));
  b.insert(b.end(), s.begin(), s.end());
}

// 0xFF 0xFE len_lo len_hi (255-(len_lo+len_hi)%256) topic_lo topic_hi payload (255-(sum)%256)
inline Bytes frame(uint16_t topic, const Bytes &payload) {
  Bytes f{0xFF, 0xFE};
  put_u16(f, static_cast<uint16_t>(payload.size()));
  f.push_back(static_cast<uint8_t>(255 - ((f[2] + f[3]) % 256)));
  put_u16(f, topic);
  unsigned sum = f[5] + f[6];
  for (uint8_t p : payload) sum += p;
  f.insert(f.end(), payload.begin(), payload.end());
  f.push_back(static_cast<uint8_t>(255 - (sum % 256)));
  return f;
}

struct Cmd {
  uint32_t seq = 7, sec = 1700000000, nsec = 500;
  float throttle = 0.5f, elevator = -2.0f, aileron = 1.0f, rudder = 0.25f, alpha = 3.0f,
        beta = -0.5f;
  uint8_t converged = 1, healthy = 1;
  uint32_t crc = 0xA5A5A5A5u;
};

// msg/ServoCommand.msg field by field, little endian (42 bytes).
inline Bytes servo_command_payload(const Cmd &c) {
  Bytes b;
  put_u32(b, c.seq);
  put_u32(b, c.sec);
  put_u32(b, c.nsec);
  for (float f : {c.throttle, c.elevator, c.aileron, c.rudder, c.alpha, c.beta}) put_f32(b, f);
  b.push_back(c.converged);
  b.push_back(c.healthy);
  put_u32(b, c.crc);
  return b;
}

// msg/OperatorCommand.msg's fields up to use_current (stamp 5 s 6 ns): what every request
// carries before SET_HOME's position.
inline Bytes operator_fields(uint8_t command, uint32_t request_id) {
  Bytes b;
  put_u32(b, 5);
  put_u32(b, 6);
  b.push_back(command);
  put_u32(b, request_id);
  b.push_back(0);  // use_current
  return b;
}

// msg/OperatorCommand.msg's crc32 appended: CRC-32 over the fields' serialization before it.
inline Bytes sealed_operator_payload(Bytes fields) {
  put_u32(fields, ha_crc32(fields.data(), fields.size()));
  return fields;
}

// Splits what the device wrote back into frames with the device decoder.
struct Capture {
  Bytes bytes;
  static void write(void *ctx, const uint8_t *data, size_t len) {
    auto *self = static_cast<Capture *>(ctx);
    self->bytes.insert(self->bytes.end(), data, data + len);
  }
  std::vector<std::pair<uint16_t, Bytes>> frames() const {
    HaLinkDecoder dec;
    ha_link_decoder_init(&dec, 1000000u);
    std::vector<std::pair<uint16_t, Bytes>> out;
    for (uint8_t b : bytes) {
      HaLinkFrame f;
      ha_link_decoder_push(&dec, b, 0u);
      while (ha_link_decoder_next(&dec, &f)) {
        out.emplace_back(f.topic_id, Bytes(f.payload, f.payload + f.payload_len));
      }
    }
    return out;
  }
};

}  // namespace link_test

#endif
