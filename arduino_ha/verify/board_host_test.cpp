// Runs the real sketch (arduino_ha.ino's setup/loop: board layer, core, link) on the host against
// verify/arduino_shim/fake_arduino.cpp, with scripted time, RC edges, I2C replies and ADC counts.
// One timeline, checked as stories; exits non-zero naming every failed story. Built and run by
// board_compile_check.sh. What it cannot show (timing on the chip, the real libraries) is listed
// in README.md.
#include <Arduino.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "arduino_shim/fake_arduino.h"
#include "src/board_due/due_board.h"
#include "src/board_due/due_config.h"
#include "src/board_due/due_main.h"
#include "src/core/ha_aircraft.h"
#include "src/vn200/ha_vn200_feed.h"
#include "src/vn200/vn_checksum.h"

namespace {

int g_failures = 0;
int g_checks = 0;

void check(bool ok, const char *story, const char *what) {
  ++g_checks;
  if (!ok) {
    std::printf("FAIL %s: %s\n", story, what);
    ++g_failures;
  }
}

const uint32_t kRcPins[5] = {DUE_PIN_RC_THROTTLE, DUE_PIN_RC_ELEVATOR, DUE_PIN_RC_AILERON,
                             DUE_PIN_RC_RUDDER, DUE_PIN_RC_PIC};
const uint32_t kServoPins[4] = {DUE_PIN_SERVO_ELEVATOR, DUE_PIN_SERVO_AILERON, DUE_PIN_SERVO_RUDDER,
                                DUE_PIN_SERVO_THROTTLE};

const fake::ServoRecord *servo_on(uint32_t pin) {
  for (uint32_t i = 0u; i < fake::state.servo_count; ++i) {
    if (fake::state.servos[i].pin == static_cast<int>(pin)) {
      return &fake::state.servos[i];
    }
  }
  return nullptr;
}

int pulse_on(uint32_t pin) {
  const fake::ServoRecord *r = servo_on(pin);
  return r != nullptr ? r->pulse_us : -1;
}

// One 20 ms receiver frame: every channel's pulse (if rc_on), then loop() once per millisecond.
void run_frame(const uint16_t widths_us[5], bool rc_on) {
  const uint32_t t0 = fake::state.now_us;
  if (rc_on) {
    for (uint32_t ch = 0u; ch < 5u; ++ch) {
      fake::state.now_us = t0;
      fake::set_pin(kRcPins[ch], 1);
      fake::state.now_us = t0 + widths_us[ch];
      fake::set_pin(kRcPins[ch], 0);
    }
  }
  for (uint32_t ms = 3u; ms <= 20u; ++ms) {
    fake::state.now_us = t0 + ms * 1000u;
    due_main_loop();
  }
}

void run_ms(uint32_t ms, const uint16_t widths_us[5], bool rc_on) {
  for (uint32_t t = 0u; t < ms; t += 20u) {
    run_frame(widths_us, rc_on);
  }
}

// One VN-200 solution and its binary output packet as the sensor sends it (manual, "Binary
// Output Messages"): Common group with yaw/pitch/roll, angular rate, LLA position, NED velocity
// and INS status; GPS group with the fix type; little-endian fields, big-endian CRC-16.
struct Vn200Solution {
  float ypr_deg[3];
  float rate_radps[3];
  double lla[3];
  float vel_ned_mps[3];
  uint16_t ins_status;
  uint8_t gps_fix;
};

const Vn200Solution kParkedAtHome = {{10.0f, 0.0f, 0.0f},
                                     {0.0f, 0.0f, 0.0f},
                                     {45.0, -122.0, 100.0},
                                     {0.0f, 0.0f, 0.0f},
                                     0x0006u /* tracking, GNSS fix */,
                                     3u};
const Vn200Solution kFlying50mUp = {{90.0f, 4.0f, -15.0f},
                                    {0.1f, 0.0f, -0.2f},
                                    {45.0, -122.0, 150.0},
                                    {0.0f, 25.0f, 0.0f},
                                    0x0006u,
                                    3u};

size_t put(uint8_t *out, size_t n, const void *value, size_t size) {
  std::memcpy(out + n, value, size);  // the host is little-endian like the sensor's fields
  return n + size;
}

size_t vn200_packet(const Vn200Solution &s, uint8_t *out) {
  const uint16_t common = VN_COMMON_YPR | VN_COMMON_ANGULAR_RATE | VN_COMMON_POSITION |
                          VN_COMMON_VELOCITY | VN_COMMON_INS_STATUS;
  const uint16_t gps = VN_GPS_FIX;
  size_t n = 0u;
  out[n++] = VN_BIN_SYNC;
  out[n++] = VN_GROUP_COMMON | VN_GROUP_GPS;
  n = put(out, n, &common, 2u);
  n = put(out, n, &gps, 2u);
  n = put(out, n, s.ypr_deg, 12u);
  n = put(out, n, s.rate_radps, 12u);
  n = put(out, n, s.lla, 24u);
  n = put(out, n, s.vel_ned_mps, 12u);
  n = put(out, n, &s.ins_status, 2u);
  n = put(out, n, &s.gps_fix, 1u);
  const uint16_t crc = vn_crc16(out + 1, n - 1u);
  out[n++] = static_cast<uint8_t>(crc >> 8);
  out[n++] = static_cast<uint8_t>(crc & 0xFFu);
  return n;
}

// The firmware's VN-200 feed on the Due, as the sketch runs it.
const HaVn200Feed &due_feed() { return due_main_firmware()->ins; }
const HaIns *due_ins_state() { return &due_feed().ins; }
void send_vn200(const Vn200Solution &s) {
  uint8_t pkt[VN_BIN_MAX_PACKET];
  const size_t len = vn200_packet(s, pkt);
  (void)fake::serial1_feed(pkt, len);
}

}  // namespace

int main() {
  fake::reset();
  fake::state.now_us = 1000000u;
  watchdogSetup();  // the SAM core's init() calls it before setup()
  due_main_setup();

  check(fake::state.watchdog_timeout_ms == DUE_WATCHDOG_TIMEOUT_MS, "WatchdogEnabledBeforeSetup",
        "watchdogSetup() did not enable the watchdog");
  check(fake::state.servo_count == 0u, "NothingDrivenBeforeFirstPeriod",
        "servos attached before the core decided anything");
  check(fake::state.pin_mode[DUE_PIN_HP_RESET] == OUTPUT &&
            fake::state.written[DUE_PIN_HP_RESET] == LOW,
        "HpNotHeldInResetAtBoot", "HP reset line not an output driven low");
  check(fake::state.i2c_clock_hz == DUE_I2C_CLOCK_HZ && fake::state.adc_bits == DUE_ADC_BITS,
        "SensorsConfiguredAtBoot", "I2C clock or ADC resolution not set");

  // Receiver alive, sticks centred, computer in command (PIC channel low).
  const uint16_t cic[5] = {1000u, 1500u, 1500u, 1500u, 1100u};
  const uint32_t kicks_before = fake::state.watchdog_kicks;
  run_ms(1000u, cic, true);
  const uint32_t periods = fake::state.watchdog_kicks - kicks_before;
  check(periods >= 99u && periods <= 101u, "OnePeriodEvery10ms",
        "watchdog kicks (one per completed period) in 1 s not 100");
  check(fake::state.servo_count == 4u, "FourServosAttachedAtFirstPeriod",
        "not exactly four servos attached");
  bool ranges_ok = true;
  for (uint32_t pin : kServoPins) {
    const fake::ServoRecord *r = servo_on(pin);
    ranges_ok = ranges_ok && r != nullptr &&
                r->min_us == static_cast<int>(ha_aircraft_config.servo_pulse_min_us) &&
                r->max_us == static_cast<int>(ha_aircraft_config.servo_pulse_max_us) &&
                r->writes >= 99u;
  }
  check(ranges_ok, "ServosGetConfiguredRangeAndAWriteEveryPeriod",
        "servo pin, pulse range or write count wrong");
  check(fake::state.written[DUE_PIN_LED_MANUAL] == LOW, "NoManualWhilePicSwitchLow",
        "manual LED on with the PIC switch low");

  // Pilot flips PIC/CIC to pilot in command, sticks away from centre.
  const uint16_t pic[5] = {1250u, 2000u, 1000u, 1500u, 1900u};
  run_ms(2000u, pic, true);
  check(fake::state.written[DUE_PIN_LED_MANUAL] == HIGH, "PilotSwitchSelectsManual",
        "manual LED off after the PIC switch went high");
  check(std::abs(pulse_on(DUE_PIN_SERVO_ELEVATOR) - 2000) <= 2 &&
            std::abs(pulse_on(DUE_PIN_SERVO_AILERON) - 1000) <= 2 &&
            std::abs(pulse_on(DUE_PIN_SERVO_RUDDER) - 1500) <= 2 &&
            std::abs(pulse_on(DUE_PIN_SERVO_THROTTLE) - 1250) <= 2,
        "PilotSticksReachServosInManual", "servo pulses do not follow the RC sticks");

  // Receiver goes silent while the switch was at PIC: RC lost is not manual.
  run_ms(300u, pic, false);
  check(fake::state.written[DUE_PIN_LED_MANUAL] == LOW, "RcLostLeavesManual",
        "still manual 300 ms after the receiver went silent");

  // The loop stalls for 55 ms (e.g. an I2C hang): one period runs, not a burst of five.
  run_ms(100u, cic, true);
  const uint32_t kicks_at_stall = fake::state.watchdog_kicks;
  fake::state.now_us += 55000u;
  due_main_loop();
  due_main_loop();
  check(fake::state.watchdog_kicks - kicks_at_stall == 1u, "StalledLoopRunsOnePeriodNotABurst",
        "catch-up burst after a stall");

  // The VN-200 talks to the Due on Serial1: parked at home first, then flying; a packet
  // corrupted on the wire in between is counted and dropped. Home latches only when the core says
  // on the ground (its verdict of the period after a parked solution): with no pitot it cannot.
  const uint64_t bytes_before = due_feed().counts.bytes_read;
  send_vn200(kParkedAtHome);
  run_ms(20u, cic, true);
  send_vn200(kParkedAtHome);
  run_ms(20u, cic, true);
  check(due_ins_state()->home_latched == 0u, "NoHomeWithoutAPitotToVouchForTheGround",
        "home latched while the pitot read nothing");
  const uint8_t still_air[4] = {0x0Cu, 0xCDu, 0x40u, 0x00u};  // 3277 counts: 0 Pa
  for (uint32_t i = 0u; i < 4u; ++i) {
    fake::state.i2c_reply[i] = still_air[i];
  }
  fake::state.i2c_reply_len = 4u;
  run_ms(20u, cic, true);
  send_vn200(kParkedAtHome);
  run_ms(20u, cic, true);
  check(due_ins_state()->home_latched == 1u, "HomeLatchedParkedOnTheGround",
        "no home after a parked solution with the pitot reading still air");
  {
    uint8_t pkt[VN_BIN_MAX_PACKET];
    const size_t len = vn200_packet(kFlying50mUp, pkt);
    pkt[20] ^= 0x40u;
    (void)fake::serial1_feed(pkt, len);
  }
  send_vn200(kFlying50mUp);
  // Split across loop passes as the UART delivers it: a 64-byte read never holds a whole packet.
  run_ms(40u, cic, true);
  check(due_feed().counts.bytes_read > bytes_before && due_feed().counts.binary_packets == 4u &&
            due_feed().ins.solutions_used == 4u,
        "Vn200PacketsOnSerial1BecomeHaState", "four intact packets did not give four solutions");
  check(vn_framer_bad_packets(&due_feed().framer.stats) == 1u &&
            due_feed().ins.solutions_rejected == 0u,
        "CorruptedVn200PacketCountedAndDropped", "the corrupted packet was not counted as bad");
  {
    // The same bytes through a copy of the Due's feed (its home) into a state the test can read:
    // HA units, from home.
    HaVn200Feed feed = due_feed();
    uint8_t pkt[VN_BIN_MAX_PACKET];
    const size_t len = vn200_packet(kFlying50mUp, pkt);
    HaInputs in;
    std::memset(&in, 0, sizeof in);
    ha_vn200_feed_bytes(&feed, pkt, len, &in, 0u, 123456u);
    check(in.state_valid == 1u && in.state_rx_us == 123456u &&
              std::fabs(in.altitude_agl_ft - 164.04f) < 0.01f &&
              std::fabs(in.heading_deg - 90.0f) < 1e-4f && std::fabs(in.roll_deg + 15.0f) < 1e-4f &&
              std::fabs(in.r_deg_s + 11.459f) < 0.01f && std::fabs(in.north_ft) < 0.01f &&
              in.on_ground == 0u,
          "Vn200SolutionInHaUnitsFromHome", "decoded state not in ft, deg, deg/s from home");
    Vn200Solution no_fix = kFlying50mUp;
    no_fix.ins_status = 0x0002u;  // tracking but the GNSS fix bit clear
    const size_t no_fix_len = vn200_packet(no_fix, pkt);
    ha_vn200_feed_bytes(&feed, pkt, no_fix_len, &in, 0u, 223456u);
    check(in.state_rx_us == 123456u, "Vn200WithoutFixIsDroppedUnstamped",
          "a solution without GNSS fix stamped the state");
    Vn200Solution nan_roll = kFlying50mUp;
    nan_roll.ypr_deg[2] = std::nanf("");  // CRC-valid, one field NaN
    const size_t nan_len = vn200_packet(nan_roll, pkt);
    ha_vn200_feed_bytes(&feed, pkt, nan_len, &in, 0u, 323456u);
    check(
        in.state_valid == 1u && in.state_rx_us == 123456u && std::fabs(in.roll_deg + 15.0f) < 1e-4f,
        "Vn200NanPacketLeavesLastGoodState",
        "a CRC-valid packet with a NaN field invalidated or changed the last good state");
  }

  // A watchdog reset in flight: setup() runs again with RAM afresh; the backup registers bring
  // back home and the airborne latch (a power-up with them cleared brings back neither).
  {
    const GeoRef home = due_ins_state()->home;
    due_main_setup();
    check(due_ins_state()->home_latched == 1u && due_ins_state()->home.lat_deg == home.lat_deg &&
              std::fabs(due_ins_state()->home.alt_m - home.alt_m) < 1e-3,
          "HomeKeptAcrossAWatchdogReset", "home lost or moved by a reset");
    for (uint32_t i = 0u; i < HA_RETAINED_WORDS; ++i) {
      fake_gpbr.SYS_GPBR[i] = 0u;  // the power went
    }
    due_main_setup();
    check(due_ins_state()->home_latched == 0u, "NoHomeAfterAPowerUp",
          "home came back from cleared backup registers");
  }

  // The board's own readings, through the HaBoard interface of a second board instance.
  DueBoard board;
  due_board_begin(&board, &ha_aircraft_config);
  const HaBoard *b = due_board_interface(&board);
  const uint8_t mid_scale[4] = {0x40u, 0x00u, 0x40u, 0x00u};  // 16384 counts each
  for (uint32_t i = 0u; i < 4u; ++i) {
    fake::state.i2c_reply[i] = mid_scale[i];
  }
  fake::state.i2c_reply_len = 4u;
  float airspeed_ftps = -1.0f;
  const int ok = b->read_airspeed_ftps(b->ctx, &airspeed_ftps);
  check(ok == 1 && std::fabs(airspeed_ftps - 134.82f) < 0.05f &&
            fake::state.i2c_last_address == DUE_AMS5812_I2C_ADDRESS,
        "AirspeedReadFromAms5812", "mid-scale reading is not 134.8 ft/s from address 0x78");
  fake::state.i2c_reply_len = 2u;
  check(b->read_airspeed_ftps(b->ctx, &airspeed_ftps) == 0 && board.airspeed_failures == 1u,
        "ShortI2cReplyCountedAndDropped", "a 2-byte reply was accepted or not counted");
  fake::state.adc_counts = 2048u;
  float battery_v = 0.0f;
  check(b->read_battery_v(b->ctx, &battery_v) == 1 && std::fabs(battery_v - 9.407f) < 0.01f,
        "BatteryVoltageThroughDivider", "2048 counts is not 9.41 V");
  b->set_hp_reset(b->ctx, 1);
  check(fake::state.written[DUE_PIN_HP_RESET] == HIGH, "HpResetLineFollowsCore",
        "set_hp_reset(1) did not drive the line high");

  if (g_failures == 0) {
    std::printf("board_host_test: %d checks passed\n", g_checks);
  }
  return g_failures == 0 ? 0 : 1;
}
