#include "link_params.h"

#include "drone_ros_common/serial_port.h"

namespace arduino_link {

namespace {
constexpr int kDueEraseBaud = 1200;
}  // namespace

bool read_link_params(const ros::NodeHandle &pnh, LinkParams *p, std::string *error) {
  pnh.param("port", p->port, p->port);
  pnh.param("baud", p->baud, p->baud);
  pnh.param("link_timeout_s", p->link_timeout_s, p->link_timeout_s);
  pnh.param("reopen_period_s", p->reopen_period_s, p->reopen_period_s);
  pnh.param("topic_request_period_s", p->topic_request_period_s, p->topic_request_period_s);
  pnh.param("frame_timeout_s", p->frame_timeout_s, p->frame_timeout_s);
  pnh.param("max_payload", p->max_payload, p->max_payload);
  pnh.param("lost_pwm_rate_hz", p->lost_pwm_rate_hz, p->lost_pwm_rate_hz);
  if (p->port.empty()) {
    *error = "~port is empty";
  } else if (!drone_ros_common::SerialPort::baud_supported(p->baud)) {
    *error = "~baud " + std::to_string(p->baud) + " is not a supported rate";
  } else if (p->baud == kDueEraseBaud) {
    // Opening and closing either Due port at 1200 baud erases the sketch: never the HA's.
    *error = "~baud 1200 would erase the Due's sketch (its bootloader's erase signal)";
  } else if (!(p->link_timeout_s > 0.0 && p->link_timeout_s < 60.0)) {
    *error = "~link_timeout_s must be in (0, 60)";
  } else if (!(p->reopen_period_s > 0.0 && p->reopen_period_s < 60.0)) {
    *error = "~reopen_period_s must be in (0, 60)";
  } else if (!(p->topic_request_period_s > 0.0 && p->topic_request_period_s < 60.0)) {
    *error = "~topic_request_period_s must be in (0, 60)";
  } else if (!(p->frame_timeout_s > 0.0 && p->frame_timeout_s < 5.0)) {
    *error = "~frame_timeout_s must be in (0, 5)";
  } else if (p->max_payload < 64 || p->max_payload > 65535) {
    *error = "~max_payload must be in [64, 65535]";
  } else if (!(p->lost_pwm_rate_hz > 0.0 && p->lost_pwm_rate_hz <= 100.0)) {
    *error = "~lost_pwm_rate_hz must be in (0, 100]";
  } else {
    return true;
  }
  return false;
}

}  // namespace arduino_link
