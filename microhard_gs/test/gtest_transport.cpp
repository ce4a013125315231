// The links against stand-ins: a pseudo-terminal for the Microhard modem (reached through a
// symlink, as udev's by-id name reaches the real one), a loopback socket for UDP.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "serial_transport.h"
#include "udp_transport.h"

using namespace microhard_gs;

namespace {

// A pty whose slave is reachable at `link`, like the modem at /dev/serial/by-id/...
struct Modem {
  int master = -1;
  int slave = -1;
  std::string slave_name;
  void plug(const std::string& link) {
    char name[128] = {};
    ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
    slave_name = name;
    ::unlink(link.c_str());
    ASSERT_EQ(::symlink(name, link.c_str()), 0);
  }
  // The USB device vanishing: the master side goes, the slave reads EIO / hang-up.
  void unplug() {
    ::close(master);
    ::close(slave);
    master = slave = -1;
  }
  ~Modem() {
    if (master >= 0) ::close(master);
    if (slave >= 0) ::close(slave);
  }
};

// A fresh directory for the modem's name, removed with it.
struct TempLink {
  std::string dir;
  std::string path;
  TempLink() {
    char tmpl[] = "/tmp/gs_transport_XXXXXX";
    EXPECT_NE(mkdtemp(tmpl), nullptr);
    dir = tmpl;
    path = dir + "/modem";
  }
  ~TempLink() {
    ::unlink(path.c_str());
    ::rmdir(dir.c_str());
  }
};

// Sends from the vehicle and reads what reached the modem.
bool vehicle_to_modem(SerialTransport* link, int master) {
  const uint8_t out[] = {0xFD, 0x01, 0x02, 0x03};
  if (!link->send(out, sizeof out)) return false;
  uint8_t got[16] = {};
  pollfd p{master, POLLIN, 0};
  if (poll(&p, 1, 2000) != 1) return false;
  return read(master, got, sizeof got) == 4 && std::memcmp(got, out, 4) == 0;
}

// Bytes from the modem reach receive() within a few loops.
bool modem_to_vehicle(SerialTransport* link, int master) {
  const uint8_t in[] = {0xFE, 0x09};
  if (write(master, in, sizeof in) != 2) return false;
  uint8_t got[16] = {};
  long total = 0;
  for (int i = 0; i < 100 && total < 2; ++i)
    total += link->receive(got + total, sizeof got - total, 20);
  return total == 2 && got[1] == 0x09;
}

// A frame's first bytes cross the link both ways.
bool bytes_cross_both_ways(SerialTransport* link, int master) {
  return vehicle_to_modem(link, master) && modem_to_vehicle(link, master);
}

// The modem plugged in behind its name, and the vehicle's link opened on it: up.
class SerialTransportOnAModem : public ::testing::Test {
 protected:
  void SetUp() override {
    modem.plug(tmp.path);
    link.maintain(0);
    ASSERT_TRUE(link.health().up) << link.health().last_error;
  }
  const TempLink tmp;
  Modem modem;
  SerialTransport link{tmp.path, 57600, 1000};
};

}  // namespace

TEST_F(SerialTransportOnAModem, BytesCrossThePseudoTerminalBothWays) {
  EXPECT_TRUE(bytes_cross_both_ways(&link, modem.master));
  uint8_t got[16];
  EXPECT_EQ(link.receive(got, sizeof got, 0), 0);  // nothing more: silence is not an outage
  EXPECT_TRUE(link.health().up);
}

TEST(SerialTransport, ModemMissingAtStartIsAnOutageAndTheLinkComesUpWhenItAppears) {
  const TempLink tmp;
  const std::string& path = tmp.path;
  SerialTransport link(path, 57600, 1000);
  link.maintain(0);
  EXPECT_FALSE(link.health().up);
  EXPECT_EQ(link.health().open_failures, 1u);
  EXPECT_NE(link.health().last_error.find(path), std::string::npos) << link.health().last_error;
  uint8_t got[16];
  EXPECT_EQ(link.receive(got, sizeof got, 1), 0);  // down: waits, reads nothing
  const uint8_t frame[] = {0xFD};
  EXPECT_FALSE(link.send(frame, sizeof frame));

  Modem modem;
  modem.plug(path);
  link.maintain(500);  // inside the reopen period: not retried yet
  EXPECT_FALSE(link.health().up);
  EXPECT_EQ(link.health().open_failures, 1u);
  link.maintain(1000);
  ASSERT_TRUE(link.health().up) << link.health().last_error;
  EXPECT_EQ(link.health().opens, 1u);
  EXPECT_EQ(link.health().outages, 0u);
  EXPECT_TRUE(bytes_cross_both_ways(&link, modem.master));
}

TEST_F(SerialTransportOnAModem, UnplugIsReportedAndTheRepluggedModemIsReopened) {
  const std::string& path = tmp.path;
  modem.unplug();
  uint8_t got[16];
  for (int i = 0; i < 10 && link.health().up; ++i) EXPECT_EQ(link.receive(got, sizeof got, 20), 0);
  EXPECT_FALSE(link.health().up);
  EXPECT_EQ(link.health().outages, 1u);
  EXPECT_NE(link.health().last_error.find("unplugged"), std::string::npos);
  link.maintain(2000);
  EXPECT_EQ(link.health().down_since_ms, 2000u);

  Modem second;  // the modem back, on another pts, behind the same name
  second.plug(path);
  link.maintain(2500);
  EXPECT_FALSE(link.health().up);  // the reopen period counts from the outage
  link.maintain(3000);
  ASSERT_TRUE(link.health().up) << link.health().last_error;
  EXPECT_EQ(link.health().opens, 2u);
  EXPECT_TRUE(bytes_cross_both_ways(&link, second.master));
}

TEST(SerialTransport, AbsurdBaudIsNotSupported) {
  EXPECT_FALSE(SerialTransport::is_supported_baud(12));
  EXPECT_TRUE(SerialTransport::is_supported_baud(57600));
}

TEST(UdpTransport, BadAddressIsReported) {
  UdpConfig c;
  c.bind_address = "not-an-address";
  c.remote_address = "127.0.0.1";
  std::string error;
  EXPECT_FALSE(UdpTransport::open(c, &error));
  EXPECT_NE(error.find("not-an-address"), std::string::npos);
}
