/* Frama-C EVA driver for the Due's link: any bytes, in any chunking, at any (non-decreasing,
 * wrapping) time, over an unknown number of loop passes, plus publishing, logging and parameter
 * requests, and the period's reports (ha_link_report_period) from any core outputs, RC pulses
 * and home. `make verify-link` fails on any alarm. */
#include "__fc_builtin.h"
#include "ha_aircraft.h"
#include "ha_link.h"
#include "ha_link_report.h"

/* The core's outputs are finite (ha_core.h); everything else any value its type holds. */
static void any_report_inputs(HaInputs *in, HaOutputs *out, HaIns *ins) {
  size_t k;
  out->controller = Frama_C_unsigned_char_interval(0u, 255u);
  out->reasons = Frama_C_unsigned_int_interval(0u, 0xFFFFFFFFu);
  out->airspeed_ftps = Frama_C_float_interval(-1e6f, 1e6f);
  out->stable_for_s = Frama_C_float_interval(0.0f, 1e9f);
  out->surfaces.throttle = Frama_C_float_interval(0.0f, 1.0f);
  out->surfaces.elevator_deg = Frama_C_float_interval(-90.0f, 90.0f);
  in->rc.valid = Frama_C_unsigned_char_interval(0u, 255u);
  for (k = 0u; k < HA_RC_CHANNELS; ++k) {
    in->rc.pulse_us[k] = (uint16_t)Frama_C_unsigned_int_interval(0u, 0xFFFFu);
  }
  ins->home_latched = Frama_C_unsigned_char_interval(0u, 1u);
  ins->home_seq = Frama_C_unsigned_int_interval(0u, 0xFFFFFFFFu);
  ins->home.lat_deg = Frama_C_double_interval(-90.0, 90.0);
  ins->home.lon_deg = Frama_C_double_interval(-180.0, 180.0);
  ins->home.alt_m = Frama_C_double_interval(-1e4, 1e5);
}

static void sink(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  (void)bytes;
  (void)len;
}

static void on_command(void *ctx, const HaHpCommand *cmd, uint32_t at_us) {
  (void)ctx;
  (void)at_us;
  (void)ha_hp_command_compute_crc(cmd);
}

static void on_param(void *ctx, const rosserial_msgs_RequestParamResponse *reply) {
  (void)ctx;
  (void)reply;
}

int main(void) {
  static HaLink link;
  static uint8_t buf[32];
  HaLinkCallbacks cb;
  uint32_t now_us = Frama_C_unsigned_int_interval(0u, 0xFFFFFFFFu);
  cb.write = sink;
  cb.on_command = on_command;
  cb.on_operator = 0;
  cb.on_param = on_param;
  cb.ctx = 0;
  ha_link_init(&link, &cb);
  while (Frama_C_nondet(0, 1)) {
    size_t i;
    const size_t n = Frama_C_unsigned_int_interval(0u, sizeof buf);
    for (i = 0u; i < sizeof buf; ++i) {
      buf[i] = Frama_C_unsigned_char_interval(0u, 255u);
    }
    now_us += Frama_C_unsigned_int_interval(0u, 100000u);
    ha_link_receive(&link, buf, n, now_us);
    ha_link_poll(&link, now_us);
    {
      drone_ros_pwm pwm = {0};
      drone_ros_DecisionStatus st = {0};
      pwm.header.stamp = ha_link_ros_time(&link, now_us);
      pwm.velocity = Frama_C_double_interval(-1e6, 1e6);
      st.reasons = Frama_C_unsigned_int_interval(0u, 0xFFFFFFFFu);
      (void)ha_link_publish_pwm(&link, &pwm);
      (void)ha_link_publish_decision_status(&link, &st);
      (void)ha_link_log(&link, ROSSERIAL_MSGS_LOG_WARN, "eva");
      (void)ha_link_request_param(&link, "rate_hz");
    }
    {
      static HaInputs in;
      static HaOutputs out;
      static HaIns ins;
      any_report_inputs(&in, &out, &ins);
      ha_link_report_period(&link, &ha_aircraft_config, &in, &out, &ins, now_us);
    }
  }
  return 0;
}
