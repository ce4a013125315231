/* Host (SIL) build of the HA firmware: the real HA core (ha_app) and the real link device side,
 * speaking rosserial over a pseudo-terminal exactly as the Due speaks over USB. The pty's slave
 * is published under --port (a symlink, like /dev/ttyACM0), so the `arduino` node opens it as
 * it would open the Due.
 *
 *   ha_sil --port PATH [--rate-hz 100] [--unplug-ms 500] [--latency-log FILE] [--param NAME]
 *          [--vn200 PATH] [--lockstep SOCKET [--realtime]]
 *
 * SIGUSR1 unplugs the USB cable: the pty is closed and the symlink removed for --unplug-ms while
 * the control loop keeps running (as the Due does), then a fresh pty is plugged in under the same
 * path. SIGINT/SIGTERM stop it cleanly. --latency-log writes "seq latency_us" per command
 * received, from the command's stamp (ROS wall time) to its arrival at the core. --param asks
 * the host for a parameter at every link-up and logs the answer back through the link, so the
 * parameter path can be seen end to end on rosout. Whenever the device drops bad input it logs
 * its decoder's counters the same way ("link errors: ..."), so the host side can see them.
 *
 * In the loop of a simulator (hil/): --vn200 PATH opens the HA's own VN-200 port (a pty the
 * simulator writes Binary Output 1 to, as the sensor's port 1 feeds the Due's Serial1) and
 * --lockstep SOCKET connects to the simulator's control channel (ha_sil_channel.h), which gives
 * the clock and the board inputs (RC, airspeed, battery) and takes back the servo outputs and
 * the decision. Without --realtime the simulator owns time: one period per step record. With
 * --realtime the SIL keeps its own clock and the records only carry board inputs. Without
 * --lockstep the board is a healthy receiver in computer-in-command and a 60 ft/s pitot. */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "../src/core/ha_aircraft.h"
#include "../src/core/ha_app.h"
#include "../src/vn200/ha_vn200_feed.h"
#include "ha_link.h"
#include "ha_link_report.h"
#include "ha_sil_channel.h"

static volatile sig_atomic_t g_stop = 0;
static volatile sig_atomic_t g_unplug = 0;

static void on_stop(int sig) {
  (void)sig;
  g_stop = 1;
}
static void on_unplug(int sig) {
  (void)sig;
  g_unplug = 1;
}

static uint32_t micros_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint32_t)((uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u);
}

typedef struct {
  int master_fd;
  int slave_fd; /* held open so the node reopening its end never hangs up ours */
  const char *port_path;
  HaApp app;
  HaLink link;
  FILE *latency_log;
  uint32_t commands;
  uint32_t negotiations_seen;
  const char *param_name;
  uint32_t errors_logged;    /* sum of the drop counters last reported */
  uint32_t errors_logged_us; /* when */
  /* In the loop of a simulator */
  int vn_fd;       /* the HA's VN-200 port, -1 without --vn200 */
  HaVn200Feed ins; /* the VN-200 port, read by the Due's own rule (src/vn200/ha_vn200_feed.c) */
  int channel_fd;  /* the simulator's control channel, -1 without --lockstep */
  int sim_clock;   /* 1: board micros() is sim_now_us (lockstep) */
  uint32_t sim_now_us;
  HaSilStep board_in; /* the latest board inputs from the simulator */
  int have_board_in;
  int hp_reset;
  uint32_t last_cmd_seq;
  HaLinkCallbacks link_cb;
  /* The board's retained words (the Due's backup registers): kept across a reset of the HA. */
  uint32_t retained[HA_RETAINED_WORDS];
  uint32_t resets;
} Sil;

/* --- the board: a host clock or the simulator's; without a simulator a healthy RC receiver in
 * computer-in-command and a pitot at 60 ft/s, with one the inputs of its latest record --- */
static uint32_t board_micros(void *ctx) {
  const Sil *sil = (const Sil *)ctx;
  return sil->sim_clock ? sil->sim_now_us : micros_now();
}
static void board_write_servos(void *ctx, const HaSurfaces *s) {
  (void)ctx;
  (void)s; /* the simulator reads app.outputs.surfaces, which is what was written */
}
static void board_read_rc(void *ctx, HaRcInputs *rc) {
  const Sil *sil = (const Sil *)ctx;
  int k;
  if (sil->have_board_in) {
    for (k = 0; k < HA_RC_CHANNELS; ++k) {
      rc->pulse_us[k] = sil->board_in.rc_pulse_us[k];
    }
    rc->valid = (uint8_t)((sil->board_in.flags & HA_SIL_RC_VALID) != 0u);
    return;
  }
  rc->pulse_us[HA_RC_THROTTLE] = 1100u;
  rc->pulse_us[HA_RC_ELEVATOR] = 1500u;
  rc->pulse_us[HA_RC_AILERON] = 1500u;
  rc->pulse_us[HA_RC_RUDDER] = 1500u;
  rc->pulse_us[HA_RC_PIC] = 1000u; /* computer in command */
  rc->valid = 1u;
}
static int board_read_airspeed(void *ctx, float *v) {
  const Sil *sil = (const Sil *)ctx;
  if (sil->have_board_in) {
    *v = sil->board_in.airspeed_ftps;
    return (sil->board_in.flags & HA_SIL_AIRSPEED_OK) != 0u;
  }
  /* In a simulator's loop the board reads nothing until the simulator's first record (real time:
   * the SIL's periods start before it): a made-up 60 ft/s would latch airborne on the ground. */
  *v = 60.0f;
  return sil->channel_fd < 0;
}
static int board_read_battery(void *ctx, float *v) {
  const Sil *sil = (const Sil *)ctx;
  if (sil->have_board_in) {
    *v = sil->board_in.battery_v;
    return (sil->board_in.flags & HA_SIL_BATTERY_OK) != 0u;
  }
  *v = 12.1f;
  return sil->channel_fd < 0;
}
static void board_set_hp_reset(void *ctx, int asserted) {
  Sil *sil = (Sil *)ctx;
  sil->hp_reset = asserted;
}
static void board_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  (void)leds;
}
static void board_kick(void *ctx) { (void)ctx; }
static int board_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  const Sil *sil = (const Sil *)ctx;
  memcpy(words, sil->retained, sizeof sil->retained);
  return 1;
}
static void board_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  Sil *sil = (Sil *)ctx;
  memcpy(sil->retained, words, sizeof sil->retained);
}

/* --- the link's callbacks --- */
static void link_write(void *ctx, const uint8_t *bytes, size_t len) {
  Sil *sil = (Sil *)ctx;
  size_t done = 0u;
  while ((sil->master_fd >= 0) && (done < len)) {
    const ssize_t n = write(sil->master_fd, bytes + done, len - done);
    if (n > 0) {
      done += (size_t)n;
    } else if ((n < 0) && (errno == EAGAIN)) {
      return; /* host not reading: drop, as a full USB buffer on the Due would */
    } else {
      return;
    }
  }
}

static void link_on_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  Sil *sil = (Sil *)ctx;
  ha_inputs_put_hp_command(&sil->app.inputs, cmd, arrival_us);
  sil->commands++;
  sil->last_cmd_seq = cmd->seq;
  if (sil->latency_log != NULL) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    const double now_s = (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
    const double stamp_s = (double)cmd->stamp_sec + (double)cmd->stamp_nsec * 1e-9;
    fprintf(sil->latency_log, "%u %.1f\n", (unsigned)cmd->seq, (now_s - stamp_s) * 1e6);
  }
}

static void link_on_operator(void *ctx, const drone_ros_OperatorCommand *op, uint32_t arrival_us) {
  Sil *sil = (Sil *)ctx;
  static const char *const kSetHome[] = {"SET_HOME: home moved",
                                         "SET_HOME refused: not parked on the ground",
                                         "SET_HOME refused: position out of range"};
  if (op->command == HA_OP_SET_HOME) { /* home is the INS adapter's, not the decision logic's */
    const int r =
        ha_ins_set_home(&sil->ins.ins, sil->app.outputs.on_ground, op->use_current ? 1u : 0u,
                        op->latitude, op->longitude, op->altitude);
    (void)arrival_us;
    (void)ha_link_log(&sil->link,
                      r == HA_INS_SET_HOME_OK ? ROSSERIAL_MSGS_LOG_INFO : ROSSERIAL_MSGS_LOG_WARN,
                      kSetHome[r >= 0 && r <= 2 ? r : 1]);
    return;
  }
  ha_inputs_put_operator(&sil->app.inputs, op->command, op->request_id);
}

static void link_on_param(void *ctx, const rosserial_msgs_RequestParamResponse *reply) {
  Sil *sil = (Sil *)ctx;
  char text[160];
  int used;
  uint32_t k;
  used = snprintf(text, sizeof text, "param %s:", sil->param_name != NULL ? sil->param_name : "?");
  for (k = 0u; (k < reply->ints_count) && (used > 0) && ((size_t)used < sizeof text); ++k) {
    used += snprintf(text + used, sizeof text - (size_t)used, " %ld", (long)reply->ints[k]);
  }
  (void)ha_link_log(&sil->link, ROSSERIAL_MSGS_LOG_INFO, text);
}

/* --- the device's own view of bad input, sent to the host as a log --- */
static uint32_t link_errors(const HaLink *link) {
  const HaLinkFrameCounters *f = &link->decoder.counters;
  return f->bytes_skipped + f->bad_protocol + f->bad_length_checksum + f->oversized +
         f->bad_checksum + f->timeouts + link->counters.unknown_topic + link->counters.bad_payload +
         link->counters.operator_bad_crc;
}

/* Whenever the device has dropped something new, it says what, at most every 200 ms: the host
 * cannot see what the device threw away, and tests compare these counts before and after they
 * inject bad bytes. Nothing is sent while input is clean. */
static void report_link_errors(Sil *sil, uint32_t now_us) {
  const HaLinkFrameCounters *f = &sil->link.decoder.counters;
  const uint32_t errors = link_errors(&sil->link);
  char text[200];
  if ((errors == sil->errors_logged) || ((uint32_t)(now_us - sil->errors_logged_us) < 200000u) ||
      !ha_link_connected(&sil->link)) {
    return;
  }
  snprintf(text, sizeof text,
           "link errors: bytes_skipped %u bad_protocol %u bad_length_checksum %u oversized %u "
           "bad_checksum %u timeouts %u unknown_topic %u bad_payload %u operator_bad_crc %u",
           (unsigned)f->bytes_skipped, (unsigned)f->bad_protocol, (unsigned)f->bad_length_checksum,
           (unsigned)f->oversized, (unsigned)f->bad_checksum, (unsigned)f->timeouts,
           (unsigned)sil->link.counters.unknown_topic, (unsigned)sil->link.counters.bad_payload,
           (unsigned)sil->link.counters.operator_bad_crc);
  if (ha_link_log(&sil->link, ROSSERIAL_MSGS_LOG_WARN, text)) {
    sil->errors_logged = errors;
    sil->errors_logged_us = now_us;
  }
}

/* --- the pseudo-terminal standing in for the USB cable --- */
static int plug(Sil *sil) {
  char name[128];
  char tmp[600];
  struct termios tio;
  int flags;
  if (openpty(&sil->master_fd, &sil->slave_fd, name, NULL, NULL) != 0) {
    return -1;
  }
  /* Raw both ways before anyone opens it, so no line discipline touches the bytes. */
  if (tcgetattr(sil->slave_fd, &tio) == 0) {
    cfmakeraw(&tio);
    (void)tcsetattr(sil->slave_fd, TCSANOW, &tio);
  }
  flags = fcntl(sil->master_fd, F_GETFL);
  (void)fcntl(sil->master_fd, F_SETFL, flags | O_NONBLOCK);
  snprintf(tmp, sizeof tmp, "%s.tmp", sil->port_path);
  (void)unlink(tmp);
  if ((symlink(name, tmp) != 0) || (rename(tmp, sil->port_path) != 0)) {
    return -1;
  }
  return 0;
}

static void unplug(Sil *sil) {
  (void)unlink(sil->port_path);
  if (sil->master_fd >= 0) {
    close(sil->master_fd);
  }
  if (sil->slave_fd >= 0) {
    close(sil->slave_fd);
  }
  sil->master_fd = -1;
  sil->slave_fd = -1;
}

/* The period's pwm, decision_status and home, built as the Due builds them. */
static void send_sensors(Sil *sil, uint32_t now_us) {
  ha_link_report_period(&sil->link, &ha_aircraft_config, &sil->app.inputs, &sil->app.outputs,
                        &sil->ins.ins, now_us);
}

/* A (re)negotiated link says so in the host's log and asks for --param. */
static void on_negotiation(Sil *sil) {
  if (sil->link.counters.topic_requests != sil->negotiations_seen) {
    sil->negotiations_seen = sil->link.counters.topic_requests;
    (void)ha_link_log(&sil->link, ROSSERIAL_MSGS_LOG_INFO, "HA SIL link up");
    if (sil->param_name != NULL) {
      (void)ha_link_request_param(&sil->link, sil->param_name);
    }
  }
}

/* --- the simulator: the HA's VN-200 port and the control channel --- */

static int open_vn200(Sil *sil, const char *path) {
  struct termios tio;
  int tries;
  for (tries = 0; tries < 300 && !g_stop; ++tries) { /* the simulator may still be starting */
    sil->vn_fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (sil->vn_fd >= 0) {
      if (tcgetattr(sil->vn_fd, &tio) == 0) {
        cfmakeraw(&tio);
        (void)cfsetspeed(&tio, B115200); /* DUE_VN200_BAUD */
        (void)tcsetattr(sil->vn_fd, TCSANOW, &tio);
      }
      return 0;
    }
    usleep(100000);
  }
  return -1;
}

static int connect_channel(Sil *sil, const char *path) {
  struct sockaddr_un addr;
  int tries;
  if (strlen(path) >= sizeof addr.sun_path) {
    return -1;
  }
  memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  strcpy(addr.sun_path, path);
  for (tries = 0; tries < 300 && !g_stop; ++tries) {
    sil->channel_fd = socket(AF_UNIX, SOCK_SEQPACKET, 0);
    if (sil->channel_fd < 0) {
      return -1;
    }
    if (connect(sil->channel_fd, (const struct sockaddr *)&addr, sizeof addr) == 0) {
      return 0;
    }
    close(sil->channel_fd);
    sil->channel_fd = -1;
    usleep(100000);
  }
  return -1;
}

/* Little-endian field access: the records have a fixed layout whatever the host's padding. */
static void put_u16(uint8_t *b, size_t *at, uint16_t v) {
  b[(*at)++] = (uint8_t)v;
  b[(*at)++] = (uint8_t)(v >> 8);
}
static void put_u32(uint8_t *b, size_t *at, uint32_t v) {
  put_u16(b, at, (uint16_t)v);
  put_u16(b, at, (uint16_t)(v >> 16));
}
static void put_u64(uint8_t *b, size_t *at, uint64_t v) {
  put_u32(b, at, (uint32_t)v);
  put_u32(b, at, (uint32_t)(v >> 32));
}
static void put_f32(uint8_t *b, size_t *at, float v) {
  uint32_t u;
  memcpy(&u, &v, sizeof u);
  put_u32(b, at, u);
}
static uint16_t get_u16(const uint8_t *b, size_t *at) {
  const uint16_t v = (uint16_t)(b[*at] | (b[*at + 1u] << 8));
  *at += 2u;
  return v;
}
static uint32_t get_u32(const uint8_t *b, size_t *at) {
  const uint32_t lo = get_u16(b, at);
  return lo | ((uint32_t)get_u16(b, at) << 16);
}
static uint64_t get_u64(const uint8_t *b, size_t *at) {
  const uint64_t lo = get_u32(b, at);
  return lo | ((uint64_t)get_u32(b, at) << 32);
}
static float get_f32(const uint8_t *b, size_t *at) {
  const uint32_t u = get_u32(b, at);
  float v;
  memcpy(&v, &u, sizeof v);
  return v;
}

#define STEP_RECORD_LEN 52u
#define REPLY_RECORD_LEN 100u

static int decode_step(const uint8_t *b, size_t len, HaSilStep *st) {
  size_t at = 0u;
  int k;
  if (len != STEP_RECORD_LEN) {
    return 0;
  }
  st->magic = get_u32(b, &at);
  st->version = get_u16(b, &at);
  st->flags = get_u16(b, &at);
  st->t_us = get_u64(b, &at);
  st->vn_bytes = get_u64(b, &at);
  st->cmd_seq = get_u32(b, &at);
  st->wait_ms = get_u32(b, &at);
  for (k = 0; k < 5; ++k) {
    st->rc_pulse_us[k] = get_u16(b, &at);
  }
  st->reserved = get_u16(b, &at);
  st->airspeed_ftps = get_f32(b, &at);
  st->battery_v = get_f32(b, &at);
  return (st->magic == HA_SIL_MAGIC_STEP || st->magic == HA_SIL_MAGIC_POLL ||
          st->magic == HA_SIL_MAGIC_RESET) &&
         st->version == HA_SIL_VERSION;
}

/* Lockstep: the simulator waits for each reply, so the send may block. Real time: the SIL keeps
 * its own clock and never waits for the simulator; a reply that finds the socket full is dropped.
 */
static void send_reply(Sil *sil, uint16_t flags, uint64_t t_us, uint32_t wait_us) {
  const HaOutputs *o = &sil->app.outputs;
  uint8_t b[REPLY_RECORD_LEN];
  size_t at = 0u;
  if (ha_link_connected(&sil->link)) flags |= HA_SIL_R_LINK_CONNECTED;
  if (sil->app.inputs.state_valid) flags |= HA_SIL_R_STATE_VALID;
  if (sil->ins.ins.home_latched) flags |= HA_SIL_R_HOME;
  if (sil->hp_reset) flags |= HA_SIL_R_HP_RESET;
  if (o->restart_requested && (flags & HA_SIL_R_STEPPED)) flags |= HA_SIL_R_RESTART_REQUESTED;
  put_u32(b, &at, HA_SIL_MAGIC_REPLY);
  put_u16(b, &at, HA_SIL_VERSION);
  put_u16(b, &at, flags);
  put_u64(b, &at, t_us);
  put_f32(b, &at, o->surfaces.elevator_deg);
  put_f32(b, &at, o->surfaces.aileron_deg);
  put_f32(b, &at, o->surfaces.rudder_deg);
  put_f32(b, &at, o->surfaces.throttle);
  put_f32(b, &at, o->ha_command.elevator_deg);
  put_f32(b, &at, o->ha_command.aileron_deg);
  put_f32(b, &at, o->ha_command.rudder_deg);
  put_f32(b, &at, o->ha_command.throttle);
  b[at++] = o->controller;
  b[at++] = o->leds;
  put_u16(b, &at, o->restart_count);
  put_u32(b, &at, o->reasons);
  put_u32(b, &at, o->reasons_at_switch);
  put_u32(b, &at, o->last_seq);
  put_u32(b, &at, sil->commands);
  put_f32(b, &at, o->stable_for_s);
  put_f32(b, &at, o->state_region_max);
  put_f32(b, &at, o->actuator_region_max);
  put_u32(b, &at, (uint32_t)sil->ins.counts.bytes_read);
  put_u32(b, &at, sil->ins.ins.solutions_used);
  put_u32(b, &at, sil->ins.ins.solutions_rejected);
  put_u32(b, &at, vn_framer_bad_packets(&sil->ins.framer.stats) + sil->ins.counts.decode_errors);
  put_u32(b, &at, wait_us);
  {
    const ssize_t n =
        send(sil->channel_fd, b, at, MSG_NOSIGNAL | (sil->sim_clock ? 0 : MSG_DONTWAIT));
    if (n != (ssize_t)at && !(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))) {
      g_stop = 1; /* the simulator is gone: so is the world this HA lives in */
    }
  }
}

/* Reads what the link and the VN-200 port have, applying it at now_us. Returns bytes taken. */
static size_t drain_inputs(Sil *sil, uint32_t now_us) {
  uint8_t buf[512];
  size_t taken = 0u;
  ssize_t n;
  if (sil->master_fd >= 0) {
    while ((n = read(sil->master_fd, buf, sizeof buf)) > 0) {
      ha_link_receive(&sil->link, buf, (size_t)n, now_us);
      taken += (size_t)n;
    }
  }
  if (sil->vn_fd >= 0) {
    while ((n = read(sil->vn_fd, buf, sizeof buf)) > 0) {
      ha_vn200_feed_bytes(&sil->ins, buf, (size_t)n, &sil->app.inputs, sil->app.outputs.on_ground,
                          now_us);
      taken += (size_t)n;
    }
  }
  return taken;
}

static double wall_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Waits (bounded) until the link and the VN-200 port have delivered what the simulator says it
 * sent for this period. Everything read is applied at the new period's time, so what arrives
 * when in wall time does not change what the core sees. Returns the HA_SIL_R_*_TIMEOUT flags. */
static uint16_t gather_period_inputs(Sil *sil, const HaSilStep *st) {
  const double deadline = wall_s() + (double)st->wait_ms * 1e-3;
  for (;;) {
    struct pollfd p[2];
    int np = 0;
    int want_cmd, want_vn;
    (void)drain_inputs(sil, sil->sim_now_us);
    if ((st->flags & HA_SIL_WAIT_COUNT) != 0u) {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u && sil->commands < st->cmd_seq;
    } else {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u &&
                 !(sil->commands > 0u && sil->last_cmd_seq == st->cmd_seq);
    }
    want_vn = sil->vn_fd >= 0 && sil->ins.counts.bytes_read < st->vn_bytes;
    if (!want_cmd && !want_vn) {
      return 0u;
    }
    if (wall_s() >= deadline || g_stop) {
      return (uint16_t)((want_cmd ? HA_SIL_R_COMMAND_TIMEOUT : 0u) |
                        (want_vn ? HA_SIL_R_VN_TIMEOUT : 0u));
    }
    if (sil->master_fd >= 0) {
      p[np].fd = sil->master_fd;
      p[np].events = POLLIN;
      np++;
    }
    if (sil->vn_fd >= 0) {
      p[np].fd = sil->vn_fd;
      p[np].events = POLLIN;
      np++;
    }
    (void)poll(p, (nfds_t)np, 2);
  }
}

static void take_board_inputs(Sil *sil, const HaSilStep *st) {
  sil->board_in = *st;
  sil->have_board_in = 1;
}

/* The firmware's state from power-up or a reset, as the Due's setup() makes it: the core, the INS
 * adapter and the link device afresh, then what the board retained taken back. What the Due does
 * not reset is kept: the retained words, the pty (the USB bridge stays up), and the SIL's own
 * counts the simulator waits on (VN-200 bytes taken, commands delivered). */
static void firmware_start(Sil *sil, const HaBoard *board) {
  const uint64_t vn_bytes = sil->ins.counts.bytes_read;
  ha_app_init(&sil->app, &ha_aircraft_config);
  ha_vn200_feed_init(&sil->ins, &ha_aircraft_config);
  sil->ins.counts.bytes_read = vn_bytes;
  ha_link_init(&sil->link, &sil->link_cb);
  sil->negotiations_seen = 0u; /* the link's own counts start afresh with it */
  sil->errors_logged = 0u;
  ha_app_restore(&sil->app, board, &sil->ins.ins);
  sil->hp_reset = 0; /* the Due's pins come up low: the HP out of reset */
}

static void firmware_reset(Sil *sil, const HaBoard *board) {
  sil->resets++;
  firmware_start(sil, board);
  fprintf(stderr, "ha_sil: reset %u (as a watchdog reset): home %s, airborne %u\n",
          (unsigned)sil->resets, sil->ins.ins.home_latched ? "kept" : "none",
          (unsigned)sil->app.core.airborne);
}

/* Lockstep: the simulator's records drive everything; between them the SIL sleeps. */
static int run_lockstep(Sil *sil, const HaBoard *board) {
  uint8_t rec[128];
  while (!g_stop) {
    HaSilStep st;
    struct pollfd p;
    ssize_t n;
    p.fd = sil->channel_fd;
    p.events = POLLIN;
    if (poll(&p, 1, 200) <= 0) {
      continue;
    }
    n = recv(sil->channel_fd, rec, sizeof rec, 0);
    if (n <= 0) {
      fprintf(stderr, "ha_sil: simulator closed the control channel\n");
      break;
    }
    if (!decode_step(rec, (size_t)n, &st)) {
      fprintf(stderr, "ha_sil: dropped a control record of %zd bytes (not a step or poll)\n", n);
      continue;
    }
    if (st.magic == HA_SIL_MAGIC_RESET) {
      firmware_reset(sil, board);
      send_reply(sil, 0u, sil->sim_now_us, 0u);
      continue;
    }
    if (st.magic == HA_SIL_MAGIC_POLL) {
      (void)drain_inputs(sil, sil->sim_now_us);
      ha_link_poll(&sil->link, sil->sim_now_us);
      on_negotiation(sil);
      send_reply(sil, 0u, sil->sim_now_us, 0u);
      continue;
    }
    {
      uint16_t flags;
      double waited_s;
      /* The clock never runs backwards (the link requires it): a step to an earlier time is
       * taken as the current one. */
      if ((int32_t)((uint32_t)st.t_us - sil->sim_now_us) > 0) {
        sil->sim_now_us = (uint32_t)st.t_us;
      }
      waited_s = wall_s();
      flags = gather_period_inputs(sil, &st);
      waited_s = wall_s() - waited_s;
      take_board_inputs(sil, &st);
      ha_app_period(&sil->app, board);
      send_sensors(sil, sil->sim_now_us);
      ha_link_poll(&sil->link, sil->sim_now_us);
      on_negotiation(sil);
      report_link_errors(sil, sil->sim_now_us);
      send_reply(sil, (uint16_t)(flags | HA_SIL_R_STEPPED), st.t_us, (uint32_t)(waited_s * 1e6));
    }
  }
  return 0;
}

int main(int argc, char **argv) {
  static Sil sil;
  HaBoard board;
  HaLinkCallbacks cb;
  double rate_hz = 100.0;
  uint32_t unplug_us = 500000u;
  uint32_t next_period_us;
  uint32_t replug_at_us = 0u;
  int unplugged = 0;
  int i;
  const char *vn200_path = NULL;
  const char *channel_path = NULL;
  int realtime = 0;
  memset(&sil, 0, sizeof sil);
  sil.master_fd = -1;
  sil.slave_fd = -1;
  sil.vn_fd = -1;
  sil.channel_fd = -1;
  for (i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--realtime") == 0) {
      realtime = 1;
      continue;
    }
    if (i + 1 >= argc || strncmp(argv[i], "--", 2) != 0) {
      continue; /* roslaunch's __name:= and __log:= */
    }
    if (strcmp(argv[i], "--port") == 0) {
      sil.port_path = argv[++i];
    } else if (strcmp(argv[i], "--rate-hz") == 0) {
      rate_hz = atof(argv[++i]);
    } else if (strcmp(argv[i], "--unplug-ms") == 0) {
      unplug_us = (uint32_t)atoi(argv[++i]) * 1000u;
    } else if (strcmp(argv[i], "--param") == 0) {
      sil.param_name = argv[++i];
    } else if (strcmp(argv[i], "--vn200") == 0) {
      vn200_path = argv[++i];
    } else if (strcmp(argv[i], "--lockstep") == 0) {
      channel_path = argv[++i];
    } else if (strcmp(argv[i], "--latency-log") == 0) {
      sil.latency_log = fopen(argv[++i], "w");
      if (sil.latency_log != NULL) {
        setvbuf(sil.latency_log, NULL, _IOLBF, 0); /* readers watch it while we run */
      }
    }
  }
  if ((sil.port_path == NULL) || !(rate_hz >= 1.0 && rate_hz <= 1000.0)) {
    fprintf(stderr,
            "usage: ha_sil --port PATH [--rate-hz 1..1000] [--unplug-ms N] [--latency-log FILE]\n"
            "              [--param NAME] [--vn200 PATH] [--lockstep SOCKET [--realtime]]\n");
    return 2;
  }
  signal(SIGINT, on_stop);
  signal(SIGTERM, on_stop);
  signal(SIGUSR1, on_unplug);
  signal(SIGPIPE, SIG_IGN);

  board.ctx = &sil;
  board.micros = board_micros;
  board.write_servos = board_write_servos;
  board.read_rc = board_read_rc;
  board.read_airspeed_ftps = board_read_airspeed;
  board.read_battery_v = board_read_battery;
  board.set_hp_reset = board_set_hp_reset;
  board.set_leds = board_set_leds;
  board.kick_watchdog = board_kick;
  board.read_retained = board_read_retained;
  board.write_retained = board_write_retained;

  memset(&cb, 0, sizeof cb);
  cb.write = link_write;
  cb.on_command = link_on_command;
  cb.on_operator = link_on_operator;
  cb.on_param = link_on_param;
  cb.ctx = &sil;
  sil.link_cb = cb;
  firmware_start(&sil, &board); /* power-up: the retained words hold no record yet */
  if (vn200_path != NULL && open_vn200(&sil, vn200_path) != 0) {
    fprintf(stderr, "ha_sil: cannot open the VN-200 port %s: %s\n", vn200_path, strerror(errno));
    return 1;
  }
  if (channel_path != NULL && connect_channel(&sil, channel_path) != 0) {
    fprintf(stderr, "ha_sil: cannot connect to the simulator at %s: %s\n", channel_path,
            strerror(errno));
    return 1;
  }
  if (plug(&sil) != 0) {
    perror("ha_sil: openpty");
    return 1;
  }
  if (channel_path != NULL && !realtime) {
    sil.sim_clock = 1;
    fprintf(stderr, "ha_sil: up on %s, lockstep with %s\n", sil.port_path, channel_path);
    (void)run_lockstep(&sil, &board);
  } else {
    fprintf(stderr, "ha_sil: up on %s at %.0f Hz%s\n", sil.port_path, rate_hz,
            channel_path != NULL ? " (board inputs from the simulator)" : "");
    next_period_us = micros_now();
    while (!g_stop) {
      uint8_t buf[512];
      /* One time per pass: the link needs a clock that never runs backwards between its calls. */
      const uint32_t now_us = micros_now();
      if (g_unplug && !unplugged) {
        g_unplug = 0;
        unplug(&sil);
        unplugged = 1;
        replug_at_us = now_us + unplug_us;
      }
      if (unplugged && (int32_t)(now_us - replug_at_us) >= 0) {
        if (plug(&sil) == 0) {
          unplugged = 0;
        }
      }
      if (sil.master_fd >= 0) {
        const ssize_t n = read(sil.master_fd, buf, sizeof buf);
        if (n > 0) {
          ha_link_receive(&sil.link, buf, (size_t)n, now_us);
        }
      }
      if (sil.vn_fd >= 0) {
        const ssize_t n = read(sil.vn_fd, buf, sizeof buf);
        if (n > 0) {
          ha_vn200_feed_bytes(&sil.ins, buf, (size_t)n, &sil.app.inputs, sil.app.outputs.on_ground,
                              now_us);
        }
      }
      if (sil.channel_fd >= 0) {
        HaSilStep st;
        const ssize_t n = recv(sil.channel_fd, buf, sizeof buf, MSG_DONTWAIT);
        if (n == 0) {
          break; /* the simulator is gone */
        }
        if (n > 0 && decode_step(buf, (size_t)n, &st) && st.magic == HA_SIL_MAGIC_STEP) {
          take_board_inputs(&sil, &st);
        } else if (n > 0 && decode_step(buf, (size_t)n, &st) && st.magic == HA_SIL_MAGIC_RESET) {
          firmware_reset(&sil, &board);
        }
      }
      ha_link_poll(&sil.link, now_us);
      on_negotiation(&sil);
      report_link_errors(&sil, now_us);
      if ((int32_t)(now_us - next_period_us) >= 0) {
        next_period_us += (uint32_t)(1e6 / rate_hz);
        if ((int32_t)(now_us - next_period_us) > 100000) {
          next_period_us = now_us; /* stalled (debugger, loaded CI): do not burst to catch up */
        }
        ha_app_period(&sil.app, &board);
        send_sensors(&sil, now_us);
        if (sil.channel_fd >= 0) {
          send_reply(&sil, HA_SIL_R_STEPPED, now_us, 0u);
        }
      }
      usleep(200); /* poll the pty often: command latency is part of what the bench measures */
    }
  }
  unplug(&sil);
  if (sil.vn_fd >= 0) {
    close(sil.vn_fd);
  }
  if (sil.channel_fd >= 0) {
    close(sil.channel_fd);
  }
  if (sil.latency_log != NULL) {
    fclose(sil.latency_log);
  }
  fprintf(stderr,
          "ha_sil: %u commands, frames ok %u, bad checksum %u, skipped %u, unknown topic %u, "
          "VN-200 bytes %llu\n",
          (unsigned)sil.commands, (unsigned)sil.link.decoder.counters.frames_ok,
          (unsigned)sil.link.decoder.counters.bad_checksum,
          (unsigned)sil.link.decoder.counters.bytes_skipped,
          (unsigned)sil.link.counters.unknown_topic, (unsigned long long)sil.ins.counts.bytes_read);
  return 0;
}
