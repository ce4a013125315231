// The serial port over a pseudo-terminal: bytes both ways, and an unplug reported as -1.
#include <gtest/gtest.h>
#include <pty.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "serial_port.h"

namespace {

TEST(SerialPort, ExchangesBytesAndReportsTheDeviceVanishing) {
  int master = -1, slave = -1;
  ASSERT_EQ(0, openpty(&master, &slave, nullptr, nullptr, nullptr));
  const std::string path = ttyname(slave);
  vn200::SerialPort port;
  std::string error;
  ASSERT_TRUE(port.open(path, 921600, &error)) << error;
  close(slave);  // the port holds its own descriptor

  ASSERT_TRUE(port.write("$VNWRG,06,0*6C\r\n", 16));
  char got[32] = {};
  ssize_t n = read(master, got, sizeof got);
  ASSERT_EQ(16, n);
  EXPECT_EQ(0, std::memcmp(got, "$VNWRG,06,0*6C\r\n", 16));

  uint8_t buf[64];
  EXPECT_EQ(0, port.read(buf, sizeof buf, 10));  // nothing sent yet: a timeout, not an error
  ASSERT_EQ(3, write(master, "\xFA\x01\x08", 3));
  EXPECT_EQ(3, port.read(buf, sizeof buf, 500));
  EXPECT_EQ(0xFA, buf[0]);

  close(master);  // USB adapter unplugged
  long r = 0;
  for (int i = 0; i < 10 && r == 0; ++i) r = port.read(buf, sizeof buf, 100);
  EXPECT_EQ(-1, r);
}

TEST(SerialPort, MissingDeviceAndUnsupportedBaudAreErrorsNotCrashes) {
  vn200::SerialPort port;
  std::string error;
  EXPECT_FALSE(port.open("/nonexistent/vn200", 115200, &error));
  EXPECT_NE(std::string::npos, error.find("/nonexistent/vn200"));
  EXPECT_FALSE(port.open("/dev/null", 128000, &error));
  EXPECT_FALSE(port.isOpen());
  uint8_t b;
  EXPECT_EQ(-1, port.read(&b, 1, 0));
  EXPECT_FALSE(port.write("x", 1));
}

}  // namespace
