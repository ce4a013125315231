// MAVLink 2 message signing: the key, which messages may come unsigned, the signing clock.
#include "gs_core.h"

#include <cstring>

namespace microhard_gs {
namespace {

// MAVLink 2 signing timestamps count 10 us units since 2015-01-01T00:00:00Z.
constexpr uint64_t kSigningEpochUnixUs = 1420070400ULL * 1000000ULL;

// Messages that only read: accepted unsigned even when signing is on, so a GCS can still see
// the vehicle, its parameters and its mission. Everything else changes something and must be
// signed with the key.
bool accept_unsigned(const mavlink_status_t*, uint32_t msgid) {
  switch (msgid) {
    case MAVLINK_MSG_ID_HEARTBEAT:
    case MAVLINK_MSG_ID_SYSTEM_TIME:
    case MAVLINK_MSG_ID_PING:
    case MAVLINK_MSG_ID_PARAM_REQUEST_READ:
    case MAVLINK_MSG_ID_PARAM_REQUEST_LIST:
    case MAVLINK_MSG_ID_MISSION_REQUEST:
    case MAVLINK_MSG_ID_MISSION_REQUEST_LIST:
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT:
    case MAVLINK_MSG_ID_MISSION_ACK:
    case MAVLINK_MSG_ID_TIMESYNC:
    case MAVLINK_MSG_ID_RADIO_STATUS:
      return true;
    default:
      return false;
  }
}

}  // namespace

void GsCore::start_signing() {
  std::memcpy(signing_.secret_key, config_.signing_key.data(), sizeof signing_.secret_key);
  signing_.link_id = config_.signing_link_id;
  signing_.flags = MAVLINK_SIGNING_FLAG_SIGN_OUTGOING;
  signing_.accept_unsigned_callback = accept_unsigned;
  rx_status_.signing = &signing_;
  rx_status_.signing_streams = &signing_streams_;
  out_.status()->signing = &signing_;
  out_.status()->signing_streams = &signing_streams_;
}

void GsCore::update_signing_clock(const Clock& now) {
  if (!config_.signing || now.unix_us < kSigningEpochUnixUs) return;
  const uint64_t ts = (now.unix_us - kSigningEpochUnixUs) / 10;
  if (ts > signing_.timestamp) signing_.timestamp = ts;
}

}  // namespace microhard_gs
