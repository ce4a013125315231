// The shared serial port on pseudo-terminals, as the `arduino` and `vn200` nodes use it: opened
// at standard and non-standard rates (and really running at them), bytes both ways, silence told
// apart from an unplug, whole writes through a full buffer, and every failure a reason, never a
// crash.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "drone_ros_common/serial_port.h"
#include "termios2_probe.h"

using drone_ros_common::SerialPort;

namespace {

struct Pty {
  int master = -1, slave = -1;
  std::string name;
  Pty() {
    char buf[128];
    EXPECT_EQ(openpty(&master, &slave, buf, nullptr, nullptr), 0);
    name = buf;
  }
  ~Pty() {
    if (master >= 0) close(master);
    if (slave >= 0) close(slave);
  }
};

// Reads the pty's device end until `want` bytes came or nothing more arrives for a second.
// Reads the device end until `want` bytes came, or until nothing has come for a generous while
// (the writer gave up: the test then fails on what was seen instead of hanging).
std::vector<uint8_t> drain(int master, std::size_t want) {
  std::vector<uint8_t> seen;
  uint8_t chunk[4096];
  while (seen.size() < want) {
    pollfd pfd{master, POLLIN, 0};
    const int ready = poll(&pfd, 1, 10000);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) break;
    const ssize_t n = read(master, chunk, sizeof chunk);
    if (n > 0) {
      seen.insert(seen.end(), chunk, chunk + n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  return seen;
}

// Opens port at baud; on failure the assertion carries the port's reason.
testing::AssertionResult opened(SerialPort *port, const std::string &path, int baud) {
  std::string error;
  if (port->open(path, baud, &error)) return testing::AssertionSuccess();
  return testing::AssertionFailure() << error;
}

std::vector<uint8_t> pattern(std::size_t len) {
  std::vector<uint8_t> v(len);
  for (std::size_t i = 0; i < len; ++i) v[i] = static_cast<uint8_t>((i * 7u) ^ (i >> 8));
  return v;
}

}  // namespace

// --- From the arduino link: the Due's 250000 baud, silence vs. unplug ---------------------------

TEST(SerialPort, OpensAtTheChosenNonStandardBaudAndCarriesBytesBothWays) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 250000));
  EXPECT_EQ(tty_output_baud(pty.slave), 250000);
  const uint8_t out[] = {0xFF, 0xFE, 0x00, 0x00, 0xFF, 0x00, 0x00, 0xFF};
  ASSERT_TRUE(port.write_all(out, sizeof out));
  uint8_t seen[16] = {0};
  ASSERT_EQ(read(pty.master, seen, sizeof seen), static_cast<ssize_t>(sizeof out));
  EXPECT_EQ(0, memcmp(seen, out, sizeof out));
  const uint8_t in[] = {1, 2, 3};
  ASSERT_EQ(write(pty.master, in, sizeof in), 3);
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(port.read(buf, sizeof buf, 500, &got), SerialPort::ReadResult::kData);
  EXPECT_EQ(got, 3u);
}

TEST(SerialPort, SilenceIsATimeoutNotAnError) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 115200));
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(port.read(buf, sizeof buf, 20, &got), SerialPort::ReadResult::kTimeout);
  EXPECT_EQ(got, 0u);
  EXPECT_TRUE(port.is_open());
}

TEST(SerialPort, UnplugIsReportedAsGone) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 250000));
  close(pty.master);
  close(pty.slave);
  pty.master = pty.slave = -1;
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(port.read(buf, sizeof buf, 200, &got), SerialPort::ReadResult::kGone);
  EXPECT_FALSE(port.write_all(buf, 1));
}

TEST(SerialPort, MissingDeviceAndAbsurdBaudAreRefusedWithAReason) {
  SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/nonexistent/ttyACM9", 250000, &error));
  EXPECT_NE(std::string::npos, error.find("/nonexistent/ttyACM9")) << error;
  EXPECT_NE(std::string::npos, error.find(std::strerror(ENOENT))) << error;
  EXPECT_FALSE(SerialPort::baud_supported(0));
  EXPECT_FALSE(SerialPort::baud_supported(50000000));
  EXPECT_TRUE(SerialPort::baud_supported(250000));
  Pty pty;
  EXPECT_FALSE(port.open(pty.name, 50000000, &error));
  EXPECT_NE(std::string::npos, error.find("50000000")) << error;
  EXPECT_FALSE(port.is_open());
}

// What a user sees when the port will not open: the port and what to do about it.
TEST(SerialPort, AMissingDeviceNamesThePortAndTheByIdPath) {
  SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/dev/ttyACM_not_plugged", 115200, &error));
  EXPECT_NE(std::string::npos, error.find("/dev/ttyACM_not_plugged")) << error;
  EXPECT_NE(std::string::npos, error.find("plugged in")) << error;
  EXPECT_NE(std::string::npos, error.find("/dev/serial/by-id/")) << error;
}

TEST(SerialPort, APathThatIsNoSerialDeviceSaysSo) {
  SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/dev/null", 115200, &error));
  EXPECT_NE(std::string::npos, error.find("not a serial device")) << error;
}

// As root every device opens, so the denied user is a child that drops to nobody's ids first.
TEST(SerialPort, APortThisUserMayNotOpenNamesTheDialoutGroup) {
  Pty pty;
  // Root's child becomes nobody, whom 0600 keeps out; a developer's own pty needs 0000.
  ASSERT_EQ(0, chmod(pty.name.c_str(), getuid() == 0 ? 0600 : 0000));
  int pipe_fds[2];
  ASSERT_EQ(0, pipe(pipe_fds));
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    const uid_t nobody = 65534;
    if (getuid() == 0 && (setgid(nobody) != 0 || setuid(nobody) != 0)) _exit(2);
    SerialPort port;
    std::string error;
    const bool opened = port.open(pty.name, 115200, &error);
    const ssize_t w = write(pipe_fds[1], error.data(), error.size());
    _exit(opened ? 1 : (w < 0 ? 3 : 0));
  }
  ::close(pipe_fds[1]);
  std::string error;
  char buf[512];
  ssize_t n;
  while ((n = read(pipe_fds[0], buf, sizeof buf)) > 0) error.append(buf, static_cast<size_t>(n));
  ::close(pipe_fds[0]);
  int status = 0;
  ASSERT_EQ(child, waitpid(child, &status, 0));
  ASSERT_TRUE(WIFEXITED(status));
  ASSERT_EQ(0, WEXITSTATUS(status))
      << "the unprivileged child opened the port, or could not drop privileges";
  EXPECT_NE(std::string::npos, error.find(pty.name)) << error;
  EXPECT_NE(std::string::npos, error.find(std::strerror(EACCES))) << error;
  EXPECT_NE(std::string::npos, error.find("usermod -aG dialout")) << error;
}

// --- From the VN-200 driver: its command line, its rates, the adapter vanishing -----------------

TEST(SerialPort, ExchangesBytesAndReportsTheDeviceVanishing) {
  int master = -1, slave = -1;
  ASSERT_EQ(0, openpty(&master, &slave, nullptr, nullptr, nullptr));
  const std::string path = ttyname(slave);
  SerialPort port;
  ASSERT_TRUE(opened(&port, path, 921600));
  EXPECT_EQ(tty_output_baud(slave), 921600);
  close(slave);  // the port holds its own descriptor

  ASSERT_TRUE(port.write_all("$VNWRG,06,0*6C\r\n", 16));
  char seen[32] = {};
  ASSERT_EQ(16, read(master, seen, sizeof seen));
  EXPECT_EQ(0, std::memcmp(seen, "$VNWRG,06,0*6C\r\n", 16));

  uint8_t buf[64];
  std::size_t got = 0;
  // Nothing sent yet: a timeout, not an error.
  EXPECT_EQ(SerialPort::ReadResult::kTimeout, port.read(buf, sizeof buf, 10, &got));
  ASSERT_EQ(3, write(master, "\xFA\x01\x08", 3));
  EXPECT_EQ(SerialPort::ReadResult::kData, port.read(buf, sizeof buf, 500, &got));
  EXPECT_EQ(3u, got);
  EXPECT_EQ(0xFA, buf[0]);

  close(master);  // USB adapter unplugged
  auto r = SerialPort::ReadResult::kTimeout;
  for (int i = 0; i < 10 && r == SerialPort::ReadResult::kTimeout; ++i) {
    r = port.read(buf, sizeof buf, 100, &got);
  }
  EXPECT_EQ(SerialPort::ReadResult::kGone, r);
}

TEST(SerialPort, MissingDeviceAndUnsupportedBaudAreErrorsNotCrashes) {
  SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/nonexistent/vn200", 115200, &error));
  EXPECT_NE(std::string::npos, error.find("/nonexistent/vn200"));
  // Not a tty at all: refused with the reason, not configured blindly.
  EXPECT_FALSE(port.open("/dev/null", 115200, &error));
  EXPECT_NE(std::string::npos, error.find("/dev/null")) << error;
  // Before the shared port, 128000 was refused here (termios has no constant for it); it now
  // opens (see the next test), so the rate refused is one below what any UART here runs at.
  Pty pty;
  EXPECT_FALSE(port.open(pty.name, 600, &error));
  EXPECT_NE(std::string::npos, error.find("baud 600")) << error;
  EXPECT_FALSE(port.is_open());
  uint8_t b;
  std::size_t got = 0;
  EXPECT_EQ(SerialPort::ReadResult::kGone, port.read(&b, 1, 0, &got));
  EXPECT_FALSE(port.write_all("x", 1));
}

TEST(SerialPort, OpensAtTheVn200s128000BaudThatTermiosHasNoConstantFor) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 128000));
  EXPECT_EQ(tty_output_baud(pty.slave), 128000);
  ASSERT_TRUE(port.write_all("$VNRRG,01*72\r\n", 14));
  char seen[32] = {};
  ASSERT_EQ(14, read(pty.master, seen, sizeof seen));
  EXPECT_EQ(0, std::memcmp(seen, "$VNRRG,01*72\r\n", 14));
}

// --- Behaviour both nodes rely on ----------------------------------------------------------------

TEST(SerialPort, StandardRatesStayVisibleToTermiosReaders) {
  // Tools that read the speed through plain termios (the fake VN-200 does) must see B115200,
  // not "custom": standard rates are set with their termios constant.
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 115200));
  termios tio{};
  ASSERT_EQ(0, tcgetattr(pty.slave, &tio));
  EXPECT_EQ(B115200, cfgetospeed(&tio));
  EXPECT_EQ(B115200, cfgetispeed(&tio));
  EXPECT_EQ(0u, tio.c_lflag & (ECHO | ICANON));  // raw: a binary protocol, no echo back
}

TEST(SerialPort, ReopeningDropsBytesThatArrivedBeforeAndFindsTheDeviceAgain) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 250000));
  ASSERT_EQ(5, write(pty.master, "stale", 5));
  // Wait until the bytes sit in the tty's input queue, so the reopen has something to drop.
  int queued = 0;
  for (int i = 0; i < 200 && queued < 5; ++i) {
    ASSERT_EQ(0, ioctl(pty.slave, FIONREAD, &queued));
    if (queued < 5) usleep(10000);
  }
  ASSERT_EQ(5, queued);
  ASSERT_TRUE(opened(&port, pty.name, 250000));
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(SerialPort::ReadResult::kTimeout, port.read(buf, sizeof buf, 20, &got));
  ASSERT_EQ(3, write(pty.master, "new", 3));
  ASSERT_EQ(SerialPort::ReadResult::kData, port.read(buf, sizeof buf, 500, &got));
  EXPECT_EQ(0, std::memcmp(buf, "new", 3));
}

TEST(SerialPort, LargeWriteArrivesWholeThroughPartialWritesWhileTheDeviceDrains) {
  // Far more than a tty buffer holds, so the driver takes it in pieces and says "full" between.
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 921600));
  // The device thread drains when the scheduler lets it: on a loaded machine that can take
  // longer than the default stall, which is not what this test is about.
  port.set_write_stall_ms(10000);
  const std::vector<uint8_t> out = pattern(256 * 1024);
  std::vector<uint8_t> seen;
  std::thread device([&] { seen = drain(pty.master, out.size()); });
  EXPECT_TRUE(port.write_all(out.data(), out.size()));
  device.join();
  EXPECT_EQ(seen, out);
}

TEST(SerialPort, DeviceThatStopsDrainingMakesWriteGiveUpInsteadOfHanging) {
  Pty pty;  // nobody reads the device end: its buffer fills and stays full
  SerialPort port;
  ASSERT_TRUE(opened(&port, pty.name, 921600));
  const std::vector<uint8_t> out = pattern(1024 * 1024);
  EXPECT_FALSE(port.write_all(out.data(), out.size()));
  EXPECT_TRUE(port.is_open());  // stalled, not gone: the node decides what to do
}

namespace {
std::atomic<int> g_alarms{0};
void on_alarm(int) { g_alarms.fetch_add(1); }
}  // namespace

TEST(SerialPort, SignalsDuringReadAndWriteAreNotMistakenForUnplug) {
  // A 1 ms interval timer without SA_RESTART interrupts poll() and write() over and over.
  struct sigaction sa {};
  sa.sa_handler = on_alarm;
  sigemptyset(&sa.sa_mask);
  struct sigaction old {};
  ASSERT_EQ(0, sigaction(SIGALRM, &sa, &old));
  itimerval every_ms{{0, 1000}, {0, 1000}};
  ASSERT_EQ(0, setitimer(ITIMER_REAL, &every_ms, nullptr));

  Pty pty;
  SerialPort port;
  std::string error;
  const bool open_ok = port.open(pty.name, 250000, &error);
  port.set_write_stall_ms(10000);  // a slow device thread on a loaded machine is not a signal
  uint8_t buf[16];
  std::size_t got = 0;
  const auto silent = port.read(buf, sizeof buf, 200, &got);
  const std::vector<uint8_t> out = pattern(128 * 1024);
  std::vector<uint8_t> seen;
  std::thread device([&] { seen = drain(pty.master, out.size()); });
  const bool written = port.write_all(out.data(), out.size());
  device.join();

  itimerval off{};
  setitimer(ITIMER_REAL, &off, nullptr);
  sigaction(SIGALRM, &old, nullptr);
  ASSERT_TRUE(open_ok) << error;
  EXPECT_GT(g_alarms.load(), 0);
  EXPECT_EQ(SerialPort::ReadResult::kTimeout, silent);
  EXPECT_TRUE(written);
  EXPECT_EQ(seen, out);
}

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
