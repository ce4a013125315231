#include "due_link.h"

#include <Arduino.h>
#include <string.h>

/* ha_surfaces.h is a core-internal C header without C++ guards. */
extern "C" {
#include "../core/ha_surfaces.h"
}
#include "../link/ha_link.h"
#include "due_ins_seam.h"
#include "due_config.h"

namespace {

#if DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_PROGRAMMING
/* UART0 through the 16U2. Its receive ring holds 128 bytes, about 5 ms at 250000 baud; loop()
 * drains it every pass, far more often. Its 128-byte transmit ring makes write() wait out the
 * rest of a period's 150-byte burst (about 0.9 ms), which the budget's margin covers. */
UARTClass &g_port = Serial;
#elif DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_NATIVE
Serial_ &g_port = SerialUSB;
#else
#error "DUE_HP_LINK_PORT must be DUE_HP_LINK_PORT_PROGRAMMING or DUE_HP_LINK_PORT_NATIVE (due_config.h)"
#endif

HaLink g_link;
HaInputs *g_inputs = nullptr;

/* Bytes handed to the link per loop; the port's buffer holds more, the next loop takes them. */
const size_t kMaxBytesPerPoll = 64u;
const double kRadPerDeg = 0.017453292519943295;

void link_write(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  (void)g_port.write(bytes, len);
}

void link_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  (void)ctx;
  ha_inputs_put_hp_command(g_inputs, cmd, arrival_us);
}

void link_operator(void *ctx, const drone_ros_OperatorCommand *cmd, uint32_t arrival_us) {
  (void)ctx;
  if (cmd->command == HA_OP_SET_HOME) {  // home is the INS adapter's, not the decision logic's
    const int r = due_ins_set_home(cmd->use_current ? 1u : 0u, cmd->latitude, cmd->longitude,
                                   cmd->altitude, arrival_us);
    (void)ha_link_log(&g_link, r == HA_INS_SET_HOME_OK ? ROSSERIAL_MSGS_LOG_INFO : ROSSERIAL_MSGS_LOG_WARN,
                      r == HA_INS_SET_HOME_OK ? "SET_HOME: home moved"
                      : r == HA_INS_SET_HOME_BAD_POSITION ? "SET_HOME refused: position out of range"
                                                          : "SET_HOME refused: not parked on the ground");
    return;
  }
  ha_inputs_put_operator(g_inputs, cmd->command, cmd->request_id);
}

}  // namespace

void due_link_begin(HaInputs *inputs) {
  g_inputs = inputs;
  g_port.begin(DUE_HP_LINK_BAUD); /* the native port ignores the rate */
  HaLinkCallbacks cb;
  cb.write = link_write;
  cb.on_command = link_command;
  cb.on_operator = link_operator;
  cb.on_param = nullptr;
  cb.ctx = nullptr;
  ha_link_init(&g_link, &cb);
}

void due_link_poll(uint32_t now_us) {
  uint8_t bytes[kMaxBytesPerPoll];
  size_t len = 0u;
  while (len < kMaxBytesPerPoll && g_port.available() > 0) {
    bytes[len++] = static_cast<uint8_t>(g_port.read());
  }
  if (len > 0u) {
    ha_link_receive(&g_link, bytes, len, now_us);
  }
  ha_link_poll(&g_link, now_us);
}

void due_link_publish(const HaAircraftConfig *cfg, const HaInputs *inputs, const HaOutputs *out,
                      uint32_t now_us) {
  if (!ha_link_connected(&g_link)) {
    return;
  }
  const HaRosTime stamp = ha_link_ros_time(&g_link, now_us);

  drone_ros_DecisionStatus status;
  status.stamp = stamp;
  status.controller = out->controller;
  status.reasons = out->reasons;
  status.reasons_at_switch = out->reasons_at_switch;
  status.restart_count = out->restart_count;
  status.restart_requested = out->restart_requested;
  status.last_seq = out->last_seq;
  status.stable_for_s = out->stable_for_s;
  status.airspeed_ftps = out->airspeed_ftps;
  status.altitude_agl_ft = out->altitude_agl_ft;
  status.alpha_deg = out->alpha_deg;
  status.beta_deg = out->beta_deg;
  status.state_region_max = out->state_region_max;
  status.actuator_region_max = out->actuator_region_max;
  status.throttle = out->surfaces.throttle;
  status.elevator_deg = out->surfaces.elevator_deg;
  status.aileron_deg = out->surfaces.aileron_deg;
  status.rudder_deg = out->surfaces.rudder_deg;
  (void)ha_link_publish_decision_status(&g_link, &status);

  // The HA owns home: the host hears it on a change and every few seconds, not every period.
  drone_ros_HomePosition home;
  memset(&home, 0, sizeof home);
  const HaIns *ins = due_ins_state();
  if (ins->home_latched) {
    home.stamp = stamp;
    home.seq = ins->home_seq;
    home.latitude = ins->home.lat_deg;
    home.longitude = ins->home.lon_deg;
    home.altitude = ins->home.alt_m;
  }
  (void)ha_link_offer_home(&g_link, &home, now_us);

  /* The pilot's sticks, decoded with the same calibration the core uses in manual mode. */
  HaSurfaces rc;
  ha_surfaces_from_rc(cfg, &inputs->rc, &rc);
  drone_ros_pwm pwm;
  pwm.header.seq = 0u;
  pwm.header.stamp = stamp;
  pwm.header.frame_id = ha_ros_string("");
  pwm.PICCIC = out->controller == HA_CONTROLLER_MANUAL ? 0u : 1u;
  pwm.Throttle = rc.throttle;
  pwm.Elevator = rc.elevator_deg * kRadPerDeg;
  pwm.Aileron = rc.aileron_deg * kRadPerDeg;
  pwm.Rudder = rc.rudder_deg * kRadPerDeg;
  pwm.velocity = out->airspeed_ftps;
  pwm.tach = 0.0; /* no tachometer on this board */
  pwm.usbstatus = 1u;
  (void)ha_link_publish_pwm(&g_link, &pwm);
}
