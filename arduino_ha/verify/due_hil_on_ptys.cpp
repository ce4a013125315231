// A Due running its HIL build, emulated at its real interfaces, for the simulator's end of the
// Due in the loop (hil/ha_due.py, run_flight.py --ha due) where no Due is plugged in: the sketch
// (arduino_ha.ino's setup/loop with HA_DUE_HIL=1: due_hil_board.cpp, the firmware loop, the core)
// runs on the host against arduino_shim/fake_arduino.cpp, on the host's monotonic clock, and
// each of the Due's three ports is a pty whose slave is published under a path, as the USB
// devices of a real bench appear:
//   --prog PATH    Serial, the programming port: the HP link (the `arduino` node; /dev/ttyACM0)
//   --native PATH  SerialUSB, the native port: the simulator's records and replies (/dev/ttyACM1)
//   --rx1 PATH     Serial1's receive pin: the VN-200's port 1 through a USB-serial adapter
//                  (/dev/ttyUSB0)
// It runs until SIGINT or SIGTERM and removes the paths. Each port keeps its own slave open, so a
// host that closes and reopens its end never finds the pty hung up. A port takes from its pty
// only what its receive ring has room for (the rest waits in the pty, as USB's flow control keeps
// it at the host); what the host does not read in time is dropped, as a USB-serial bridge with
// no reader drops it, and counted. What it does not emulate: the chip's timing (the host is far
// faster), its watchdog reset, and a baud rate (a pty has none). Built by
// board_compile_check.sh; hil/test/test_due_flight.py flies against it.
#include <Arduino.h>
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include "arduino_shim/fake_arduino.h"
#include "src/board_due/due_main.h"

namespace {

volatile sig_atomic_t g_stop = 0;
void on_stop(int sig) {
  (void)sig;
  g_stop = 1;
}

struct PortPty {
  const char *name;
  std::string link;
  int master;
  int slave;
  unsigned long tx_dropped;
};

PortPty g_ports[3] = {
    {"prog", "", -1, -1, 0u}, {"rx1", "", -1, -1, 0u}, {"native", "", -1, -1, 0u}};

bool open_pty(PortPty *p) {
  if (openpty(&p->master, &p->slave, nullptr, nullptr, nullptr) != 0) {
    return false;
  }
  for (int fd : {p->master, p->slave}) {
    termios t;
    if (tcgetattr(fd, &t) != 0) {
      return false;
    }
    cfmakeraw(&t);
    (void)tcsetattr(fd, TCSANOW, &t);
  }
  (void)fcntl(p->master, F_SETFL, fcntl(p->master, F_GETFL) | O_NONBLOCK);
  const std::string tmp = p->link + ".tmp";
  (void)unlink(tmp.c_str());
  return symlink(ttyname(p->slave), tmp.c_str()) == 0 && rename(tmp.c_str(), p->link.c_str()) == 0;
}

size_t to_host(fake::Port port, const uint8_t *bytes, size_t len) {
  PortPty &p = g_ports[port];
  const ssize_t n = write(p.master, bytes, len);
  const size_t sent = n > 0 ? static_cast<size_t>(n) : 0u;
  p.tx_dropped += len - sent;
  /* The sketch sees its bytes taken: a UART's transmitter does not know whether anyone listens. */
  return port == fake::kSerialUsb ? sent : len;
}

void from_host(fake::Port port) {
  uint8_t bytes[4096];
  size_t room = fake::room(port);
  if (room > sizeof bytes) {
    room = sizeof bytes;
  }
  if (room == 0u) {
    return;
  }
  const ssize_t n = read(g_ports[port].master, bytes, room);
  if (n <= 0) {
    return;
  }
  const size_t len = static_cast<size_t>(n);
  (void)(port == fake::kSerial    ? fake::serial0_feed(bytes, len)
         : port == fake::kSerial1 ? fake::serial1_feed(bytes, len)
                                  : fake::usb_feed(bytes, len));
}

uint64_t monotonic_us() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<uint64_t>(ts.tv_sec) * 1000000u + static_cast<uint64_t>(ts.tv_nsec) / 1000u;
}

}  // namespace

int main(int argc, char **argv) {
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string opt = argv[i];
    PortPty *p = opt == "--prog"     ? &g_ports[fake::kSerial]
                 : opt == "--rx1"    ? &g_ports[fake::kSerial1]
                 : opt == "--native" ? &g_ports[fake::kSerialUsb]
                                     : nullptr;
    if (p == nullptr) {
      std::fprintf(stderr, "due_hil_on_ptys: unknown option %s\n", argv[i]);
      return 2;
    }
    p->link = argv[i + 1];
  }
  for (PortPty &p : g_ports) {
    if (p.link.empty()) {
      std::fprintf(stderr, "usage: due_hil_on_ptys --prog PATH --native PATH --rx1 PATH\n");
      return 2;
    }
  }
  std::signal(SIGINT, on_stop);
  std::signal(SIGTERM, on_stop);
  std::signal(SIGPIPE, SIG_IGN);
  int code = 0;
  for (PortPty &p : g_ports) {
    if (!open_pty(&p)) {
      std::fprintf(stderr, "due_hil_on_ptys: cannot publish %s at %s: %s\n", p.name, p.link.c_str(),
                   std::strerror(errno));
      code = 1;
    }
  }
  const uint64_t start_us = monotonic_us();
  if (code == 0) {
    fake::reset();
    fake::state.tx_sink = to_host;
    fake::state.now_us = 1000000u;
    watchdogSetup();  // the SAM core's init() calls it before setup()
    due_main_setup();
    std::fprintf(stderr, "due_hil_on_ptys: up: prog %s, native %s, rx1 %s\n",
                 g_ports[fake::kSerial].link.c_str(), g_ports[fake::kSerialUsb].link.c_str(),
                 g_ports[fake::kSerial1].link.c_str());
  }
  while (code == 0 && !g_stop) {
    pollfd fds[3];
    for (int k = 0; k < 3; ++k) {
      fds[k] = pollfd{g_ports[k].master, POLLIN, 0};
    }
    /* A pass every 200 us at the latest: the period (10 ms) starts on time, and a command is taken
     * within a fraction of it, as the Due's loop() spins. */
    const timespec wait = {0, 200000};
    if (ppoll(fds, 3, &wait, nullptr) > 0) {
      for (int k = 0; k < 3; ++k) {
        if ((fds[k].revents & POLLIN) != 0) {
          from_host(static_cast<fake::Port>(k));
        }
      }
    }
    fake::state.now_us = static_cast<uint32_t>(1000000u + (monotonic_us() - start_us));
    due_main_loop();
  }
  for (PortPty &p : g_ports) {
    if (!p.link.empty()) {
      (void)unlink(p.link.c_str());
    }
    for (int fd : {p.master, p.slave}) {
      if (fd >= 0) {
        (void)close(fd);
      }
    }
  }
  std::fprintf(
      stderr,
      "due_hil_on_ptys: stopped; bytes no host read: prog %lu, native %lu; watchdog kicks %u\n",
      g_ports[fake::kSerial].tx_dropped, g_ports[fake::kSerialUsb].tx_dropped,
      fake::state.watchdog_kicks);
  return code;
}
