#include "ha_test_util.h"

#include <algorithm>
#include <cmath>

#include "hp_command.h"

HaHpCommand MakeCommand(uint32_t seq, float throttle, float elevator_deg, float aileron_deg,
                        float rudder_deg) {
  HaHpCommand c{};
  c.seq = seq;
  c.stamp_sec = 1700000000u + seq / 100u;
  c.stamp_nsec = (seq % 100u) * 10000000u;
  c.throttle = throttle;
  c.elevator_deg = elevator_deg;
  c.aileron_deg = aileron_deg;
  c.rudder_deg = rudder_deg;
  c.alpha_est_deg = 4.0f;
  c.beta_est_deg = 0.5f;
  c.estimator_converged = 1;
  c.sensor_links_healthy = 1;
  SealCommand(&c);
  return c;
}

void SealCommand(HaHpCommand* cmd) { cmd->crc32 = ha_hp_command_compute_crc(cmd); }

bool SurfacesFinite(const HaSurfaces& s) {
  return std::isfinite(s.throttle) && std::isfinite(s.elevator_deg) &&
         std::isfinite(s.aileron_deg) && std::isfinite(s.rudder_deg);
}

bool SurfacesInside(const HaAircraftConfig& cfg, const HaSurfaces& s) {
  return SurfacesFinite(s) && std::fabs(s.elevator_deg) <= cfg.elevator_limit_deg &&
         std::fabs(s.aileron_deg) <= cfg.aileron_limit_deg &&
         std::fabs(s.rudder_deg) <= cfg.rudder_limit_deg && s.throttle >= cfg.throttle_min &&
         s.throttle <= cfg.throttle_max;
}

Timeline::Timeline(const HaAircraftConfig& config) : cfg(config) {
  ha_app_init(&app, &cfg);
  board.now_us = 5000000u;  // not zero: time zero is not special to the core
  Cruise();
}

void WriteCruiseState(const HaAircraftConfig& cfg, HaInputs* in, uint32_t now_us,
                      float altitude_agl_ft, float airspeed_ftps) {
  in->roll_deg = 0.0f;
  in->pitch_deg = 2.0f;
  in->heading_deg = 90.0f;
  in->p_deg_s = in->q_deg_s = in->r_deg_s = 0.0f;
  in->altitude_agl_ft = altitude_agl_ft;
  in->north_ft = cfg.sc_circle_radius_ft;
  in->east_ft = 0.0f;
  in->groundspeed_ftps = airspeed_ftps;
  in->vel_north_ftps = 0.0f;  // heading 90: east, in still air
  in->vel_east_ftps = airspeed_ftps;
  in->climb_ftps = 0.0f;
  in->altitude_msl_ft = altitude_agl_ft;  // a field at sea level
  in->on_ground = 0;
  in->state_valid = 1;
  in->state_rx_us = now_us;
}

void Timeline::Cruise(float altitude_agl_ft, float airspeed_ftps) {
  WriteCruiseState(cfg, &app.inputs, board.now_us, altitude_agl_ft, airspeed_ftps);
  board.airspeed_ftps = airspeed_ftps;
}

void Timeline::Parked() {
  Cruise(0.0f, 0.0f);
  app.inputs.pitch_deg = 0.0f;
  app.inputs.on_ground = 1;
}

const HaOutputs& Timeline::Step() {
  board.now_us += cfg.period_us;
  if (refresh_state) {
    app.inputs.state_rx_us = board.now_us - cfg.period_us / 4u;
  }
  ha_app_period(&app, &board.iface);
  return app.outputs;
}

const HaOutputs& Timeline::StepWith(const HaHpCommand& cmd) {
  ha_inputs_put_hp_command(&app.inputs, &cmd, board.now_us + cfg.period_us / 2u);
  return Step();
}

const HaOutputs& Timeline::StepWithGood(float aileron_deg, float elevator_deg, float rudder_deg,
                                        float throttle) {
  return StepWith(MakeCommand(NextSeq(), throttle, elevator_deg, aileron_deg, rudder_deg));
}

int Timeline::ReachHp(int max_periods) {
  for (int i = 1; i <= max_periods; ++i) {
    if (StepWithGood().controller == HA_CONTROLLER_HP) {
      // Let the rate-limited handover finish so the HP's command passes unchanged.
      for (int j = 0; j < max_periods && app.core.transition_active; ++j) {
        StepWithGood();
      }
      return i;
    }
  }
  return -1;
}

void Timeline::Operator(uint8_t command) { ha_app_put_operator(&app, command, ++operator_id); }

namespace {
constexpr float kDegPerRad = 57.29578f;
constexpr float kG = 32.174f;
// Pitch minus flight path (the angle of attack) in level flight at kAlphaTrimFtps: the lift
// holds the weight times the load factor, so it goes as (kAlphaTrimFtps / V)^2 / cos(bank), and
// at a fixed pitch more thrust climbs rather than only speeding up.
constexpr float kAlphaTrimDeg =
    2.0f;  // the DG808 JSBSim model: 1.7 deg at 66 ft/s in a 20 deg bank
constexpr float kAlphaTrimFtps = 60.0f;

float AlphaDeg(float airspeed_ftps, float roll_deg) {
  const float r = kAlphaTrimFtps / airspeed_ftps;
  const float c = std::max(std::cos(roll_deg / kDegPerRad), 0.2f);
  return kAlphaTrimDeg * r * r / c;
}
}  // namespace

void PointMassAircraft::Step(const HaSurfaces& u, float dt) {
  // Roll: first-order rate response to aileron. Pitch: rate response to elevator (trailing
  // edge down pitches down) about a trim the integrator must learn: 0.6 deg trailing edge down,
  // where airframe.yaml's pitching moment trims the DG808 at cruise (cm0 0.045 against cm_alpha
  // at its 2 deg alpha), so the HA's elevator stop leaves it the pull the airframe has. The rate
  // a deflection buys grows with speed (the same alpha is more lift, q = g dn / V with dn ~ V^2).
  p_deg_s += dt * (4.0f * u.aileron_deg - p_deg_s) / 0.25f;
  const float q_per_deg = 2.0f * std::max(airspeed_ftps, 20.0f) / 60.0f;
  q_deg_s += dt * (q_per_deg * (0.6f - u.elevator_deg) - q_deg_s) / 0.3f;
  roll_deg += dt * p_deg_s;
  pitch_deg += dt * q_deg_s;
  const float gamma = (pitch_deg - AlphaDeg(airspeed_ftps, roll_deg)) / kDegPerRad;
  // Speed: electric motor thrust falling with speed, quadratic drag (L/D about 25), gravity.
  const float thrust = 9.5f * u.throttle * (1.0f - airspeed_ftps / 115.0f);
  const float drag = 0.00052f * airspeed_ftps * airspeed_ftps;
  airspeed_ftps += dt * (thrust - drag - kG * std::sin(gamma));
  if (airspeed_ftps < 5.0f) airspeed_ftps = 5.0f;
  altitude_ft += dt * airspeed_ftps * std::sin(gamma);
  const float turn_rate = kG * std::tan(roll_deg / kDegPerRad) / airspeed_ftps;  // rad/s
  r_deg_s = turn_rate * kDegPerRad * std::cos(roll_deg / kDegPerRad);
  heading_deg += dt * turn_rate * kDegPerRad;
  heading_deg = std::fmod(heading_deg + 360.0f, 360.0f);
  north_ft +=
      dt * (airspeed_ftps * std::cos(gamma) * std::cos(heading_deg / kDegPerRad) + wind_north_ftps);
  east_ft +=
      dt * (airspeed_ftps * std::cos(gamma) * std::sin(heading_deg / kDegPerRad) + wind_east_ftps);
}

void PointMassAircraft::WriteTo(HaInputs* in, uint32_t now_us) const {
  in->airspeed_ftps = airspeed_ftps;
  in->roll_deg = roll_deg;
  in->pitch_deg = pitch_deg;
  in->heading_deg = heading_deg;
  in->p_deg_s = p_deg_s;
  in->q_deg_s = q_deg_s;
  in->r_deg_s = r_deg_s;
  in->altitude_agl_ft = altitude_ft;
  in->north_ft = north_ft;
  in->east_ft = east_ft;
  // The velocity over the ground is the airspeed along the heading and flight path plus the wind.
  const float gamma = (pitch_deg - AlphaDeg(airspeed_ftps, roll_deg)) / kDegPerRad;
  const float air_ftps = airspeed_ftps * std::cos(gamma);
  in->vel_north_ftps = air_ftps * std::cos(heading_deg / kDegPerRad) + wind_north_ftps;
  in->vel_east_ftps = air_ftps * std::sin(heading_deg / kDegPerRad) + wind_east_ftps;
  in->groundspeed_ftps = std::hypot(in->vel_north_ftps, in->vel_east_ftps);
  in->climb_ftps = airspeed_ftps * std::sin(gamma);
  in->altitude_msl_ft = altitude_ft;
  in->on_ground = 0;
  in->state_valid = 1;
  in->state_rx_us = now_us;
}

HaAloneFlight::HaAloneFlight(uint32_t start_us, const HaAircraftConfig& config)
    : cfg(config), now_us(start_us) {
  ha_core_init(&core, &cfg);
}

void HaAloneFlight::StartOnTheCircle(float altitude_ft, float airspeed_ftps) {
  ac.north_ft = cfg.sc_circle_radius_ft;
  ac.heading_deg = 90.0f;
  ac.altitude_ft = altitude_ft;
  ac.airspeed_ftps = airspeed_ftps;
}

const HaOutputs& HaAloneFlight::Step() { return StepWithPitot(ac.airspeed_ftps); }

const HaOutputs& HaAloneFlight::StepWithPitot(float airspeed_ftps) {
  now_us += cfg.period_us;
  ac.WriteTo(&in, now_us);
  in.airspeed_ftps = airspeed_ftps;
  ha_core_step(&core, &in, now_us, &out);
  ac.Step(out.surfaces, PeriodS());
  return out;
}

float PointMassAircraft::DistanceFt() const { return std::hypot(north_ft, east_ft); }
