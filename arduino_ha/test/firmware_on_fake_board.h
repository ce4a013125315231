// The firmware loop (src/firmware/) on the fake board, as every board runs it, for stories told
// through the bytes on its two ports: a simulated clock, the loop called every millisecond as a
// Due's loop() is (far more often, there), the host answering time requests as the arduino node
// does.
#ifndef ARDUINO_HA_TEST_FIRMWARE_ON_FAKE_BOARD_H
#define ARDUINO_HA_TEST_FIRMWARE_ON_FAKE_BOARD_H

#include <cstdint>

#include "fake_board.h"
#include "ha_aircraft.h"
#include "ha_firmware.h"
#include "ha_test_util.h"
#include "link_test_util.h"

struct FirmwareOnFakeBoard {
  HaAircraftConfig cfg = ha_aircraft_config;
  FakeBoard board;
  HaFirmware fw{};
  bool cruising = true;  // false: the INS state comes only from the INS port
  uint32_t seq = 1000;
  uint32_t last_time_reply_us = 0;
  uint32_t periods = 0;

  explicit FirmwareOnFakeBoard(const HaFirmwareOptions* opts = nullptr) {
    board.now_us = 5000000u;  // not zero: time zero is not special
    ha_firmware_start(&fw, &board.iface, &cfg, opts);
  }
  void Hp(const link_test::Bytes& b) { board.hp_rx.insert(board.hp_rx.end(), b.begin(), b.end()); }
  void Ins(const link_test::Bytes& b) {
    board.ins_rx.insert(board.ins_rx.end(), b.begin(), b.end());
  }
  void Negotiate() {
    Hp(link_test::frame(0u, {}));  // rosserial's topic request
    Pass();
  }
  // One pass of the loop `us` after the last; returns 1 when it ran a period.
  int Pass(uint32_t us = 1000u) {
    board.now_us += us;
    if (cruising) {
      WriteCruiseState(cfg, &fw.app.inputs, board.now_us - 100u, 200.0f, 60.0f);
      board.airspeed_ftps = 60.0f;
    }
    if (board.now_us - last_time_reply_us >= 400000u) {
      link_test::Bytes t;
      link_test::put_u32(t, 1700000000u + board.now_us / 1000000u);
      link_test::put_u32(t, 0u);
      Hp(link_test::frame(10u, t));  // rosserial's time topic
      last_time_reply_us = board.now_us;
    }
    const int ran = ha_firmware_loop(&fw);
    periods += static_cast<uint32_t>(ran);
    return ran;
  }
  // Passes until one has run a period.
  const HaOutputs& Period() {
    for (int i = 0; i < 100 && !Pass(); ++i) {
    }
    return fw.app.outputs;
  }
  HaHpCommand NextCommand(float aileron_deg = 2.0f) {
    return MakeCommand(++seq, 0.45f, -1.0f, aileron_deg, 0.5f);
  }
  // The period, with the next command (framed by `frame`) and `extra` bytes on the HP port.
  template <typename Frame>
  const HaOutputs& PeriodWithCommand(Frame frame, const link_test::Bytes& extra = {},
                                     float aileron_deg = 2.0f) {
    Hp(frame(NextCommand(aileron_deg)));
    Hp(extra);
    return Period();
  }
  // Valid commands until the HP flies and the handover slew is over.
  template <typename Frame>
  bool ReachHp(Frame frame) {
    for (int i = 0; i < 1000; ++i) {
      if (PeriodWithCommand(frame).controller == HA_CONTROLLER_HP &&
          !fw.app.core.transition_active) {
        return true;
      }
    }
    return false;
  }
};

#endif  // ARDUINO_HA_TEST_FIRMWARE_ON_FAKE_BOARD_H
