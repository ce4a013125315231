#include "ha_link_report.h"

#include <string.h>

#include "../core/ha_surfaces.h"

#define HA_REPORT_RAD_PER_DEG 0.017453292519943295

void ha_report_decision_status(const HaOutputs *out, HaRosTime stamp,
                               drone_ros_DecisionStatus *msg) {
  memset(msg, 0, sizeof *msg);
  msg->stamp = stamp;
  msg->controller = out->controller;
  msg->reasons = out->reasons;
  msg->reasons_at_switch = out->reasons_at_switch;
  msg->restart_count = out->restart_count;
  msg->restart_requested = out->restart_requested;
  msg->last_seq = out->last_seq;
  msg->stable_for_s = out->stable_for_s;
  msg->airspeed_ftps = out->airspeed_ftps;
  msg->altitude_agl_ft = out->altitude_agl_ft;
  msg->alpha_deg = out->alpha_deg;
  msg->beta_deg = out->beta_deg;
  msg->state_region_max = out->state_region_max;
  msg->actuator_region_max = out->actuator_region_max;
  msg->throttle = out->surfaces.throttle;
  msg->elevator_deg = out->surfaces.elevator_deg;
  msg->aileron_deg = out->surfaces.aileron_deg;
  msg->rudder_deg = out->surfaces.rudder_deg;
}

void ha_report_pwm(const HaAircraftConfig *cfg, const HaInputs *in, const HaOutputs *out,
                   HaRosTime stamp, drone_ros_pwm *msg) {
  HaSurfaces rc;
  ha_surfaces_from_rc(cfg, &in->rc, &rc);
  memset(msg, 0, sizeof *msg);
  msg->header.stamp = stamp;
  msg->header.frame_id = ha_ros_string("");
  msg->PICCIC = (uint8_t)(out->controller == HA_CONTROLLER_MANUAL ? 0u : 1u);
  msg->Throttle = rc.throttle;
  msg->Elevator = rc.elevator_deg * HA_REPORT_RAD_PER_DEG;
  msg->Aileron = rc.aileron_deg * HA_REPORT_RAD_PER_DEG;
  msg->Rudder = rc.rudder_deg * HA_REPORT_RAD_PER_DEG;
  msg->velocity = out->airspeed_ftps;
  msg->tach = 0.0; /* no tachometer on the HA */
  msg->usbstatus = 1u;
}

void ha_report_home(const HaIns *ins, HaRosTime stamp, drone_ros_HomePosition *msg) {
  memset(msg, 0, sizeof *msg);
  if (ins->home_latched) {
    msg->stamp = stamp;
    msg->seq = ins->home_seq;
    msg->latitude = ins->home.lat_deg;
    msg->longitude = ins->home.lon_deg;
    msg->altitude = ins->home.alt_m;
  }
}

void ha_link_report_period(HaLink *link, const HaAircraftConfig *cfg, const HaInputs *in,
                           const HaOutputs *out, const HaIns *ins, uint32_t now_us) {
  drone_ros_DecisionStatus status;
  drone_ros_pwm pwm;
  drone_ros_HomePosition home;
  HaRosTime stamp;
  if (!ha_link_connected(link)) {
    return;
  }
  stamp = ha_link_ros_time(link, now_us);
  ha_report_decision_status(out, stamp, &status);
  (void)ha_link_publish_decision_status(link, &status);
  ha_report_home(ins, stamp, &home);
  (void)ha_link_offer_home(link, &home, now_us);
  ha_report_pwm(cfg, in, out, stamp, &pwm);
  (void)ha_link_publish_pwm(link, &pwm);
}
