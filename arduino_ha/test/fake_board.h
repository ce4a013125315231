// Host implementation of the HA Board interface: a simulated clock and recorded outputs, so a
// test sees exactly what the Due would put on its pins.
#ifndef ARDUINO_HA_TEST_FAKE_BOARD_H
#define ARDUINO_HA_TEST_FAKE_BOARD_H

#include <cstdint>
#include <deque>
#include <vector>

#include "ha_board.h"

struct FakeBoard {
  FakeBoard();
  FakeBoard(const FakeBoard&) = delete;
  FakeBoard& operator=(const FakeBoard&) = delete;

  // Sticks centred, throttle low, PIC switch at CIC (computer in command), receiver alive.
  void CenterSticks();
  void SetPilotInCommand(bool pilot);

  HaBoard iface;
  uint32_t now_us = 0;
  HaRcInputs rc{};
  float airspeed_ftps = 0.0f;
  bool airspeed_ok = true;
  bool pitot_noise = true;  // false: the reading repeats to the bit (a stuck sensor)
  uint32_t airspeed_reads = 0;
  float battery_v = 12.6f;
  bool battery_ok = true;
  std::vector<HaSurfaces> servo_writes;
  bool hp_reset = false;
  int hp_reset_assertions = 0;  // rising edges of the reset line
  uint8_t leds = 0;
  uint64_t watchdog_kicks = 0;
  // The backup registers: kept across a reset of the HA (a new HaApp on the same board).
  uint32_t retained[HA_RETAINED_WORDS] = {};
  uint32_t retained_writes = 0;
  // The two byte ports: bytes waiting to be read (the HP's, the VN-200's), and what the HA wrote
  // to the HP. Each read hands over what is waiting, as a UART's ring would.
  std::deque<uint8_t> hp_rx;
  std::vector<uint8_t> hp_tx;
  std::deque<uint8_t> ins_rx;
  uint32_t port_reads = 0;  // reads of either port
};

#endif  // ARDUINO_HA_TEST_FAKE_BOARD_H
