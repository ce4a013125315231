#include "output_config.h"

namespace vn200 {

VnBinaryOutputConfig node_output_config(unsigned rate_hz, VnAsyncMode port, unsigned output) {
  VnBinaryOutputConfig cfg{};
  cfg.output = static_cast<uint8_t>(output);
  cfg.async_mode = static_cast<uint8_t>(port);
  cfg.rate_divisor =
      static_cast<uint16_t>(rate_supported(rate_hz) ? VN_BINARY_BASE_RATE_HZ / rate_hz : 0u);
  cfg.groups = VN_GROUP_COMMON | VN_GROUP_GPS | VN_GROUP_ATTITUDE | VN_GROUP_INS;
  cfg.masks[0] = VN_COMMON_TIME_STARTUP | VN_COMMON_TIME_GPS | VN_COMMON_YPR |
                 VN_COMMON_QUATERNION | VN_COMMON_ANGULAR_RATE | VN_COMMON_POSITION |
                 VN_COMMON_VELOCITY | VN_COMMON_ACCEL | VN_COMMON_MAG_PRES | VN_COMMON_INS_STATUS;
  cfg.masks[3] = VN_GPS_NUM_SATS | VN_GPS_FIX | VN_GPS_POS_U | VN_GPS_VEL_U;
  cfg.masks[4] = VN_ATT_YPR_U;
  cfg.masks[5] = VN_INS_POS_U | VN_INS_VEL_U;
  return cfg;
}

bool rate_supported(unsigned rate_hz) {
  return rate_hz >= 1 && rate_hz <= VN_BINARY_BASE_RATE_HZ && VN_BINARY_BASE_RATE_HZ % rate_hz == 0;
}

double stream_bits_per_second(const VnBinaryOutputConfig& cfg, unsigned rate_hz) {
  return 10.0 * static_cast<double>(vn_binary_output_packet_len(&cfg)) * rate_hz;
}

}  // namespace vn200
