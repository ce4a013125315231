/* Host (SIL) build of the HA firmware: the real HA core (ha_app) and the real link device side,
 * speaking rosserial over a pseudo-terminal exactly as the Due speaks over USB. The pty's slave
 * is published under --port (a symlink, like /dev/ttyACM0), so the `arduino` node opens it as
 * it would open the Due.
 *
 *   ha_sil --port PATH [--rate-hz 100] [--unplug-ms 500] [--latency-log FILE] [--param NAME]
 *
 * SIGUSR1 unplugs the USB cable: the pty is closed and the symlink removed for --unplug-ms while
 * the control loop keeps running (as the Due does), then a fresh pty is plugged in under the same
 * path. SIGINT/SIGTERM stop it cleanly. --latency-log writes "seq latency_us" per command
 * received, from the command's stamp (ROS wall time) to its arrival at the core. --param asks
 * the host for a parameter at every link-up and logs the answer back through the link, so the
 * parameter path can be seen end to end on rosout. Whenever the device drops bad input it logs
 * its decoder's counters the same way ("link errors: ..."), so the host side can see them. */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pty.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "../src/core/ha_aircraft.h"
#include "../src/core/ha_app.h"
#include "ha_link.h"

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
  uint32_t errors_logged;     /* sum of the drop counters last reported */
  uint32_t errors_logged_us;  /* when */
} Sil;

/* --- the board: a host clock, a healthy RC receiver in computer-in-command, a pitot --- */
static uint32_t board_micros(void *ctx) {
  (void)ctx;
  return micros_now();
}
static void board_write_servos(void *ctx, const HaSurfaces *s) {
  (void)ctx;
  (void)s;
}
static void board_read_rc(void *ctx, HaRcInputs *rc) {
  (void)ctx;
  rc->pulse_us[HA_RC_THROTTLE] = 1100u;
  rc->pulse_us[HA_RC_ELEVATOR] = 1500u;
  rc->pulse_us[HA_RC_AILERON] = 1500u;
  rc->pulse_us[HA_RC_RUDDER] = 1500u;
  rc->pulse_us[HA_RC_PIC] = 1000u; /* computer in command */
  rc->valid = 1u;
}
static int board_read_airspeed(void *ctx, float *v) {
  (void)ctx;
  *v = 60.0f;
  return 1;
}
static int board_read_battery(void *ctx, float *v) {
  (void)ctx;
  *v = 12.1f;
  return 1;
}
static void board_set_hp_reset(void *ctx, int asserted) {
  (void)ctx;
  (void)asserted;
}
static void board_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  (void)leds;
}
static void board_kick(void *ctx) { (void)ctx; }

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
  (void)arrival_us;
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
  return f->bytes_skipped + f->bad_protocol + f->bad_length_checksum + f->oversized + f->bad_checksum +
         f->timeouts + link->counters.unknown_topic + link->counters.bad_payload;
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
           "bad_checksum %u timeouts %u unknown_topic %u bad_payload %u",
           (unsigned)f->bytes_skipped, (unsigned)f->bad_protocol, (unsigned)f->bad_length_checksum,
           (unsigned)f->oversized, (unsigned)f->bad_checksum, (unsigned)f->timeouts,
           (unsigned)sil->link.counters.unknown_topic, (unsigned)sil->link.counters.bad_payload);
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

static void send_sensors(Sil *sil, uint32_t now_us) {
  const HaOutputs *o = &sil->app.outputs;
  const HaInputs *in = &sil->app.inputs;
  drone_ros_pwm pwm;
  drone_ros_DecisionStatus st;
  const HaRosTime stamp = ha_link_ros_time(&sil->link, now_us);
  memset(&pwm, 0, sizeof pwm);
  pwm.header.stamp = stamp;
  pwm.PICCIC = (in->rc.pulse_us[HA_RC_PIC] >= 1500u) ? 0u : 1u;
  pwm.velocity = in->airspeed_ftps;
  (void)ha_link_publish_pwm(&sil->link, &pwm);
  memset(&st, 0, sizeof st);
  st.stamp = stamp;
  st.controller = o->controller;
  st.reasons = o->reasons;
  st.reasons_at_switch = o->reasons_at_switch;
  st.restart_count = o->restart_count;
  st.restart_requested = o->restart_requested;
  st.last_seq = o->last_seq;
  st.stable_for_s = o->stable_for_s;
  st.airspeed_ftps = o->airspeed_ftps;
  st.altitude_agl_ft = o->altitude_agl_ft;
  st.alpha_deg = o->alpha_deg;
  st.beta_deg = o->beta_deg;
  st.state_region_max = o->state_region_max;
  st.actuator_region_max = o->actuator_region_max;
  st.throttle = o->surfaces.throttle;
  st.elevator_deg = o->surfaces.elevator_deg;
  st.aileron_deg = o->surfaces.aileron_deg;
  st.rudder_deg = o->surfaces.rudder_deg;
  (void)ha_link_publish_decision_status(&sil->link, &st);
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
  memset(&sil, 0, sizeof sil);
  sil.master_fd = -1;
  sil.slave_fd = -1;
  for (i = 1; i + 1 < argc; i += 2) {
    if (strcmp(argv[i], "--port") == 0) {
      sil.port_path = argv[i + 1];
    } else if (strcmp(argv[i], "--rate-hz") == 0) {
      rate_hz = atof(argv[i + 1]);
    } else if (strcmp(argv[i], "--unplug-ms") == 0) {
      unplug_us = (uint32_t)atoi(argv[i + 1]) * 1000u;
    } else if (strcmp(argv[i], "--param") == 0) {
      sil.param_name = argv[i + 1];
    } else if (strcmp(argv[i], "--latency-log") == 0) {
      sil.latency_log = fopen(argv[i + 1], "w");
      if (sil.latency_log != NULL) {
        setvbuf(sil.latency_log, NULL, _IOLBF, 0); /* readers watch it while we run */
      }
    }
  }
  if ((sil.port_path == NULL) || !(rate_hz >= 1.0 && rate_hz <= 1000.0)) {
    fprintf(stderr, "usage: ha_sil --port PATH [--rate-hz 1..1000] [--unplug-ms N] [--latency-log FILE]\n");
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
  ha_app_init(&sil.app, &ha_aircraft_config);

  memset(&cb, 0, sizeof cb);
  cb.write = link_write;
  cb.on_command = link_on_command;
  cb.on_operator = link_on_operator;
  cb.on_param = link_on_param;
  cb.ctx = &sil;
  ha_link_init(&sil.link, &cb);
  if (plug(&sil) != 0) {
    perror("ha_sil: openpty");
    return 1;
  }
  fprintf(stderr, "ha_sil: up on %s at %.0f Hz\n", sil.port_path, rate_hz);

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
    ha_link_poll(&sil.link, now_us);
    if (sil.link.counters.topic_requests != sil.negotiations_seen) {
      sil.negotiations_seen = sil.link.counters.topic_requests;
      (void)ha_link_log(&sil.link, ROSSERIAL_MSGS_LOG_INFO, "HA SIL link up");
      if (sil.param_name != NULL) {
        (void)ha_link_request_param(&sil.link, sil.param_name);
      }
    }
    report_link_errors(&sil, now_us);
    if ((int32_t)(now_us - next_period_us) >= 0) {
      next_period_us += (uint32_t)(1e6 / rate_hz);
      if ((int32_t)(now_us - next_period_us) > 100000) {
        next_period_us = now_us; /* stalled (debugger, loaded CI): do not burst to catch up */
      }
      ha_app_period(&sil.app, &board);
      send_sensors(&sil, now_us);
    }
    usleep(200); /* poll the pty often: command latency is part of what the bench measures */
  }
  unplug(&sil);
  if (sil.latency_log != NULL) {
    fclose(sil.latency_log);
  }
  fprintf(stderr, "ha_sil: %u commands, frames ok %u, bad checksum %u, skipped %u, unknown topic %u\n",
          (unsigned)sil.commands, (unsigned)sil.link.decoder.counters.frames_ok,
          (unsigned)sil.link.decoder.counters.bad_checksum, (unsigned)sil.link.decoder.counters.bytes_skipped,
          (unsigned)sil.link.counters.unknown_topic);
  return 0;
}
