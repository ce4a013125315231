// Builds VN-200 binary packets field by field, the way the sensor lays them out, so tests and the
// benchmark produce byte streams without a sensor. Independent of the decoder under test: it
// writes little-endian values and appends the big-endian CRC itself.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "vn_checksum.h"

class VnPacketBuilder {
 public:
  VnPacketBuilder(uint8_t groups, std::vector<uint16_t> masks_in_group_order) {
    bytes_.push_back(0xFA);
    bytes_.push_back(groups);
    for (uint16_t m : masks_in_group_order) u16(m);
  }
  VnPacketBuilder& u8(uint8_t v) {
    bytes_.push_back(v);
    return *this;
  }
  VnPacketBuilder& u16(uint16_t v) { return raw(&v, 2); }
  VnPacketBuilder& u32(uint32_t v) { return raw(&v, 4); }
  VnPacketBuilder& u64(uint64_t v) { return raw(&v, 8); }
  VnPacketBuilder& f32(float v) { return raw(&v, 4); }
  VnPacketBuilder& f64(double v) { return raw(&v, 8); }
  VnPacketBuilder& zeros(size_t n) {
    bytes_.insert(bytes_.end(), n, 0);
    return *this;
  }
  // Appends the CRC (big-endian, over everything after the sync) and returns the packet.
  std::vector<uint8_t> finish() const {
    std::vector<uint8_t> out = bytes_;
    uint16_t crc = vn_crc16(out.data() + 1, out.size() - 1);
    out.push_back(static_cast<uint8_t>(crc >> 8));
    out.push_back(static_cast<uint8_t>(crc & 0xFF));
    return out;
  }

 private:
  // Host is little-endian on every target we build for (x86-64, Cortex-M3), like the wire.
  VnPacketBuilder& raw(const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    bytes_.insert(bytes_.end(), b, b + n);
    return *this;
  }
  std::vector<uint8_t> bytes_;
};

// The packet the node configures, with distinctive values in every field, in manual order.
inline std::vector<uint8_t> makeNodePacket(float yaw_deg = 123.5f,
                                           uint64_t time_startup_ns = 1234567890123ull) {
  VnPacketBuilder b(0x39, {0x15FB, 0x0618, 0x0100, 0x0600});
  b.u64(time_startup_ns)            // TimeStartup [ns]
      .u64(1370000000123456789ull)  // TimeGps [ns]
      .f32(yaw_deg)
      .f32(-4.5f)
      .f32(1.25f)  // YPR [deg]
      .f32(0.1f)
      .f32(0.2f)
      .f32(0.3f)
      .f32(0.927362f)  // quaternion x y z w
      .f32(0.01f)
      .f32(-0.02f)
      .f32(0.03f)  // angular rate [rad/s]
      .f64(37.12345678)
      .f64(-121.98765432)
      .f64(123.456)  // LLA
      .f32(10.0f)
      .f32(-2.5f)
      .f32(0.125f)  // velocity NED [m/s]
      .f32(0.5f)
      .f32(-0.25f)
      .f32(-9.81f)  // accel [m/s^2]
      .f32(0.2f)
      .f32(0.0f)
      .f32(0.45f)
      .f32(31.5f)
      .f32(101.325f)  // mag, temp, pressure
      .u16(0x0206)    // INS status
      .u8(9)
      .u8(3)  // GPS NumSats, Fix
      .f32(1.5f)
      .f32(1.5f)
      .f32(3.0f)  // GPS PosU NED [m]
      .f32(0.2f)  // GPS VelU [m/s]
      .f32(0.5f)
      .f32(0.1f)
      .f32(0.1f)  // YprU [deg]
      .f32(2.5f)
      .f32(0.15f);  // INS PosU [m], VelU [m/s]
  return b.finish();
}
