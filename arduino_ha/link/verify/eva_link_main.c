/* Frama-C EVA driver for the Due's link: any bytes, in any chunking, at any (non-decreasing,
 * wrapping) time, over an unknown number of loop passes, plus publishing, logging and parameter
 * requests. `make verify-link` fails on any alarm. */
#include "__fc_builtin.h"
#include "ha_link.h"

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
  }
  return 0;
}
