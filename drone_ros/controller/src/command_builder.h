// Turns one GNC step into the messages controller_<aircraft> publishes: the HP command with its
// sequence number and CRC (/servo_op), the ground telemetry (/data) and the HiL record (/to_hil).
#ifndef CONTROLLER_COMMAND_BUILDER_H
#define CONTROLLER_COMMAND_BUILDER_H

#include <drone_ros/ServoCommand.h>
#include <drone_ros/data.h>
#include <drone_ros/hil_data.h>
#include <ros/time.h>

#include "gnc.h"
#include "gnc_aircraft.h"
#include "sensor_board.h"

namespace controller {

// Never puts a NaN on the wire: a non-finite value (impossible from a correct GNC) makes the
// command neutral, with estimator_converged false so the HA refuses it.
drone_ros::ServoCommand build_servo_command(uint32_t seq, const ros::Time &stamp,
                                            const GncOutput &out, bool links_healthy,
                                            double throttle_min);

// The CRC the HA checks (common/src/hp_command.h), over the fields before crc32.
uint32_t servo_command_crc(const drone_ros::ServoCommand &cmd);

void fill_data(const SensorBoard &board, const GncOutput &out, bool hp_in_control,
               drone_ros::data *msg);

void fill_hil(const GncOutput &out, drone_ros::hil_data *msg);

}  // namespace controller

#endif
