// The HA's view of a ServoCommand, field by field as the Due's link decodes it
// (arduino_ha/src/link ha_link_command_from_msg), for the host tests that check the controller
// and the HA compute the same CRC (test/test_messages.cpp, drone_ros/controller/test).
#pragma once

#include <drone_ros/ServoCommand.h>

#include "hp_command.h"

inline HaHpCommand servo_command_as_ha(const drone_ros::ServoCommand& cmd) {
  HaHpCommand ha = {};
  ha.seq = cmd.seq;
  ha.stamp_sec = cmd.stamp.sec;
  ha.stamp_nsec = cmd.stamp.nsec;
  ha.throttle = cmd.throttle;
  ha.elevator_deg = cmd.elevator_deg;
  ha.aileron_deg = cmd.aileron_deg;
  ha.rudder_deg = cmd.rudder_deg;
  ha.alpha_est_deg = cmd.alpha_est_deg;
  ha.beta_est_deg = cmd.beta_est_deg;
  ha.estimator_converged = cmd.estimator_converged ? 1 : 0;
  ha.sensor_links_healthy = cmd.sensor_links_healthy ? 1 : 0;
  ha.crc32 = cmd.crc32;
  return ha;
}
