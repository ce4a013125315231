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
  b->pins.standalone = 1; /* until a simulator's channel is connected */
  ha_sil_pins_board(&b->iface);
  b->iface.ctx = b;
  b->iface.micros = board_micros;
  b->iface.hp_link = (HaBytePort){.read = hp_read, .write = hp_write};
  b->iface.ins = (HaBytePort){.read = ins_read, .write = NULL}; /* the HA never writes to it */
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
