#include "ha_firmware.h"

#include <string.h>

#include "../link/ha_link_report.h"

/* ---- text for the host's log, without printf: bounded, no locale, no heap ---- */

#define HA_FW_TEXT_MAX 200u

typedef struct {
  char text[HA_FW_TEXT_MAX];
  size_t len;
} FwText;

/* The whole buffer zeroed: the text stays terminated whatever is put (the last byte is never
 * written). */
static void text_start(FwText *t) {
  memset(t->text, 0, sizeof t->text);
  t->len = 0u;
}

static void text_put(FwText *t, const char *s) {
  const size_t n = strlen(s);
  size_t i;
  for (i = 0u; i < n && t->len + 1u < sizeof t->text; ++i) {
    t->text[t->len++] = s[i]; /* the last byte stays '\0' */
  }
}

static void text_put_u32(FwText *t, uint32_t value) {
  char digits[11];
  size_t at = sizeof digits - 1u;
  uint32_t v = value;
  memset(digits, 0, sizeof digits);
  do { /* least significant digit last */
    digits[--at] = (char)('0' + (int)(v % 10u));
    v /= 10u;
  } while (v != 0u && at > 0u);
  text_put(t, &digits[at]);
}

static void text_put_i32(FwText *t, int32_t value) {
  if (value < 0) {
    text_put(t, "-");
    /* the magnitude of INT32_MIN fits uint32_t */
    text_put_u32(t, (uint32_t)(-(value + 1)) + 1u);
  } else {
    text_put_u32(t, (uint32_t)value);
  }
}

/* ---- the link's callbacks: the routing of what the HP and the operator send ---- */

static void link_write(void *ctx, const uint8_t *bytes, size_t len) {
  const HaFirmware *fw = (const HaFirmware *)ctx;
  if (fw->board->hp_link.write != NULL) { /* a board without a way to the HP hears nothing */
    fw->board->hp_link.write(fw->board->ctx, bytes, len);
  }
}

static void link_on_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  HaFirmware *fw = (HaFirmware *)ctx;
  ha_inputs_put_hp_command(&fw->app.inputs, cmd, arrival_us);
  if (fw->opts.command_tap != NULL) {
    fw->opts.command_tap(fw->opts.tap_ctx, cmd, arrival_us);
  }
}

static void link_on_operator(void *ctx, const drone_ros_OperatorCommand *op, uint32_t arrival_us) {
  HaFirmware *fw = (HaFirmware *)ctx;
  int r;
  (void)arrival_us;
  if (op->command != HA_OP_SET_HOME) {
    ha_app_put_operator(&fw->app, op->command, op->request_id);
    return;
  }
  /* Home is the INS adapter's, not the decision logic's: judged on the core's latest verdict. */
  r = ha_ins_set_home(&fw->ins.ins, fw->app.outputs.on_ground, op->use_current ? 1u : 0u,
                      op->latitude, op->longitude, op->altitude);
  (void)ha_link_log(
      &fw->link, r == HA_INS_SET_HOME_OK ? ROSSERIAL_MSGS_LOG_INFO : ROSSERIAL_MSGS_LOG_WARN,
      r == HA_INS_SET_HOME_OK             ? "SET_HOME: home moved"
      : r == HA_INS_SET_HOME_BAD_POSITION ? "SET_HOME refused: position out of range"
                                          : "SET_HOME refused: not parked on the ground");
}

static void link_on_param(void *ctx, const rosserial_msgs_RequestParamResponse *reply) {
  HaFirmware *fw = (HaFirmware *)ctx;
  FwText t;
  uint32_t k;
  text_start(&t);
  text_put(&t, "param ");
  text_put(&t, fw->opts.probe_param != NULL ? fw->opts.probe_param : "?");
  text_put(&t, ":");
  for (k = 0u; k < reply->ints_count && k < (uint32_t)HA_MSGS_VAR_ARRAY_CAP; ++k) {
    text_put(&t, " ");
    text_put_i32(&t, reply->ints[k]);
  }
  (void)ha_link_log(&fw->link, ROSSERIAL_MSGS_LOG_INFO, t.text);
}

/* ---- start ---- */

void ha_firmware_start(HaFirmware *fw, const HaBoard *board, const HaAircraftConfig *cfg,
                       const HaFirmwareOptions *opts) {
  HaLinkCallbacks cb;
  fw->cfg = cfg;
  fw->board = board;
  if (opts != NULL) {
    fw->opts = *opts;
  } else {
    memset(&fw->opts, 0, sizeof fw->opts);
  }
  fw->period_us = fw->opts.period_us != 0u ? fw->opts.period_us : cfg->period_us;
  ha_app_init(&fw->app, cfg);
  /* The VN-200 feed before the restore: home comes back into its INS adapter. */
  ha_vn200_feed_init(&fw->ins, cfg);
  cb.write = link_write;
  cb.on_command = link_on_command;
  cb.on_operator = link_on_operator;
  cb.on_param = link_on_param;
  cb.ctx = fw;
  ha_link_init(&fw->link, &cb);
  fw->negotiations_seen = 0u;
  fw->errors_logged = 0u;
  fw->errors_logged_us = 0u;
  /* After a watchdog or brown-out reset in flight: home, the airborne latch and the HA's latches
   * as they were (the board's retained words). */
  ha_app_restore(&fw->app, board, &fw->ins.ins);
  fw->next_period_us = board->micros(board->ctx);
  fw->period_at_us = fw->next_period_us;
  fw->commands_at_period = 0u;
  fw->commanded = 0;
}

/* ---- one pass ---- */

/* Up to `reads` reads of one port, each applied at now_us to the link or the VN-200 feed; stops at
 * a read that found less than a chunk (the port is drained for now). */
static size_t drain(HaFirmware *fw, const HaBytePort *port, int to_link, uint32_t now_us,
                    uint32_t reads) {
  uint8_t bytes[HA_FW_READ_CHUNK];
  size_t taken = 0u;
  uint32_t k;
  if (port->read == NULL) {
    return 0u; /* a board without this port (no INS wired, say) */
  }
  for (k = 0u; k < reads; ++k) {
    size_t n = port->read(fw->board->ctx, bytes, sizeof bytes);
    if (n > sizeof bytes) {
      n = sizeof bytes; /* a board that claims more than it may hand over */
    }
    if (n > 0u && to_link) {
      ha_link_receive(&fw->link, bytes, n, now_us);
    } else if (n > 0u) {
      ha_vn200_feed_bytes(&fw->ins, bytes, n, &fw->app.inputs, fw->app.outputs.on_ground, now_us);
    }
    taken += n;
    if (n < sizeof bytes) {
      break;
    }
  }
  return taken;
}

size_t ha_firmware_receive(HaFirmware *fw, uint32_t now_us, uint32_t reads) {
  const size_t hp = drain(fw, &fw->board->hp_link, 1, now_us, reads);
  return hp + drain(fw, &fw->board->ins, 0, now_us, reads);
}

uint32_t ha_firmware_link_errors(const HaLink *link) {
  const HaLinkFrameCounters *f = &link->decoder.counters;
  /* Wrapping sums: only a change is looked at. */
  return f->bytes_skipped + f->bad_protocol + f->bad_length_checksum + f->oversized +
         f->bad_checksum + f->timeouts + link->counters.unknown_topic + link->counters.bad_payload +
         link->counters.operator_bad_crc;
}

static void put_counter(FwText *t, const char *name, uint32_t value) {
  text_put(t, " ");
  text_put(t, name);
  text_put(t, " ");
  text_put_u32(t, value);
}

/* Whenever the device has dropped something new, it says what, at most every 200 ms: the host
 * cannot see what the device threw away, and tests compare these counts before and after they
 * inject bad bytes. Nothing is sent while input is clean. */
static void report_link_errors(HaFirmware *fw, uint32_t now_us) {
  const HaLinkFrameCounters *f = &fw->link.decoder.counters;
  const HaLinkCounters *c = &fw->link.counters;
  const uint32_t errors = ha_firmware_link_errors(&fw->link);
  FwText t;
  if (errors == fw->errors_logged || (uint32_t)(now_us - fw->errors_logged_us) < 200000u ||
      !ha_link_connected(&fw->link)) {
    return;
  }
  text_start(&t);
  text_put(&t, "link errors:");
  put_counter(&t, "bytes_skipped", f->bytes_skipped);
  put_counter(&t, "bad_protocol", f->bad_protocol);
  put_counter(&t, "bad_length_checksum", f->bad_length_checksum);
  put_counter(&t, "oversized", f->oversized);
  put_counter(&t, "bad_checksum", f->bad_checksum);
  put_counter(&t, "timeouts", f->timeouts);
  put_counter(&t, "unknown_topic", c->unknown_topic);
  put_counter(&t, "bad_payload", c->bad_payload);
  put_counter(&t, "operator_bad_crc", c->operator_bad_crc);
  if (ha_link_log(&fw->link, ROSSERIAL_MSGS_LOG_WARN, t.text)) {
    fw->errors_logged = errors;
    fw->errors_logged_us = now_us;
  }
}

void ha_firmware_service(HaFirmware *fw, uint32_t now_us) {
  ha_link_poll(&fw->link, now_us);
  /* A (re)negotiated link says so in the host's log and asks for the probe parameter. */
  if (fw->link.counters.topic_requests != fw->negotiations_seen) {
    fw->negotiations_seen = fw->link.counters.topic_requests;
    if (fw->opts.link_up_text != NULL) {
      (void)ha_link_log(&fw->link, ROSSERIAL_MSGS_LOG_INFO, fw->opts.link_up_text);
    }
    if (fw->opts.probe_param != NULL) {
      (void)ha_link_request_param(&fw->link, fw->opts.probe_param);
    }
  }
  report_link_errors(fw, now_us);
}

void ha_firmware_period(HaFirmware *fw, uint32_t now_us) {
  ha_app_period(&fw->app, fw->board);
  ha_link_report_period(&fw->link, fw->cfg, &fw->app.inputs, &fw->app.outputs, &fw->ins.ins,
                        now_us);
  fw->period_at_us = now_us;
  fw->commanded = fw->link.counters.commands != fw->commands_at_period;
  fw->commands_at_period = fw->link.counters.commands;
}

/* When a period is due: not yet, on the HA's own grid (every period_us from the start, as on a
 * free clock), or off it. */
enum { DUE_NOT = 0, DUE_ON_GRID = 1, DUE_OFF_GRID = 2 };

/* Paced by the command: the servos take an HP command when it arrives, not up to a period later
 * on a clock at any phase to the HP's. Bounded both ways, so the HP cannot set the HA's rate:
 * never sooner than 3/4 of a period after the last (an HP babbling faster is taken at most at
 * 4/3 of the rate), and on the clock when no command comes. After a period with a command the
 * clock waits 5/4 of a period, so a command a little late still runs its own period on arrival
 * rather than being counted late; after a period without one the HA's own grid runs, exactly as
 * a free clock's, so the HA flying on its own keeps its rate. A silent HP is thus found late at
 * 5/4 of a period after its last command's period and missed (late_periods_tolerated = 1) at 9/4,
 * against up to 3 on a free clock. */
static int paced_period_due(const HaFirmware *fw, uint32_t now_us) {
  const uint32_t since_us = now_us - fw->period_at_us;
  const uint32_t quarter_us = fw->period_us / 4u;
  if (fw->link.counters.commands != fw->commands_at_period) {
    return since_us >= fw->period_us - quarter_us ? DUE_OFF_GRID : DUE_NOT;
  }
  if (fw->commanded) {
    return since_us >= fw->period_us + quarter_us ? DUE_OFF_GRID : DUE_NOT;
  }
  return (int32_t)(now_us - fw->next_period_us) >= 0 ? DUE_ON_GRID : DUE_NOT;
}

int ha_firmware_loop(HaFirmware *fw) {
  const uint32_t now_us = fw->board->micros(fw->board->ctx);
  int due;
  (void)ha_firmware_receive(fw, now_us,
                            fw->opts.reads_per_pass != 0u ? fw->opts.reads_per_pass : 1u);
  ha_firmware_service(fw, now_us);
  if (fw->opts.pace_by_command) {
    due = paced_period_due(fw, now_us);
  } else {
    due = (int32_t)(now_us - fw->next_period_us) >= 0 ? DUE_ON_GRID : DUE_NOT;
  }
  if (due == DUE_NOT) {
    return 0;
  }
  ha_firmware_period(fw, now_us);
  /* Off the grid, the grid starts again from this period. */
  fw->next_period_us =
      due == DUE_ON_GRID ? fw->next_period_us + fw->period_us : now_us + fw->period_us;
  if ((int32_t)(now_us - fw->next_period_us) >= 0) {
    /* More than a period behind (a long I2C stall, a loaded host): restart the schedule from now
     * instead of running a burst of catch-up periods. The core sees the longer period in its dt. */
    fw->next_period_us = now_us + fw->period_us;
  }
  return 1;
}
