/* Host (SIL) build of the HA firmware: the real HA core (ha_app) and the real link device side,
 * speaking rosserial over a pseudo-terminal exactly as the Due speaks over USB. The pty's slave
 * is published under --port (a symlink, like /dev/ttyACM0), so the `arduino` node opens it as
 * it would open the Due.
 *
 *   ha_sil --port PATH [--rate-hz HZ] [--unplug-ms 500] [--latency-log FILE] [--param NAME]
 *          [--vn200 PATH] [--lockstep SOCKET [--realtime]]
 *
 * --rate-hz runs the control loop at another rate than the aircraft's own (limits.yaml's
 * decision.rate_hz, compiled in), as a benchmark at 20 Hz does; without it, the aircraft's.
 *
 * SIGUSR1 unplugs the USB cable: the pty is closed and the symlink removed for --unplug-ms while
 * the control loop keeps running (as the Due does), then a fresh pty is plugged in under the same
 * path. SIGINT/SIGTERM stop it cleanly. --latency-log writes "seq latency_us" per command
 * received, from the command's stamp (ROS wall time) to its arrival at the core. --param asks
 * the host for a parameter at every link-up and logs the answer back through the link, so the
 * parameter path can be seen end to end on rosout. Whenever the device drops bad input it logs
 * its decoder's counters the same way ("link errors: ..."), so the host side can see them.
 *
 * The firmware is the one every board runs (src/firmware/ha_firmware.h: the schedule, the link,
 * the INS feed, operator routing, the reports); the SIL adds its Board (ha_sil_board.c: the ptys
 * and the simulator's board inputs) and, here, the simulator's control channel.
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
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "../src/core/ha_aircraft.h"
#include "../src/firmware/ha_firmware.h"
#include "../src/hil/ha_sil_channel.h"
#include "../src/hil/ha_sil_records.h"
#include "ha_sil_board.h"

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

typedef struct {
  SilBoard board;
  HaFirmware fw;
  HaFirmwareOptions opts;
  FILE *latency_log;
  /* The SIL's own counts the simulator waits on; a reset of the HA keeps them. */
  uint32_t commands;
  uint32_t last_cmd_seq;
  uint32_t resets;
} Sil;

/* Each HP command the firmware hands to the core: counted for the simulator's waits, and its
 * latency from the command's stamp (ROS wall time) to now written to --latency-log. */
static void on_command(void *ctx, const HaHpCommand *cmd, uint32_t arrival_us) {
  Sil *sil = (Sil *)ctx;
  (void)arrival_us;
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

/* --- the simulator's control channel --- */

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
    sil->board.channel_fd = socket(AF_UNIX, SOCK_SEQPACKET, 0);
    if (sil->board.channel_fd < 0) {
      return -1;
    }
    if (connect(sil->board.channel_fd, (const struct sockaddr *)&addr, sizeof addr) == 0) {
      return 0;
    }
    close(sil->board.channel_fd);
    sil->board.channel_fd = -1;
    usleep(100000);
  }
  return -1;
}

/* Lockstep: the simulator waits for each reply, so the send may block. Real time: the SIL keeps
 * its own clock and never waits for the simulator; a reply that finds the socket full is dropped.
 */
static void send_reply(Sil *sil, uint16_t flags, uint64_t t_us, uint32_t wait_us) {
  uint8_t b[HA_SIL_REPLY_RECORD_LEN];
  const HaSilReplyBoard board = {.flags = flags,
                                 .t_us = t_us,
                                 .commands = sil->commands,
                                 .vn_bytes = sil->board.vn_bytes,
                                 .hp_reset = sil->board.pins.hp_reset,
                                 .wait_us = wait_us};
  ha_sil_encode_reply(&sil->fw, &board, b);
  {
    const ssize_t n = send(sil->board.channel_fd, b, sizeof b,
                           MSG_NOSIGNAL | (sil->board.sim_clock ? 0 : MSG_DONTWAIT));
    if (n != (ssize_t)sizeof b && !(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))) {
      g_stop = 1; /* the simulator is gone: so is the world this HA lives in */
    }
  }
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
  const SilBoard *b = &sil->board;
  for (;;) {
    struct pollfd p[2];
    int np = 0;
    int want_cmd, want_vn;
    (void)ha_firmware_receive(&sil->fw, b->sim_now_us, UINT32_MAX);
    if ((st->flags & HA_SIL_WAIT_COUNT) != 0u) {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u && sil->commands < st->cmd_seq;
    } else {
      want_cmd = (st->flags & HA_SIL_WAIT_COMMAND) != 0u &&
                 !(sil->commands > 0u && sil->last_cmd_seq == st->cmd_seq);
    }
    want_vn = b->vn_fd >= 0 && b->vn_bytes < st->vn_bytes;
    if (!want_cmd && !want_vn) {
      return 0u;
    }
    if (wall_s() >= deadline || g_stop) {
      return (uint16_t)((want_cmd ? HA_SIL_R_COMMAND_TIMEOUT : 0u) |
                        (want_vn ? HA_SIL_R_VN_TIMEOUT : 0u));
    }
    if (b->master_fd >= 0) {
      p[np].fd = b->master_fd;
      p[np].events = POLLIN;
      np++;
    }
    if (b->vn_fd >= 0) {
      p[np].fd = b->vn_fd;
      p[np].events = POLLIN;
      np++;
    }
    (void)poll(p, (nfds_t)np, 2);
  }
}

/* A reset of the HA as a watchdog reset resets the Due: the firmware starts afresh and takes back
 * what the board retained. What the Due does not reset is kept: the retained words, the pty (the
 * USB bridge stays up), and the SIL's own counts the simulator waits on. */
static void firmware_reset(Sil *sil) {
  sil->resets++;
  ha_firmware_start(&sil->fw, &sil->board.iface, &ha_aircraft_config, &sil->opts);
  sil->board.pins.hp_reset = 0; /* the Due's pins come up low: the HP out of reset */
  fprintf(stderr, "ha_sil: reset %u (as a watchdog reset): home %s, airborne %u\n",
          (unsigned)sil->resets, sil->fw.ins.ins.home_latched ? "kept" : "none",
          (unsigned)sil->fw.app.core.airborne);
}

/* Lockstep: the simulator's records drive everything; between them the SIL sleeps. */
static void run_lockstep(Sil *sil) {
  uint8_t rec[128];
  SilBoard *b = &sil->board;
  while (!g_stop) {
    HaSilStep st;
    struct pollfd p;
    ssize_t n;
    p.fd = b->channel_fd;
    p.events = POLLIN;
    if (poll(&p, 1, 200) <= 0) {
      continue;
    }
    n = recv(b->channel_fd, rec, sizeof rec, 0);
    if (n <= 0) {
      fprintf(stderr, "ha_sil: simulator closed the control channel\n");
      break;
    }
    if (!ha_sil_decode_step(rec, (size_t)n, &st)) {
      fprintf(stderr, "ha_sil: dropped a control record of %zd bytes (not a step or poll)\n", n);
      continue;
    }
    if (st.magic == HA_SIL_MAGIC_RESET) {
      firmware_reset(sil);
      send_reply(sil, 0u, b->sim_now_us, 0u);
      continue;
    }
    if (st.magic == HA_SIL_MAGIC_POLL) {
      (void)ha_firmware_receive(&sil->fw, b->sim_now_us, UINT32_MAX);
      ha_firmware_service(&sil->fw, b->sim_now_us);
      send_reply(sil, 0u, b->sim_now_us, 0u);
      continue;
    }
    {
      uint16_t flags;
      double waited_s;
      /* The clock never runs backwards (the link requires it): a step to an earlier time is
       * taken as the current one. */
      if ((int32_t)((uint32_t)st.t_us - b->sim_now_us) > 0) {
        b->sim_now_us = (uint32_t)st.t_us;
      }
      waited_s = wall_s();
      flags = gather_period_inputs(sil, &st);
      waited_s = wall_s() - waited_s;
      b->pins.in = st;
      b->pins.have_in = 1;
      ha_firmware_period(&sil->fw, b->sim_now_us);
      ha_firmware_service(&sil->fw, b->sim_now_us);
      send_reply(sil, (uint16_t)(flags | HA_SIL_R_STEPPED), st.t_us, (uint32_t)(waited_s * 1e6));
    }
  }
}

/* Real time: the firmware's own schedule on the host clock; the simulator's records, if any,
 * only bring board inputs (and resets). SIGUSR1 pulls the cable for unplug_us. */
static void run_realtime(Sil *sil, uint32_t unplug_us) {
  SilBoard *b = &sil->board;
  uint32_t replug_at_us = 0u;
  int unplugged = 0;
  while (!g_stop) {
    const uint32_t now_us = b->iface.micros(b);
    if (g_unplug && !unplugged) {
      g_unplug = 0;
      sil_board_unplug(b);
      unplugged = 1;
      replug_at_us = now_us + unplug_us;
    }
    if (unplugged && (int32_t)(now_us - replug_at_us) >= 0 && sil_board_plug(b) == 0) {
      unplugged = 0;
    }
    if (b->channel_fd >= 0) {
      uint8_t rec[128];
      HaSilStep st;
      const ssize_t n = recv(b->channel_fd, rec, sizeof rec, MSG_DONTWAIT);
      if (n == 0) {
        break; /* the simulator is gone */
      }
      if (n > 0 && ha_sil_decode_step(rec, (size_t)n, &st) && st.magic == HA_SIL_MAGIC_STEP) {
        b->pins.in = st;
        b->pins.have_in = 1;
      } else if (n > 0 && ha_sil_decode_step(rec, (size_t)n, &st) &&
                 st.magic == HA_SIL_MAGIC_RESET) {
        firmware_reset(sil);
      }
    }
    if (ha_firmware_loop(&sil->fw) && b->channel_fd >= 0) {
      send_reply(sil, HA_SIL_R_STEPPED, sil->fw.period_at_us, 0u);
    }
    usleep(200); /* poll the pty often: command latency is part of what the bench measures */
  }
}

/* The command line: what the SIL serves and how. */
typedef struct {
  double rate_hz; /* 0: the aircraft's own period (its limits.yaml, compiled in) */
  uint32_t unplug_us;
  const char *vn200_path;
  const char *channel_path;
  int realtime;
} SilArgs;

/* Parses argv into args and the board's port; 0 when the command line is usable. */
static int parse_args(int argc, char **argv, Sil *sil, SilArgs *args) {
  int i;
  args->rate_hz = 0.0;
  args->unplug_us = 500000u;
  args->vn200_path = NULL;
  args->channel_path = NULL;
  args->realtime = 0;
  for (i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--realtime") == 0) {
      args->realtime = 1;
      continue;
    }
    if (i + 1 >= argc || strncmp(argv[i], "--", 2) != 0) {
      continue; /* roslaunch's __name:= and __log:= */
    }
    if (strcmp(argv[i], "--port") == 0) {
      sil->board.port_path = argv[++i];
    } else if (strcmp(argv[i], "--rate-hz") == 0) {
      args->rate_hz = atof(argv[++i]);
    } else if (strcmp(argv[i], "--unplug-ms") == 0) {
      args->unplug_us = (uint32_t)atoi(argv[++i]) * 1000u;
    } else if (strcmp(argv[i], "--param") == 0) {
      sil->opts.probe_param = argv[++i];
    } else if (strcmp(argv[i], "--vn200") == 0) {
      args->vn200_path = argv[++i];
    } else if (strcmp(argv[i], "--lockstep") == 0) {
      args->channel_path = argv[++i];
    } else if (strcmp(argv[i], "--latency-log") == 0) {
      sil->latency_log = fopen(argv[++i], "w");
      if (sil->latency_log != NULL) {
        setvbuf(sil->latency_log, NULL, _IOLBF, 0); /* readers watch it while we run */
      }
    }
  }
  if ((sil->board.port_path == NULL) ||
      !(args->rate_hz == 0.0 || (args->rate_hz >= 1.0 && args->rate_hz <= 1000.0))) {
    fprintf(stderr,
            "usage: ha_sil --port PATH [--rate-hz 1..1000] [--unplug-ms N] [--latency-log FILE]\n"
            "              [--param NAME] [--vn200 PATH] [--lockstep SOCKET [--realtime]]\n");
    return 2;
  }
  return 0;
}

/* The board's ports: the VN-200's, the simulator's channel, the HP link's pty. */
static int open_ports(Sil *sil, const SilArgs *args) {
  SilBoard *b = &sil->board;
  if (args->vn200_path != NULL && sil_board_open_vn200(b, args->vn200_path, &g_stop) != 0) {
    fprintf(stderr, "ha_sil: cannot open the VN-200 port %s: %s\n", args->vn200_path,
            strerror(errno));
    return 1;
  }
  if (args->channel_path != NULL && connect_channel(sil, args->channel_path) != 0) {
    fprintf(stderr, "ha_sil: cannot connect to the simulator at %s: %s\n", args->channel_path,
            strerror(errno));
    return 1;
  }
  b->pins.standalone = args->channel_path == NULL;
  if (sil_board_plug(b) != 0) {
    perror("ha_sil: openpty");
    return 1;
  }
  return 0;
}

static void close_ports_and_report(Sil *sil) {
  SilBoard *b = &sil->board;
  sil_board_unplug(b);
  if (b->vn_fd >= 0) {
    close(b->vn_fd);
  }
  if (b->channel_fd >= 0) {
    close(b->channel_fd);
  }
  if (sil->latency_log != NULL) {
    fclose(sil->latency_log);
  }
  fprintf(stderr,
          "ha_sil: %u commands, frames ok %u, bad checksum %u, skipped %u, unknown topic %u, "
          "VN-200 bytes %llu\n",
          (unsigned)sil->commands, (unsigned)sil->fw.link.decoder.counters.frames_ok,
          (unsigned)sil->fw.link.decoder.counters.bad_checksum,
          (unsigned)sil->fw.link.decoder.counters.bytes_skipped,
          (unsigned)sil->fw.link.counters.unknown_topic, (unsigned long long)b->vn_bytes);
}

int main(int argc, char **argv) {
  static Sil sil;
  SilBoard *b = &sil.board;
  SilArgs args;
  int status;
  memset(&sil, 0, sizeof sil);
  sil_board_init(b);
  status = parse_args(argc, argv, &sil, &args);
  if (status != 0) {
    return status;
  }
  signal(SIGINT, on_stop);
  signal(SIGTERM, on_stop);
  signal(SIGUSR1, on_unplug);
  signal(SIGPIPE, SIG_IGN);

  sil.opts.link_up_text = "HA SIL link up";
  sil.opts.period_us = args.rate_hz > 0.0 ? (uint32_t)(1e6 / args.rate_hz) : 0u;
  sil.opts.reads_per_pass = 8u; /* 512 bytes a port per pass, 200 us apart */
  /* Real time: on its own clock, as the Due; in lockstep the simulator's records set the periods.
   */
  sil.opts.pace_by_command = args.realtime;
  sil.opts.command_tap = on_command;
  sil.opts.tap_ctx = &sil;
  if (open_ports(&sil, &args) != 0) {
    return 1;
  }
  b->sim_clock = args.channel_path != NULL && !args.realtime;
  /* power-up: the retained words hold no record yet */
  ha_firmware_start(&sil.fw, &b->iface, &ha_aircraft_config, &sil.opts);
  if (b->sim_clock) {
    fprintf(stderr, "ha_sil: up on %s, lockstep with %s\n", b->port_path, args.channel_path);
    run_lockstep(&sil);
  } else {
    fprintf(stderr, "ha_sil: up on %s at %.0f Hz%s\n", b->port_path, 1e6 / sil.fw.period_us,
            args.channel_path != NULL ? " (board inputs from the simulator)" : "");
    run_realtime(&sil, args.unplug_us);
  }
  close_ports_and_report(&sil);
  return 0;
}
