#define _DEFAULT_SOURCE
#include "ha_sil_board.h"

#include <errno.h>
#include <fcntl.h>
#include <pty.h>
#include <stdio.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

static SilBoard *as_sil(void *ctx) { return (SilBoard *)ctx; }

/* The host clock or the simulator's. */
static uint32_t board_micros(void *ctx) {
  struct timespec ts;
  if (as_sil(ctx)->sim_clock) {
    return as_sil(ctx)->sim_now_us;
  }
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint32_t)((uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u);
}

static void board_write_servos(void *ctx, const HaSurfaces *s) {
  (void)ctx;
  (void)s; /* the simulator reads the core's outputs, which is what was written */
}

/* Without a simulator a healthy receiver in computer-in-command and a pitot at 60 ft/s; with one
 * the inputs of its latest record. */
static void board_read_rc(void *ctx, HaRcInputs *rc) {
  const SilBoard *b = as_sil(ctx);
  int k;
  if (b->have_board_in) {
    for (k = 0; k < HA_RC_CHANNELS; ++k) {
      rc->pulse_us[k] = b->board_in.rc_pulse_us[k];
    }
    rc->valid = (uint8_t)((b->board_in.flags & HA_SIL_RC_VALID) != 0u);
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
  const SilBoard *b = as_sil(ctx);
  if (b->have_board_in) {
    *v = b->board_in.airspeed_ftps;
    return (b->board_in.flags & HA_SIL_AIRSPEED_OK) != 0u;
  }
  /* In a simulator's loop the board reads nothing until the simulator's first record (real time:
   * the SIL's periods start before it): a made-up 60 ft/s would latch airborne on the ground. */
  *v = 60.0f;
  return b->channel_fd < 0;
}

static int board_read_battery(void *ctx, float *v) {
  const SilBoard *b = as_sil(ctx);
  if (b->have_board_in) {
    *v = b->board_in.battery_v;
    return (b->board_in.flags & HA_SIL_BATTERY_OK) != 0u;
  }
  *v = 12.1f;
  return b->channel_fd < 0;
}

static void board_set_hp_reset(void *ctx, int asserted) { as_sil(ctx)->hp_reset = asserted; }

static void board_set_leds(void *ctx, uint8_t leds) {
  (void)ctx;
  (void)leds; /* the simulator reads the core's outputs */
}

static void board_kick(void *ctx) { (void)ctx; }

static int board_read_retained(void *ctx, uint32_t words[HA_RETAINED_WORDS]) {
  memcpy(words, as_sil(ctx)->retained, sizeof as_sil(ctx)->retained);
  return 1;
}

static void board_write_retained(void *ctx, const uint32_t words[HA_RETAINED_WORDS]) {
  memcpy(as_sil(ctx)->retained, words, sizeof as_sil(ctx)->retained);
}

static size_t read_fd(int fd, uint8_t *bytes, size_t max_len) {
  const ssize_t n = fd >= 0 ? read(fd, bytes, max_len) : -1;
  return n > 0 ? (size_t)n : 0u;
}

static size_t hp_read(void *ctx, uint8_t *bytes, size_t max_len) {
  return read_fd(as_sil(ctx)->master_fd, bytes, max_len);
}

static void hp_write(void *ctx, const uint8_t *bytes, size_t len) {
  const SilBoard *b = as_sil(ctx);
  size_t done = 0u;
  while (b->master_fd >= 0 && done < len) {
    const ssize_t n = write(b->master_fd, bytes + done, len - done);
    if (n <= 0) {
      return; /* host not reading (EAGAIN): drop, as a full USB buffer on the Due would */
    }
    done += (size_t)n;
  }
}

static size_t ins_read(void *ctx, uint8_t *bytes, size_t max_len) {
  const size_t n = read_fd(as_sil(ctx)->vn_fd, bytes, max_len);
  as_sil(ctx)->vn_bytes += n;
  return n;
}

void sil_board_init(SilBoard *b) {
  memset(b, 0, sizeof *b);
  b->master_fd = -1;
  b->slave_fd = -1;
  b->vn_fd = -1;
  b->channel_fd = -1;
  b->iface = (HaBoard){.ctx = b,
                       .micros = board_micros,
                       .write_servos = board_write_servos,
                       .read_rc = board_read_rc,
                       .read_airspeed_ftps = board_read_airspeed,
                       .read_battery_v = board_read_battery,
                       .set_hp_reset = board_set_hp_reset,
                       .set_leds = board_set_leds,
                       .kick_watchdog = board_kick,
                       .read_retained = board_read_retained,
                       .write_retained = board_write_retained,
                       .hp_link = {.read = hp_read, .write = hp_write},
                       /* the HA never writes to its VN-200 */
                       .ins = {.read = ins_read, .write = NULL}};
}

int sil_board_plug(SilBoard *b) {
  char name[128];
  char tmp[600];
  struct termios tio;
  if (openpty(&b->master_fd, &b->slave_fd, name, NULL, NULL) != 0) {
    return -1;
  }
  /* Raw both ways before anyone opens it, so no line discipline touches the bytes. */
  if (tcgetattr(b->slave_fd, &tio) == 0) {
    cfmakeraw(&tio);
    (void)tcsetattr(b->slave_fd, TCSANOW, &tio);
  }
  (void)fcntl(b->master_fd, F_SETFL, fcntl(b->master_fd, F_GETFL) | O_NONBLOCK);
  snprintf(tmp, sizeof tmp, "%s.tmp", b->port_path);
  (void)unlink(tmp);
  if ((symlink(name, tmp) != 0) || (rename(tmp, b->port_path) != 0)) {
    return -1;
  }
  return 0;
}

void sil_board_unplug(SilBoard *b) {
  (void)unlink(b->port_path);
  if (b->master_fd >= 0) {
    close(b->master_fd);
  }
  if (b->slave_fd >= 0) {
    close(b->slave_fd);
  }
  b->master_fd = -1;
  b->slave_fd = -1;
}

int sil_board_open_vn200(SilBoard *b, const char *path, volatile const sig_atomic_t *stop) {
  struct termios tio;
  int tries;
  for (tries = 0; tries < 300 && !*stop; ++tries) { /* the simulator may still be starting */
    b->vn_fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (b->vn_fd >= 0) {
      if (tcgetattr(b->vn_fd, &tio) == 0) {
        cfmakeraw(&tio);
        (void)cfsetspeed(&tio, B115200); /* DUE_VN200_BAUD */
        (void)tcsetattr(b->vn_fd, TCSANOW, &tio);
      }
      return 0;
    }
    usleep(100000);
  }
  return -1;
}
