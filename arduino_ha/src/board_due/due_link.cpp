#include "due_link.h"

#include <Arduino.h>

#include "../link/ha_link.h"
#include "../link/ha_link_report.h"
#include "due_config.h"
#include "due_ins_seam.h"

namespace {

#if DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_PROGRAMMING
/* UART0 through the 16U2. Its receive ring holds 128 bytes, about 5 ms at 250000 baud; loop()
 * drains it every pass, far more often. Its 128-byte transmit ring makes write() wait out the
 * rest of a period's 150-byte burst (about 0.9 ms), which the budget's margin covers. */
UARTClass &g_port = Serial;
#elif DUE_HP_LINK_PORT == DUE_HP_LINK_PORT_NATIVE
Serial_ &g_port = SerialUSB;
#else
#error \
    "DUE_HP_LINK_PORT must be DUE_HP_LINK_PORT_PROGRAMMING or DUE_HP_LINK_PORT_NATIVE (due_config.h)"
#endif

HaLink g_link;
HaInputs *g_inputs = nullptr;
const HaOutputs *g_outputs = nullptr;

/* Bytes handed to the link per loop; the port's buffer holds more, the next loop takes them. */
const size_t kMaxBytesPerPoll = 64u;

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
    (void)arrival_us;
    const int r = due_ins_set_home(g_outputs->on_ground, cmd->use_current ? 1u : 0u, cmd->latitude,
                                   cmd->longitude, cmd->altitude);
    (void)ha_link_log(
        &g_link, r == HA_INS_SET_HOME_OK ? ROSSERIAL_MSGS_LOG_INFO : ROSSERIAL_MSGS_LOG_WARN,
        r == HA_INS_SET_HOME_OK             ? "SET_HOME: home moved"
        : r == HA_INS_SET_HOME_BAD_POSITION ? "SET_HOME refused: position out of range"
                                            : "SET_HOME refused: not parked on the ground");
    return;
  }
  ha_inputs_put_operator(g_inputs, cmd->command, cmd->request_id);
}

}  // namespace

void due_link_begin(HaInputs *inputs, const HaOutputs *outputs) {
  g_inputs = inputs;
  g_outputs = outputs;
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
  ha_link_report_period(&g_link, cfg, inputs, out, due_ins_state(), now_us);
}
