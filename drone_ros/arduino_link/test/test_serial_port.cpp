// The serial port on a pseudo-terminal, as the node uses it: opened at the chosen (non-standard)
// baud, bytes both ways, and "gone" reported when the other end disappears (USB unplug).
#include <gtest/gtest.h>
#include <pty.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "serial_port.h"

using arduino_link::SerialPort;

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
}  // namespace

TEST(SerialPort, OpensAtTheChosenNonStandardBaudAndCarriesBytesBothWays) {
  Pty pty;
  SerialPort port;
  std::string error;
  ASSERT_TRUE(port.open(pty.name, 250000, &error)) << error;
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
  std::string error;
  ASSERT_TRUE(port.open(pty.name, 115200, &error)) << error;
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(port.read(buf, sizeof buf, 20, &got), SerialPort::ReadResult::kTimeout);
}

TEST(SerialPort, UnplugIsReportedAsGone) {
  Pty pty;
  SerialPort port;
  std::string error;
  ASSERT_TRUE(port.open(pty.name, 250000, &error)) << error;
  close(pty.master);
  close(pty.slave);
  pty.master = pty.slave = -1;
  uint8_t buf[16];
  std::size_t got = 0;
  EXPECT_EQ(port.read(buf, sizeof buf, 200, &got), SerialPort::ReadResult::kGone);
}

TEST(SerialPort, MissingDeviceAndAbsurdBaudAreRefusedWithAReason) {
  SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/nonexistent/ttyACM9", 250000, &error));
  EXPECT_FALSE(error.empty());
  EXPECT_FALSE(SerialPort::baud_supported(0));
  EXPECT_FALSE(SerialPort::baud_supported(50000000));
  EXPECT_TRUE(SerialPort::baud_supported(250000));
}
