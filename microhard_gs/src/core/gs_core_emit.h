// GsCore::emit, shared by the units that make GsCore (one per MAVLink microservice): encodes one
// message with the vehicle's ids and signing state and queues its frame.
#pragma once

#include "gs_core.h"

namespace microhard_gs {

template <typename Encode>
void GsCore::emit(Encode encode) {
  mavlink_message_t msg;
  encode(&msg);
  uint8_t buf[MAVLINK_MAX_PACKET_LEN];
  const uint16_t n = mavlink_msg_to_send_buffer(buf, &msg);
  frames_.emplace_back(buf, buf + n);
}

}  // namespace microhard_gs
