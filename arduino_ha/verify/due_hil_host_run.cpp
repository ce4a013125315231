// The Due's HIL build (arduino_ha.ino's setup/loop with HA_DUE_HIL=1: due_hil_board.cpp, the
// firmware loop, the core) run on the host against arduino_shim/fake_arduino.cpp, driven by a
// script on stdin that test/test_due_hil_board.py writes with the simulator's own record encoders
// (hil/ha_channel.py, hil/ha_qemu.py's frame()):
//   usb <hex>     bytes the host sends on the native USB port (SerialUSB)
//   close / open  the host closes / opens that port (the CDC line state)
//   run <ms>      loop() once a millisecond of fake time for that long
// It prints each `run <ms>` it starts and, for every period the firmware ran, what the core got
// from the board that period:
//   period <t_us> <rc throttle elevator aileron rudder pic> <rc valid> <airspeed ft/s> <battery V>
// and at the end every byte the sketch wrote on the native port: `usb_tx <hex>`.
// Built by board_compile_check.sh.
#include <Arduino.h>

#include <cstdio>
#include <cstring>

#include "arduino_shim/fake_arduino.h"
#include "src/board_due/due_main.h"

namespace {

bool feed_hex(const char *hex) {
  uint8_t bytes[2048];
  size_t n = 0u;
  unsigned byte = 0u;
  int used = 0;
  while (hex[0] != '\0' && hex[0] != '\n') {
    if (n == sizeof bytes || std::sscanf(hex, "%2x%n", &byte, &used) != 1 || used != 2) {
      return false;
    }
    bytes[n++] = static_cast<uint8_t>(byte);
    hex += 2;
  }
  return fake::usb_feed(bytes, n) == 1;
}

void run_ms(unsigned ms) {
  const HaFirmware *fw = due_main_firmware();
  for (unsigned k = 0u; k < ms; ++k) {
    fake::state.now_us += 1000u;
    const uint32_t kicks = fake::state.watchdog_kicks;
    due_main_loop();
    if (fake::state.watchdog_kicks != kicks) {  // one kick a completed period
      const HaInputs &in = fw->app.inputs;
      std::printf("period %u %u %u %u %u %u %u %.3f %.3f\n", fw->period_at_us, in.rc.pulse_us[0],
                  in.rc.pulse_us[1], in.rc.pulse_us[2], in.rc.pulse_us[3], in.rc.pulse_us[4],
                  in.rc.valid, static_cast<double>(in.airspeed_ftps),
                  static_cast<double>(fw->app.battery_v));
    }
  }
}

}  // namespace

int main() {
  static char line[8192];
  fake::reset();
  fake::state.now_us = 1000000u;
  watchdogSetup();  // the SAM core's init() calls it before setup()
  due_main_setup();
  while (std::fgets(line, sizeof line, stdin) != nullptr) {
    unsigned ms = 0u;
    if (std::strncmp(line, "usb ", 4u) == 0) {
      if (!feed_hex(line + 4)) {
        std::fprintf(stderr, "due_hil_host_run: bad or too many bytes: %s", line);
        return 2;
      }
    } else if (std::strcmp(line, "close\n") == 0) {
      fake::state.usb_open = 0;
    } else if (std::strcmp(line, "open\n") == 0) {
      fake::state.usb_open = 1;
    } else if (std::sscanf(line, "run %u", &ms) == 1) {
      std::printf("run %u\n", ms);
      run_ms(ms);
    } else {
      std::fprintf(stderr, "due_hil_host_run: unknown line: %s", line);
      return 2;
    }
  }
  std::printf("usb_tx ");
  for (size_t i = 0u; i < fake::state.usb_tx_len; ++i) {
    std::printf("%02x", fake::state.usb_tx[i]);
  }
  std::printf("\n");
  return 0;
}
