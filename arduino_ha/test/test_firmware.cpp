// The firmware loop (src/firmware/ha_firmware.c), the one every board runs, over the fake board:
// a simulated clock, rosserial frames on the HP port as the host writes them, VN-200 packets on
// the INS port as the sensor sends them, and what the HA writes back to the host decoded again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "firmware_on_fake_board.h"
#include "ha_aircraft.h"
#include "link_test_util.h"
#include "vn_binary.h"
#include "vn_packet_builder.h"

namespace {

using link_test::Bytes;

constexpr uint16_t kTopicRequest = 0;
constexpr uint16_t kTopicLog = 7;
constexpr uint16_t kTopicPwm = HA_LINK_TOPIC_PWM;
constexpr uint16_t kTopicDecision = HA_LINK_TOPIC_DECISION_STATUS;

Bytes servo_frame(const HaHpCommand& c) {
  link_test::Cmd w;
  w.seq = c.seq;
  w.sec = c.stamp_sec;
  w.nsec = c.stamp_nsec;
  w.throttle = c.throttle;
  w.elevator = c.elevator_deg;
  w.aileron = c.aileron_deg;
  w.rudder = c.rudder_deg;
  w.alpha = c.alpha_est_deg;
  w.beta = c.beta_est_deg;
  w.converged = c.estimator_converged;
  w.healthy = c.sensor_links_healthy;
  w.crc = c.crc32;
  return link_test::frame(HA_LINK_TOPIC_SERVO_OP, link_test::servo_command_payload(w));
}

// msg/OperatorCommand.msg on the wire, sealed as microhard_gs seals it; the position is SET_HOME's.
Bytes operator_frame(uint8_t command, uint32_t request_id, double lat_deg = 0.0,
                     double lon_deg = 0.0, double alt_m = 0.0) {
  Bytes fields = link_test::operator_fields(command, request_id);  // use_current 0
  for (double v : {lat_deg, lon_deg, alt_m}) {
    uint8_t raw[8];
    std::memcpy(raw, &v, 8);  // little-endian like the wire
    fields.insert(fields.end(), raw, raw + 8);
  }
  return link_test::frame(HA_LINK_TOPIC_OPERATOR_COMMAND,
                          link_test::sealed_operator_payload(fields));
}

// A VN-200 Binary Output 1 packet: the aircraft parked at 45 N 122 W, 100 m, with a 3D fix.
Bytes parked_packet() {
  VnPacketBuilder b(VN_GROUP_COMMON | VN_GROUP_GPS,
                    {VN_COMMON_YPR | VN_COMMON_ANGULAR_RATE | VN_COMMON_POSITION |
                         VN_COMMON_VELOCITY | VN_COMMON_INS_STATUS,
                     VN_GPS_FIX});
  b.f32(10.0f).f32(0.0f).f32(0.0f);    // yaw, pitch, roll [deg]
  b.f32(0.0f).f32(0.0f).f32(0.0f);     // body rates [rad/s]
  b.f64(45.0).f64(-122.0).f64(100.0);  // latitude, longitude [deg], height [m]
  b.f32(0.0f).f32(0.0f).f32(0.0f);     // velocity NED [m/s]
  b.u16(0x0006u);                      // INS status: tracking, GNSS fix
  b.u8(3u);                            // GPS fix: 3D
  return b.finish();
}

// The log lines the HA sent to the host (rosserial_msgs/Log: level, then the text).
std::vector<std::string> logs(const Bytes& written) {
  link_test::Capture c;
  c.bytes = written;
  std::vector<std::string> out;
  for (const auto& f : c.frames()) {
    if (f.first == kTopicLog && f.second.size() >= 5u) {
      out.emplace_back(f.second.begin() + 5, f.second.end());
    }
  }
  return out;
}

size_t frames_on(const Bytes& written, uint16_t topic) {
  link_test::Capture c;
  c.bytes = written;
  size_t n = 0;
  for (const auto& f : c.frames()) n += f.first == topic ? 1u : 0u;
  return n;
}

}  // namespace

// The HP's command arrives on the HP port between two periods: the next period flies it. One
// period late would be the one late period the HA tolerates, spent on every command.
TEST(HaFirmwareStories, ServoFrameOnTheHpPortReachesTheServosInTheSamePeriod) {
  FirmwareOnFakeBoard ha;
  ha.Negotiate();
  ASSERT_TRUE(ha.ReachHp(servo_frame));
  ha.Pass();  // a pass after the period: the next command arrives mid-period
  const HaHpCommand cmd = ha.NextCommand(3.5f);
  ha.Hp(servo_frame(cmd));
  const uint32_t periods_before = ha.periods;
  const HaOutputs& out = ha.Period();
  EXPECT_EQ(ha.periods, periods_before + 1u);
  EXPECT_EQ(out.controller, HA_CONTROLLER_HP);
  EXPECT_EQ(out.last_seq, cmd.seq);
  EXPECT_FLOAT_EQ(ha.board.servo_writes.back().aileron_deg, 3.5f);
  EXPECT_EQ(ha.fw.link.counters.commands, ha.seq - 1000u);  // every frame sent, decoded
}

// SET_HOME is the INS adapter's: it moves home (judged on the core's on-the-ground verdict) and
// is answered in the host's log; the decision logic never sees it as a request of its own.
TEST(HaFirmwareStories, SetHomeFromTheLinkIsRoutedToTheInsAdapter) {
  FirmwareOnFakeBoard ha;
  ha.cruising = false;
  ha.board.airspeed_ftps = 0.0f;  // the pitot reads still air: parked
  ha.Negotiate();
  for (int i = 0; i < 50 && !ha.fw.ins.ins.home_latched; ++i) {
    ha.Ins(parked_packet());
    ha.Period();
  }
  ASSERT_EQ(ha.fw.ins.ins.home_latched, 1u) << "no home from parked VN-200 packets on the INS port";
  const uint32_t home_seq = ha.fw.ins.ins.home_seq;
  const uint32_t requests_for_the_core = ha.fw.app.requests.count;
  ha.Ins(parked_packet());
  ha.Hp(operator_frame(HA_OP_SET_HOME, 77u, 45.001, -122.002, 101.5));
  ha.Period();
  EXPECT_EQ(ha.fw.ins.ins.home_seq, home_seq + 1u);
  EXPECT_DOUBLE_EQ(ha.fw.ins.ins.home.lat_deg, 45.001);
  EXPECT_DOUBLE_EQ(ha.fw.ins.ins.home.lon_deg, -122.002);
  EXPECT_EQ(ha.fw.app.requests.count, requests_for_the_core);
  const std::vector<std::string> said = logs(ha.board.hp_tx);
  EXPECT_NE(std::find(said.begin(), said.end(), "SET_HOME: home moved"), said.end());
}

// Every other request is the core's: queued, executed in its period and acknowledged.
TEST(HaFirmwareStories, SelectHaFromTheLinkIsQueuedForTheCoreAndAcknowledged) {
  FirmwareOnFakeBoard ha;
  ha.Negotiate();
  ASSERT_TRUE(ha.ReachHp(servo_frame));
  const uint32_t home_seq = ha.fw.ins.ins.home_seq;
  ha.Hp(operator_frame(HA_OP_SELECT_HA, 41u));
  const HaOutputs& out = ha.PeriodWithCommand(servo_frame);
  EXPECT_EQ(out.controller, HA_CONTROLLER_HA);
  EXPECT_EQ(out.reasons & HA_REASON_GROUND_COMMAND, HA_REASON_GROUND_COMMAND);
  EXPECT_EQ(ha.fw.app.requests.ack_id, 41u);
  EXPECT_EQ(ha.fw.app.requests.ack_accepted, 1u);
  EXPECT_EQ(ha.fw.ins.ins.home_seq, home_seq);
}

// The watchdog is kicked by a period that ran, never by a pass that only serviced the ports: a
// loop stuck before its period (a hung I2C read, say) stops kicking and the chip resets.
TEST(HaFirmwareStories, WatchdogIsKickedOnlyWhenTheStepRan) {
  FirmwareOnFakeBoard ha;
  ha.Period();  // the first, at the first pass
  ha.Period();  // then on the schedule
  const uint64_t kicks = ha.board.watchdog_kicks;
  int ran = 0;
  for (uint32_t pass = 0; pass < 9u; ++pass) {  // 9 ms of a 10 ms period
    ran += ha.Pass();
  }
  EXPECT_EQ(ran, 0);
  EXPECT_EQ(ha.board.watchdog_kicks, kicks);
  for (uint32_t pass = 0; pass < 991u; ++pass) ran += ha.Pass();  // to 1 s after that period
  EXPECT_EQ(ran, 100);                                            // one period every 10 ms
  EXPECT_EQ(ha.board.watchdog_kicks, kicks + 100u);
}

// A loop held up for 55 ms runs one period, not a burst of five catching up, and keeps the period
// after it.
TEST(HaFirmwareStories, ALoopHeldUpForFivePeriodsRunsOnePeriodNotABurst) {
  FirmwareOnFakeBoard ha;
  ha.Period();
  const uint64_t kicks = ha.board.watchdog_kicks;
  EXPECT_EQ(ha.Pass(55000u), 1);
  for (int i = 0; i < 9; ++i) EXPECT_EQ(ha.Pass(), 0) << "pass " << i << " after the stall";
  EXPECT_EQ(ha.Pass(), 1);
  EXPECT_EQ(ha.board.watchdog_kicks, kicks + 2u);
}

// The reports: nothing before the host asks for topics; then a DecisionStatus and a pwm every
// period, and the host hears the link is up.
TEST(HaFirmwareStories, DecisionStatusAndPwmGoToTheHostEveryPeriodOnceItNegotiated) {
  HaFirmwareOptions opts{};
  opts.link_up_text = "HA test link up";
  FirmwareOnFakeBoard ha(&opts);
  for (int i = 0; i < 10; ++i) ha.Period();
  EXPECT_TRUE(ha.board.hp_tx.empty()) << "the HA spoke before the host asked for its topics";
  ha.Negotiate();
  ha.board.hp_tx.clear();
  for (int i = 0; i < 10; ++i) ha.Period();
  EXPECT_EQ(frames_on(ha.board.hp_tx, kTopicDecision), 10u);
  EXPECT_EQ(frames_on(ha.board.hp_tx, kTopicPwm), 10u);
  ha.board.hp_tx.clear();
  ha.Negotiate();  // the host restarted and asks again
  const std::vector<std::string> said = logs(ha.board.hp_tx);
  EXPECT_EQ(std::count(said.begin(), said.end(), "HA test link up"), 1);
}

// What the HA's link throws away the host cannot see: the HA says what it dropped, once per new
// drop, in the words the link stories read ("link errors: name N ...").
TEST(HaFirmwareStories, AFrameCorruptedOnTheHpPortIsReportedInTheHostsLog) {
  FirmwareOnFakeBoard ha;
  ha.Negotiate();
  ha.Period();
  Bytes bad = servo_frame(ha.NextCommand());
  bad[20] ^= 0x01u;  // a payload bit: the frame's checksum fails
  ha.Hp(bad);
  for (int i = 0; i < 30; ++i) ha.Period();  // 300 ms: past the 200 ms between reports
  const std::vector<std::string> said = logs(ha.board.hp_tx);
  size_t reports = 0;
  for (const std::string& s : said) {
    if (s.rfind("link errors:", 0) == 0) {
      ++reports;
      EXPECT_NE(s.find(" bad_checksum 1 "), std::string::npos) << s;
    }
  }
  EXPECT_EQ(reports, 1u);
}

// The SIL's --param: the answer to the probe parameter comes back in the host's log.
TEST(HaFirmwareStories, ProbeParameterAnswerIsLoggedBackWithItsValues) {
  HaFirmwareOptions opts{};
  opts.probe_param = "link_probe";
  FirmwareOnFakeBoard ha(&opts);
  ha.Negotiate();
  Bytes reply;  // rosserial_msgs/RequestParamResponse: int32[] ints, float32[] floats, string[]
  link_test::put_u32(reply, 2u);
  link_test::put_u32(reply, 42u);
  link_test::put_u32(reply, static_cast<uint32_t>(-2147483647 - 1));
  link_test::put_u32(reply, 0u);
  link_test::put_u32(reply, 0u);
  ha.Hp(link_test::frame(6, reply));
  ha.Period();
  const std::vector<std::string> said = logs(ha.board.hp_tx);
  EXPECT_NE(std::find(said.begin(), said.end(), "param link_probe: 42 -2147483648"), said.end());
}

// A board with no INS wired and no way back to the HP (a bench Due with only the servos): the
// loop still flies its periods on what it has, reading and writing nothing it was not given.
TEST(HaFirmwareStories, ABoardWithoutAnInsPortOrAWayBackToTheHpStillRunsItsPeriods) {
  FirmwareOnFakeBoard ha;
  ha.board.iface.ins.read = nullptr;
  ha.board.iface.hp_link.write = nullptr;
  ha.Ins(parked_packet());  // bytes on a port the board does not have: never read
  ha.Negotiate();           // the host asks, the HA cannot answer
  const uint32_t periods = ha.periods;
  for (int i = 0; i < 10; ++i) ha.Period();
  EXPECT_EQ(ha.periods, periods + 10u);
  EXPECT_EQ(ha.board.watchdog_kicks, ha.periods);
  EXPECT_EQ(ha.board.ins_rx.size(), parked_packet().size());
  EXPECT_TRUE(ha.board.hp_tx.empty());
  EXPECT_EQ(ha.fw.link.counters.topic_requests, 1u);  // the HP port is still read
}

// ---- paced by the command (HaFirmwareOptions.pace_by_command: the Due, and the SIL and QEMU in
// real time). T is the aircraft's period (10 ms at 100 Hz).

const HaFirmwareOptions kPaced = [] {
  HaFirmwareOptions o{};
  o.pace_by_command = 1;
  return o;
}();

struct PacedHaFlownByTheHp : FirmwareOnFakeBoard {
  PacedHaFlownByTheHp() : FirmwareOnFakeBoard(&kPaced) {
    Negotiate();
    EXPECT_TRUE(ReachHp(servo_frame));
  }
};

// On a free clock the command waited for the HA's next period: up to T, at whatever phase the
// HP's timer had to it (sensor to servo 12 ms in the HiL, issue 24).
TEST(HaFirmwarePacing, TheServosTakeTheHpCommandInThePassItArrives) {
  PacedHaFlownByTheHp ha;
  const uint32_t T = ha.cfg.period_us;
  const uint32_t last = ha.fw.period_at_us;
  for (int i = 0; i < 8; ++i) EXPECT_EQ(ha.Pass(T / 10u), 0) << "no period before a command";
  ha.Hp(servo_frame(ha.NextCommand(3.5f)));
  EXPECT_EQ(ha.Pass(T / 50u), 1);
  EXPECT_EQ(ha.fw.period_at_us - last, 8u * T / 10u + T / 50u);
  EXPECT_EQ(ha.fw.app.outputs.controller, HA_CONTROLLER_HP);
  EXPECT_FLOAT_EQ(ha.board.servo_writes.back().aileron_deg, 3.5f);
}

// An HP babbling at five times the rate cannot speed the HA up past 4/3 of it.
TEST(HaFirmwarePacing, AnHpBabblingFasterIsTakenAtMostEveryThreeQuartersOfAPeriod) {
  PacedHaFlownByTheHp ha;
  const uint32_t T = ha.cfg.period_us;
  uint32_t last = ha.fw.period_at_us;
  int periods = 0;
  for (int i = 0; i < 100; ++i) {  // 2 ms apart: 200 ms
    ha.Hp(servo_frame(ha.NextCommand()));
    if (ha.Pass(T / 5u)) {
      EXPECT_GE(ha.fw.period_at_us - last, 3u * T / 4u);
      last = ha.fw.period_at_us;
      ++periods;
    }
  }
  EXPECT_EQ(periods, 25);  // every 8 ms: the first pass at or past 7.5 ms
  EXPECT_EQ(ha.fw.app.outputs.controller, HA_CONTROLLER_HP);
}

// The deadline, paced: the first period without a command comes 5/4 T after the last with one
// (a command a little late still gets its own period), the next T later; with one late period
// tolerated, that second one takes over for DEADLINE_MISS, 9/4 T after the HP's last command
// period (a free clock: up to 3 T).
TEST(HaFirmwarePacing, ASilentHpIsTakenOverNineQuartersOfAPeriodAfterItsLastCommand) {
  PacedHaFlownByTheHp ha;
  const uint32_t T = ha.cfg.period_us;
  const uint32_t last = ha.fw.period_at_us;
  while (!ha.Pass(T / 20u)) {
  }
  EXPECT_EQ(ha.fw.period_at_us - last, 5u * T / 4u);
  EXPECT_EQ(ha.fw.app.outputs.controller, HA_CONTROLLER_HP) << "one late period is tolerated";
  while (!ha.Pass(T / 20u)) {
  }
  EXPECT_EQ(ha.fw.period_at_us - last, 9u * T / 4u);
  EXPECT_EQ(ha.fw.app.outputs.controller, HA_CONTROLLER_HA);
  EXPECT_NE(ha.fw.app.outputs.reasons_at_switch & HA_REASON_DEADLINE_MISS, 0u);
  // Flying on its own the HA keeps its rate.
  for (int i = 0; i < 5; ++i) {
    const uint32_t before = ha.fw.period_at_us;
    ha.Period();
    EXPECT_EQ(ha.fw.period_at_us - before, T);
  }
}

// Commands coming back at any phase to the HA's clock (the HA flying alone, then the HP's
// first command) run their period on arrival from the fourth on, and none is counted late.
TEST(HaFirmwarePacing, CommandsAtAnyPhaseAreTakenOnArrivalFromTheFourthOn) {
  for (uint32_t tenths = 1; tenths < 10; ++tenths) {
    FirmwareOnFakeBoard ha(&kPaced);
    const uint32_t T = ha.cfg.period_us;
    ha.Period();
    const uint32_t first = ha.board.now_us + tenths * T / 10u;
    for (uint32_t k = 0; k < 8; ++k) {
      const uint32_t arrival = first + k * T;
      while (ha.board.now_us + 100u < arrival) ha.Pass(100u);
      ha.Hp(servo_frame(ha.NextCommand()));
      const uint32_t periods = ha.periods;
      ha.Pass(arrival - ha.board.now_us);
      if (k >= 3) {
        EXPECT_EQ(ha.periods, periods + 1u) << "phase " << tenths << "/10, command " << k;
        EXPECT_EQ(ha.fw.app.core.late_periods, 0u) << "phase " << tenths << "/10, command " << k;
      }
    }
  }
}
