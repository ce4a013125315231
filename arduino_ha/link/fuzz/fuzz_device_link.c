/* libFuzzer harness for the Due's link: arbitrary bytes into the device decoder and session
 * (every frame dispatched through the generated deserializers), and the generated message code
 * itself checked for round trips. Built with clang -fsanitize=fuzzer,address,undefined by
 * `make fuzz-link`; any out-of-bounds access, UB or broken invariant aborts. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ha_link.h"

static size_t g_written;

static void sink(void *ctx, const uint8_t *bytes, size_t len) {
  (void)ctx;
  (void)bytes;
  g_written += len;
  if (len > HA_LINK_TX_MAX) {
    abort();
  }
}

static void on_command(void *ctx, const HaHpCommand *cmd, uint32_t at_us) {
  (void)ctx;
  (void)at_us;
  (void)ha_hp_command_compute_crc(cmd);
}

/* The link hands over only operator requests whose CRC-32 matches their fields. */
static void on_operator(void *ctx, const drone_ros_OperatorCommand *op, uint32_t at_us) {
  uint8_t raw[HA_OPERATOR_COMMAND_FIELDS_LEN + 4u];
  size_t n = 0u;
  (void)ctx;
  (void)at_us;
  if (!drone_ros_OperatorCommand_serialize(op, raw, sizeof raw, &n) || n != sizeof raw ||
      ha_crc32(raw, HA_OPERATOR_COMMAND_FIELDS_LEN) != op->crc32) {
    abort();
  }
}

/* Deserialize, and if that succeeds the re-serialization must reproduce the consumed bytes. */
#define ROUND_TRIP(type)                                              \
  do {                                                                \
    type msg;                                                         \
    size_t used = 0u;                                                 \
    size_t written = 0u;                                              \
    static uint8_t again[4096];                                       \
    if (type##_deserialize(&msg, data, size, &used)) {                \
      if (used > size) abort();                                       \
      if (!type##_serialize(&msg, again, sizeof again, &written)) {   \
        if (used <= sizeof again) abort();                            \
      } else if (written != used || memcmp(again, data, used) != 0) { \
        abort();                                                      \
      }                                                               \
    }                                                                 \
  } while (0)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static HaLink link;
  HaLinkCallbacks cb;
  size_t pos = 0u;
  uint32_t now_us = 0xFFFF0000u; /* start near the wrap */
  memset(&cb, 0, sizeof cb);
  cb.write = sink;
  cb.on_command = on_command;
  cb.on_operator = on_operator;
  ha_link_init(&link, &cb);
  /* Chunks of varying size with time advancing between them: exercises splits and timeouts. */
  while (pos < size) {
    const size_t chunk = 1u + (size_t)(data[pos] % 64u);
    const size_t n = (chunk < size - pos) ? chunk : size - pos;
    ha_link_receive(&link, &data[pos], n, now_us);
    now_us += (uint32_t)data[pos] * 997u;
    ha_link_poll(&link, now_us);
    pos += n;
  }
  {
    drone_ros_pwm pwm;
    memset(&pwm, 0, sizeof pwm);
    (void)ha_link_publish_pwm(&link, &pwm);
    (void)ha_link_log(&link, 1u, "fuzz");
  }
  ROUND_TRIP(drone_ros_ServoCommand);
  ROUND_TRIP(drone_ros_OperatorCommand);
  ROUND_TRIP(drone_ros_pwm);
  ROUND_TRIP(drone_ros_DecisionStatus);
  ROUND_TRIP(rosserial_msgs_TopicInfo);
  ROUND_TRIP(rosserial_msgs_Log);
  ROUND_TRIP(rosserial_msgs_RequestParamResponse);
  ROUND_TRIP(std_msgs_Time);
  return 0;
}
