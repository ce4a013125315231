// Parse throughput of the VN-200 protocol core (framer + binary decoder), and the CPU share it
// takes at the sensor's maximum output. Prints `metric: value unit` lines, then the machine.
#include <sys/utsname.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "output_config.h"
#include "vn_binary.h"
#include "vn_framer.h"
#include "vn_packet_builder.h"

namespace {

struct Result {
  double mb_per_s;
  size_t frames;
};

// CPU time of the calling process, so a busy shared machine inflates the figure less.
double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

Result parse(const std::vector<uint8_t>& stream, size_t read_size, int repeats) {
  size_t frames = 0;
  volatile float sink = 0;
  const double t0 = cpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    VnFramer f;
    vn_framer_init(&f);
    for (size_t pos = 0; pos < stream.size(); pos += read_size) {
      const size_t n = std::min(read_size, stream.size() - pos);
      size_t off = 0;
      for (;;) {
        size_t used = 0;
        VnFrame fr;
        const int got = vn_framer_next(&f, stream.data() + pos + off, n - off, &used, &fr);
        off += used;
        if (!got) break;
        VnBinaryData d;
        if (vn_bin_decode(fr.data, fr.len, &d) == VN_BIN_OK) {
          ++frames;
          sink = sink + d.ypr_deg[0];
        }
      }
    }
  }
  const double dt = cpuSeconds() - t0;
  return {static_cast<double>(stream.size()) * repeats / dt / 1e6, frames};
}

std::vector<uint8_t> imuPacket(uint64_t t_ns) {
  // A lean 800 Hz stream: time, YPR, rates, acceleration, INS status (52 bytes).
  VnPacketBuilder b(VN_GROUP_COMMON,
                    {VN_COMMON_TIME_STARTUP | VN_COMMON_YPR | VN_COMMON_ANGULAR_RATE |
                     VN_COMMON_ACCEL | VN_COMMON_INS_STATUS});
  b.u64(t_ns).f32(1).f32(2).f32(3).f32(0.1f).f32(0.2f).f32(0.3f).f32(0).f32(0).f32(-9.81f).u16(2);
  return b.finish();
}

// Packets per CPU second through vn_bin_decode alone (no framer), the decoder's own cost.
double decodeRate(const std::vector<std::vector<uint8_t>>& packets, int repeats) {
  size_t ok = 0;
  volatile float sink = 0;
  const double t0 = cpuSeconds();
  for (int r = 0; r < repeats; ++r) {
    for (const std::vector<uint8_t>& p : packets) {
      VnBinaryData d;
      if (vn_bin_decode(p.data(), p.size(), &d) == VN_BIN_OK) {
        ++ok;
        sink = sink + d.ypr_deg[0];
      }
    }
  }
  const double dt = cpuSeconds() - t0;
  if (ok != packets.size() * static_cast<size_t>(repeats)) return 0.0;
  return static_cast<double>(ok) / dt;
}

// Every documented field of every group: the longest packet, where skipped fields dominate.
std::vector<uint8_t> everyFieldPacket(uint8_t seed) {
  std::vector<uint16_t> masks;
  size_t payload = 0;
  for (unsigned g = 0; g < VN_BIN_GROUP_COUNT; ++g) {
    uint16_t m = 0;
    for (unsigned b = 0; b < 16; ++b) {
      if (vn_bin_field_size(g, b) != 0) {
        m = static_cast<uint16_t>(m | (1u << b));
        payload += vn_bin_field_size(g, b);
      }
    }
    masks.push_back(m);
  }
  VnPacketBuilder b(static_cast<uint8_t>(VN_GROUPS_VALID), masks);
  // Bytes below 0x40 keep every float exponent finite.
  for (size_t i = 0; i < payload; ++i) b.u8(static_cast<uint8_t>((i * 13 + seed) & 0x3F));
  return b.finish();
}

std::string machine() {
  std::string model = "unknown cpu";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  utsname u{};
  uname(&u);
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores, " +
         u.sysname + " " + u.release;
}

}  // namespace

int main() {
  std::vector<uint8_t> node_stream, imu_stream;
  for (int i = 0; i < 20000; ++i) {
    std::vector<uint8_t> p = makeNodePacket(static_cast<float>(i % 360), 1000000ull * i);
    node_stream.insert(node_stream.end(), p.begin(), p.end());
    std::vector<uint8_t> q = imuPacket(1250000ull * i);
    imu_stream.insert(imu_stream.end(), q.begin(), q.end());
  }
  const size_t node_len = node_stream.size() / 20000, imu_len = imu_stream.size() / 20000;

  const Result node_big = parse(node_stream, 4096, 20);
  const Result node_small = parse(node_stream, 16, 20);
  const Result imu_big = parse(imu_stream, 4096, 40);
  if (node_big.frames != 20u * 20000u || imu_big.frames != 40u * 20000u) {
    std::fprintf(stderr, "bench: lost frames (%zu, %zu)\n", node_big.frames, imu_big.frames);
    return 1;
  }
  std::vector<std::vector<uint8_t>> node_packets, every_field_packets;
  for (int i = 0; i < 1000; ++i) {
    node_packets.push_back(makeNodePacket(static_cast<float>(i % 360), 1000000ull * i));
    every_field_packets.push_back(everyFieldPacket(static_cast<uint8_t>(i)));
  }
  const double node_decode_rate = decodeRate(node_packets, 400);
  const double every_field_decode_rate = decodeRate(every_field_packets, 100);
  if (node_decode_rate == 0.0 || every_field_decode_rate == 0.0) {
    std::fprintf(stderr, "bench: a packet did not decode\n");
    return 1;
  }
  // Sensor's maximum: 800 Hz binary packets; at 921600 baud (10 bits/byte) the link carries
  // 92160 B/s, so 800 Hz fits packets of up to 115 bytes.
  const double imu_800hz_Bps = 800.0 * static_cast<double>(imu_len);
  const double link_Bps = 921600.0 / 10.0;
  std::printf("vn200_parse_throughput_node_packets_4k_reads: %.1f MB/s\n", node_big.mb_per_s);
  std::printf("vn200_parse_throughput_node_packets_16B_reads: %.1f MB/s\n", node_small.mb_per_s);
  std::printf("vn200_parse_throughput_imu_packets_4k_reads: %.1f MB/s\n", imu_big.mb_per_s);
  std::printf("vn200_parse_time_per_node_packet: %.0f ns\n",
              1e9 * static_cast<double>(node_len) / (node_big.mb_per_s * 1e6));
  std::printf("vn200_decode_node_packets: %.0f packets/s\n", node_decode_rate);
  std::printf("vn200_decode_every_field_packets: %.0f packets/s\n", every_field_decode_rate);
  std::printf("vn200_node_packet_size: %zu bytes\n", node_len);
  std::printf("vn200_imu_packet_size: %zu bytes\n", imu_len);
  std::printf("vn200_cpu_share_800hz_imu_packets: %.4f %%\n",
              100.0 * imu_800hz_Bps / (imu_big.mb_per_s * 1e6));
  std::printf("vn200_cpu_share_saturated_921600_baud: %.4f %%\n",
              100.0 * link_Bps / (node_small.mb_per_s * 1e6));
  // The node's own packet is larger than 115 bytes, so it cannot stream at 800 Hz: the fastest
  // rate that is 800 Hz / integer and fits the link is what node_params.cpp lets through.
  unsigned node_max_hz = 0;
  for (unsigned divisor = 1; divisor <= 800 && node_max_hz == 0; ++divisor) {
    if (800 % divisor == 0 && (800.0 / divisor) * static_cast<double>(node_len) <= link_Bps) {
      node_max_hz = 800 / divisor;
    }
  }
  std::printf("vn200_node_packet_max_rate_at_921600_baud: %u Hz\n", node_max_hz);
  std::printf("machine: %s\n", machine().c_str());
  return 0;
}
