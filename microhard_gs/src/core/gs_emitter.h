// What every ground-station service sends through: the vehicle's MAVLink ids, the link's
// sequence and signing state, and the queue of frames the node writes out. One per GsCore, so
// the services' messages share one sequence and one signing stream, as one vehicle's must.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mavlink_all.h"

namespace microhard_gs {

class Emitter {
 public:
  Emitter(uint8_t system_id, uint8_t component_id)
      : system_id_(system_id), component_id_(component_id) {}
  Emitter(const Emitter&) = delete;
  Emitter& operator=(const Emitter&) = delete;

  uint8_t system_id() const { return system_id_; }
  uint8_t component_id() const { return component_id_; }
  // The sending side's state, for the _encode_status calls (sequence, signing).
  mavlink_status_t* status() { return &status_; }

  // Encodes one message (encode fills it, with the ids and status() above) and queues its frame.
  template <typename Encode>
  void emit(Encode encode) {
    mavlink_message_t msg;
    encode(&msg);
    uint8_t buf[MAVLINK_MAX_PACKET_LEN];
    const uint16_t n = mavlink_msg_to_send_buffer(buf, &msg);
    frames_.emplace_back(buf, buf + n);
  }
  // A STATUSTEXT; a text of 50 characters or more goes in chunks sharing a non-zero id.
  void statustext(uint8_t severity, const std::string& text);

  std::vector<std::vector<uint8_t>> take_frames();

 private:
  uint8_t system_id_;
  uint8_t component_id_;
  mavlink_status_t status_{};
  uint16_t statustext_id_ = 0;
  std::vector<std::vector<uint8_t>> frames_;
};

}  // namespace microhard_gs
