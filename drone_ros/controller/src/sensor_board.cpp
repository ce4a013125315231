#include "sensor_board.h"

#include "geo_wgs84.h"

#include <cmath>
#include <initializer_list>

namespace controller {
namespace {

bool finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) {
      return false;
    }
  }
  return true;
}

}  // namespace

const char *link_name(Link link) {
  switch (link) {
    case kLinkPwm:
      return "/pwm";
    case kLinkIns:
      return "/ins";
    case kLinkGpsPosition:
      return "/gps_position";
    case kLinkGpsVelocity:
      return "/gps_velocity";
    case kLinkImu:
      return "/imu_PQR_acceleration";
    case kLinkAttitude:
      return "/attitude";
    default:
      return "?";
  }
}

SensorBoard::SensorBoard(const ControllerParams &params)
    : params_(params),
      throttle_trim_(params.throttle_trim),
      elevator_trim_rad_(params.elevator_trim_rad),
      aileron_trim_rad_(params.aileron_trim_rad),
      rudder_trim_rad_(params.rudder_trim_rad) {}

void SensorBoard::apply_params(const ControllerParams &params) {
  // A trim set from the ground is the trim flown from now on (until the pilot next flies and
  // the RC positions are captured again); trims not touched keep whatever is in use.
  if (params.throttle_trim != params_.throttle_trim) throttle_trim_ = params.throttle_trim;
  if (params.elevator_trim_rad != params_.elevator_trim_rad)
    elevator_trim_rad_ = params.elevator_trim_rad;
  if (params.aileron_trim_rad != params_.aileron_trim_rad)
    aileron_trim_rad_ = params.aileron_trim_rad;
  if (params.rudder_trim_rad != params_.rudder_trim_rad) rudder_trim_rad_ = params.rudder_trim_rad;
  params_ = params;
}

void SensorBoard::arrived(Link link, double now_s) {
  arrival_s_[link] = now_s;
  seen_[link] = true;
  last_arrival_s_ = now_s;
}

bool SensorBoard::drop() {
  ++dropped_;
  return false;
}

template <typename Msg>
bool SensorBoard::take(const Msg &msg, std::initializer_list<double> values, Msg *slot, Link link,
                       double now_s) {
  if (!finite(values)) {
    return drop();
  }
  *slot = msg;
  arrived(link, now_s);
  return true;
}

bool SensorBoard::on_pwm(const drone_ros::pwm &msg, double now_s) {
  if (!finite({msg.Throttle, msg.Elevator, msg.Aileron, msg.Rudder, msg.velocity, msg.tach})) {
    return drop();
  }
  pwm_ = msg;
  if (msg.PICCIC == 0) {
    // The pilot is flying: whatever holds the aircraft now is the trim the computer starts from.
    throttle_trim_ = msg.Throttle;
    elevator_trim_rad_ = msg.Elevator;
    aileron_trim_rad_ = msg.Aileron;
    rudder_trim_rad_ = msg.Rudder;
  }
  arrived(kLinkPwm, now_s);
  return true;
}

bool SensorBoard::on_ins(const drone_ros::ins &msg, double now_s) {
  return take(msg, {msg.time}, &ins_, kLinkIns, now_s);
}

bool SensorBoard::all_seen() const {
  for (uint32_t i = 0; i < kLinkCount; ++i) {
    if (!seen_[i]) {
      return false;
    }
  }
  return true;
}

void SensorBoard::restamp_arrivals(double now_s) {
  for (uint32_t i = 0; i < kLinkCount; ++i) {
    if (seen_[i]) {
      arrival_s_[i] = now_s;
    }
  }
}

bool SensorBoard::on_home(double lat_deg, double lon_deg, double alt_m) {
  GeoRef judged;  // the HA's own test of a home, so no node keeps one the HA would refuse
  if (geo_ref_init(&judged, lat_deg, lon_deg, alt_m) == 0) {
    return drop();
  }
  home_valid_ = true;
  home_lat_deg_ = lat_deg;
  home_lon_deg_ = lon_deg;
  home_alt_m_ = alt_m;
  return true;
}

bool SensorBoard::on_gps_position(const sensor_msgs::NavSatFix &msg, double now_s) {
  return take(msg, {msg.latitude, msg.longitude, msg.altitude}, &gps_position_, kLinkGpsPosition,
              now_s);
}

bool SensorBoard::on_gps_velocity(const geometry_msgs::Twist &msg, double now_s) {
  return take(msg, {msg.linear.x, msg.linear.y, msg.linear.z}, &gps_velocity_, kLinkGpsVelocity,
              now_s);
}

bool SensorBoard::on_imu(const sensor_msgs::Imu &msg, double now_s) {
  return take(msg,
              {msg.angular_velocity.x, msg.angular_velocity.y, msg.angular_velocity.z,
               msg.linear_acceleration.x, msg.linear_acceleration.y, msg.linear_acceleration.z},
              &imu_, kLinkImu, now_s);
}

bool SensorBoard::on_attitude(const geometry_msgs::Point &msg, double now_s) {
  return take(msg, {msg.x, msg.y, msg.z}, &attitude_, kLinkAttitude, now_s);
}

bool SensorBoard::on_way(const drone_ros::way &msg) {
  bool ok = msg.fp >= 0 && msg.fp <= GNC_MAX_WAYPOINTS;
  for (int i = 0; ok && i < msg.fp; ++i) {
    ok = finite({msg.north[i], msg.east[i], msg.height[i], msg.velocity[i]});
  }
  if (!ok) {
    ++dropped_plans_;
    return drop();
  }
  way_ = msg;
  ++way_revision_;
  return true;
}

bool SensorBoard::on_pressure(double pressure_pa) {
  if (!std::isfinite(pressure_pa)) {
    return drop();
  }
  pressure_pa_ = pressure_pa;
  return true;
}

bool SensorBoard::on_battery(double voltage_v) {
  if (!std::isfinite(voltage_v)) {
    return drop();
  }
  voltage_v_ = voltage_v;
  return true;
}

uint32_t SensorBoard::unhealthy_links(double now_s) const {
  uint32_t mask = 0;
  for (uint32_t i = 0; i < kLinkCount; ++i) {
    if (!seen_[i] || now_s - arrival_s_[i] > params_.sensor_timeout_s) {
      mask |= 1u << i;
    }
  }
  // The nodes at the other end of the serial links say when their link is down.
  if (seen_[kLinkPwm] && pwm_.usbstatus != 1) {
    mask |= 1u << kLinkPwm;
  }
  if (seen_[kLinkIns] && ins_.usbstatus != 1) {
    mask |= 1u << kLinkIns;
  }
  return mask;
}

void SensorBoard::fill_input(GncInput *in) const {
  in->piccic = pwm_.PICCIC;
  in->airspeed_ftps = pwm_.velocity;
  in->throttle_trim = throttle_trim_;
  in->elevator_trim_rad = elevator_trim_rad_;
  in->aileron_trim_rad = aileron_trim_rad_;
  in->rudder_trim_rad = rudder_trim_rad_;
  in->lat_deg = gps_position_.latitude;
  in->lon_deg = gps_position_.longitude;
  in->alt_m = gps_position_.altitude;
  in->vel_north_mps = gps_velocity_.linear.x;
  in->vel_east_mps = gps_velocity_.linear.y;
  in->vel_down_mps = gps_velocity_.linear.z;
  in->p_radps = imu_.angular_velocity.x;
  in->q_radps = imu_.angular_velocity.y;
  in->r_radps = imu_.angular_velocity.z;
  in->fx_mps2 = imu_.linear_acceleration.x;
  in->fy_mps2 = imu_.linear_acceleration.y;
  in->fz_mps2 = imu_.linear_acceleration.z;
  in->phi_rad = attitude_.x;
  in->theta_rad = attitude_.y;
  in->psi_rad = attitude_.z;
  in->home_valid = home_valid_ ? 1 : 0;
  in->home_lat_deg = home_lat_deg_;
  in->home_lon_deg = home_lon_deg_;
  in->home_alt_m = home_alt_m_;
  in->home_cmd = params_.home_cmd ? 1 : 0;
  in->wp_count = way_.fp;
  for (int i = 0; i < GNC_MAX_WAYPOINTS; ++i) {
    in->wp_north_ft[i] = way_.north[i];
    in->wp_east_ft[i] = way_.east[i];
    in->wp_height_ft[i] = way_.height[i];
    in->wp_velocity_ftps[i] = way_.velocity[i];
  }
  in->wp_revision = way_revision_;
}

}  // namespace controller
