#include "command_builder.h"

#include <array>
#include <cmath>

#include <ros/serialization.h>

#include "hp_command.h"

namespace controller {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
constexpr double kStandardGravityMps2 = 9.80665;

}  // namespace

uint32_t servo_command_crc(const drone_ros::ServoCommand &cmd) {
  // The CRC covers the message's own ROS serialization (msg/ServoCommand.msg), so it is computed
  // from that, not from a second copy of the field list (the HA's is ha_link_command_from_msg).
  std::array<uint8_t, HA_HP_COMMAND_FIELDS_LEN + sizeof cmd.crc32> bytes{};
  static_assert(ros::message_traits::IsFixedSize<drone_ros::ServoCommand>::value,
                "ServoCommand is fixed size: its serialization is the 38 CRC'd bytes and the CRC");
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, cmd);
  return ha_crc32(bytes.data(), HA_HP_COMMAND_FIELDS_LEN);
}

drone_ros::ServoCommand build_servo_command(uint32_t seq, const ros::Time &stamp,
                                            const GncOutput &out, bool links_healthy,
                                            double throttle_min) {
  drone_ros::ServoCommand cmd;
  cmd.seq = seq;
  cmd.stamp = stamp;
  cmd.throttle = static_cast<float>(out.throttle);
  cmd.elevator_deg = static_cast<float>(out.elevator_rad * kRadToDeg);
  cmd.aileron_deg = static_cast<float>(out.aileron_rad * kRadToDeg);
  cmd.rudder_deg = static_cast<float>(out.rudder_rad * kRadToDeg);
  cmd.alpha_est_deg = static_cast<float>(out.alpha_est_rad * kRadToDeg);
  cmd.beta_est_deg = static_cast<float>(out.beta_est_rad * kRadToDeg);
  // The HA flies the command only if the GNC itself vouches for it.
  cmd.estimator_converged = out.estimator_converged != 0 && out.command_valid != 0;
  cmd.sensor_links_healthy = links_healthy && out.inputs_finite != 0;
  const float values[] = {cmd.throttle,   cmd.elevator_deg,  cmd.aileron_deg,
                          cmd.rudder_deg, cmd.alpha_est_deg, cmd.beta_est_deg};
  for (float v : values) {
    if (!std::isfinite(v)) {
      cmd.throttle = static_cast<float>(throttle_min);
      cmd.elevator_deg = cmd.aileron_deg = cmd.rudder_deg = 0.0f;
      cmd.alpha_est_deg = cmd.beta_est_deg = 0.0f;
      cmd.estimator_converged = false;
      break;
    }
  }
  cmd.crc32 = servo_command_crc(cmd);
  return cmd;
}

void fill_data(const SensorBoard &board, const GncOutput &out, bool hp_in_control,
               drone_ros::data *msg) {
  const auto &att = board.attitude();
  const auto &pos = board.gps_position();
  const auto &vel = board.gps_velocity();
  const auto &imu = board.imu();
  const auto &pwm = board.pwm();
  msg->angle.x = att.x;
  msg->angle.y = att.y;
  msg->angle.z = att.z;
  msg->lla.x = pos.latitude;
  msg->lla.y = pos.longitude;
  msg->lla.z = pos.altitude;
  msg->velocity.x = vel.linear.x;
  msg->velocity.y = vel.linear.y;
  msg->velocity.z = vel.linear.z;
  msg->angrate.x = imu.angular_velocity.x;
  msg->angrate.y = imu.angular_velocity.y;
  msg->angrate.z = imu.angular_velocity.z;
  msg->acceleration.x = imu.linear_acceleration.x / kStandardGravityMps2;
  msg->acceleration.y = imu.linear_acceleration.y / kStandardGravityMps2;
  msg->acceleration.z = imu.linear_acceleration.z / kStandardGravityMps2;
  msg->PICCIC = pwm.PICCIC;
  msg->HomeCmd = board.home_cmd() ? 1 : 0;
  msg->Throttle = pwm.Throttle;
  msg->Elevator = pwm.Elevator * kRadToDeg;
  msg->Aileron = pwm.Aileron * kRadToDeg;
  msg->Rudder = pwm.Rudder * kRadToDeg;
  msg->pressure = board.pressure_pa();
  msg->voltage = board.voltage_v();
  msg->air_velocity = pwm.velocity;
  msg->alphaest = out.alpha_est_rad;
  msg->betaest = out.beta_est_rad;
  msg->VTest = out.vt_est_ftps;
  msg->time = board.ins().time;
  msg->week = board.ins().week;
  msg->autothrottle = out.throttle;
  msg->autoelevator = out.elevator_rad * kRadToDeg;
  msg->autoaileron = out.aileron_rad * kRadToDeg;
  msg->autorudder = out.rudder_rad * kRadToDeg;
  msg->d2b = out.dist_to_waypoint_ft;
  msg->a_usbstatus = pwm.usbstatus;
  msg->v_usbstatus = board.ins().usbstatus;
  msg->guidance_VT = out.vt_cmd_ftps;
  msg->guidance_theta = out.theta_cmd_rad;
  msg->guidance_phi = out.phi_cmd_rad;
  msg->guidance_beta = out.beta_cmd_rad;
  msg->trackangles_etaLat = out.eta_lat_rad;
  msg->trackangles_etaLon = out.eta_lon_rad;
  msg->auto_switch = hp_in_control ? 0 : 1;
  // This GNC estimates air data only; attitude, rates, acceleration, position and velocity are
  // the INS solution it flies on, reported as such.
  msg->angles_est = {att.x, att.y, att.z};
  msg->brates_est = {imu.angular_velocity.x, imu.angular_velocity.y, imu.angular_velocity.z};
  msg->accel_est = {msg->acceleration.x, msg->acceleration.y, msg->acceleration.z};
  msg->pos_est = {pos.latitude, pos.longitude, pos.altitude};
  msg->vel_est = {vel.linear.x, vel.linear.y, vel.linear.z};
  msg->wind_est = {out.wind_north_ftps, out.wind_east_ftps, out.wind_up_ftps};
  msg->throttletrim = board.throttle_trim();
  msg->elevatortrim = board.elevator_trim_rad();
  msg->ailerontrim = board.aileron_trim_rad();
  msg->ruddertrim = board.rudder_trim_rad();
  msg->SAS_switch = 0;
  msg->delta_psi = out.delta_psi_rad;
  for (int i = 0; i < GNC_PREVIEW_WAYPOINTS && i < 6; ++i) {
    msg->mw_north[i] = out.mw_north_ft[i];
    msg->mw_east[i] = out.mw_east_ft[i];
    msg->mw_height[i] = out.mw_height_ft[i];
    msg->mw_velocity[i] = out.mw_velocity_ftps[i];
  }
  msg->n_op = out.n_op_ft;
  msg->e_op = out.e_op_ft;
  msg->h_op = out.h_op_ft;
  msg->waypoint_index = out.waypoint_index;
}

void fill_hil(const GncOutput &out, drone_ros::hil_data *msg) {
  msg->controller_throttle_output = out.throttle;
  msg->controller_elevator_output = out.elevator_rad;
  msg->controller_aileron_output = out.aileron_rad;
  msg->controller_rudder_output = out.rudder_rad;
  msg->dist_2_waypoint = out.dist_to_waypoint_ft;
  msg->waypoint_index = out.waypoint_index;
  msg->guidance_VT = out.vt_cmd_ftps;
  msg->guidance_phi = out.phi_cmd_rad;
  msg->guidance_theta = out.theta_cmd_rad;
  msg->eta_Lat = out.eta_lat_rad;
  msg->eta_Lon = out.eta_lon_rad;
  msg->n_op = out.n_op_ft;
  msg->e_op = out.e_op_ft;
  msg->h_op = out.h_op_ft;
}

}  // namespace controller
