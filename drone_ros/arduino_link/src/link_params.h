// The `arduino` node's private parameters, read and validated in one place.
#ifndef ARDUINO_LINK_LINK_PARAMS_H
#define ARDUINO_LINK_LINK_PARAMS_H

#include <ros/node_handle.h>

#include <string>

namespace arduino_link {

struct LinkParams {
  std::string port = "/dev/ttyACM0";
  int baud = 250000;             // programming port (16U2 USB-serial); the native port ignores it
  double link_timeout_s = 1.0;   // no valid frame for this long: link lost
  double reopen_period_s = 0.5;  // how often to retry opening a missing port
  double topic_request_period_s = 1.0;  // re-ask for topics while the device is silent
  double frame_timeout_s = 0.05;        // a started frame must complete within this
  int max_payload = 1024;               // longer announced frames are corruption
  double lost_pwm_rate_hz = 10.0;       // /pwm with usbstatus 0 while the link is down
};

// Reads ~port, ~baud, ... ; false (with the reason in *error) if any value is unusable.
bool read_link_params(const ros::NodeHandle &pnh, LinkParams *params, std::string *error);

}  // namespace arduino_link

#endif
