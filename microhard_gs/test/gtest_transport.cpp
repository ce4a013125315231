// The serial transport against a pseudo-terminal standing in for the Microhard modem.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "serial_transport.h"
#include "udp_transport.h"

using namespace microhard_gs;

TEST(SerialTransport, BytesCrossThePseudoTerminalBothWays) {
  int master = -1, slave = -1;
  char name[128] = {};
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  std::string error;
  auto link = SerialTransport::open(name, 57600, &error);
  ASSERT_TRUE(link) << error;
  const uint8_t out[] = {0xFD, 0x01, 0x02, 0x03};
  ASSERT_TRUE(link->send(out, sizeof out));
  uint8_t got[16] = {};
  pollfd p{master, POLLIN, 0};
  ASSERT_EQ(poll(&p, 1, 2000), 1);
  ASSERT_EQ(read(master, got, sizeof got), 4);
  EXPECT_EQ(std::memcmp(got, out, 4), 0);
  const uint8_t in[] = {0xFE, 0x09};
  ASSERT_EQ(write(master, in, sizeof in), 2);
  pollfd q{link->fd(), POLLIN, 0};
  ASSERT_EQ(poll(&q, 1, 2000), 1);
  EXPECT_EQ(link->receive(got, sizeof got), 2);
  EXPECT_EQ(got[1], 0x09);
  EXPECT_EQ(link->receive(got, sizeof got), 0);  // nothing more: non-blocking
  link.reset();
  close(slave);
  close(master);
}

TEST(SerialTransport, UnsupportedBaudAndMissingPortAreReported) {
  std::string error;
  EXPECT_FALSE(SerialTransport::open("/dev/null", 12345, &error));
  EXPECT_NE(error.find("baud"), std::string::npos);
  EXPECT_FALSE(SerialTransport::open("/nonexistent/tty", 57600, &error));
  EXPECT_NE(error.find("/nonexistent/tty"), std::string::npos);
}

TEST(UdpTransport, BadAddressIsReported) {
  UdpConfig c;
  c.bind_address = "not-an-address";
  c.remote_address = "127.0.0.1";
  std::string error;
  EXPECT_FALSE(UdpTransport::open(c, &error));
  EXPECT_NE(error.find("not-an-address"), std::string::npos);
}
