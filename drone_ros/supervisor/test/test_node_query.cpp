// hp_supervisor's questions to a node (node_query.h) against peers on loopback: one that answers
// getPid as a ROS node does (roscpp's own XML-RPC server), one that accepts and never answers (a
// hung node: the deadline ends the wait), a closed port (a dead node), and the answers a broken
// or failing node gives.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <xmlrpcpp/XmlRpcServer.h>
#include <xmlrpcpp/XmlRpcServerMethod.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "node_query.h"

namespace {

using supervisor::ask_pid;
using supervisor::find_node_executable;
using supervisor::node_api_int_value;
using supervisor::parse_http_uri;
using supervisor::process_running;

class GetPid : public XmlRpc::XmlRpcServerMethod {
 public:
  explicit GetPid(XmlRpc::XmlRpcServer *s) : XmlRpc::XmlRpcServerMethod("getPid", s) {}
  void execute(XmlRpc::XmlRpcValue &params, XmlRpc::XmlRpcValue &result) override {
    caller = static_cast<std::string>(params[0]);
    result[0] = 1;
    result[1] = "";
    result[2] = 4242;
  }
  std::string caller;
};

// roscpp's XML-RPC server on a free loopback port, served from a thread of its own.
class NodeApiServer {
 public:
  NodeApiServer() : method_(&server_) {
    server_.bindAndListen(0);  // a free port, as roscpp binds its own
    port_ = server_.get_port();
    thread_ = std::thread([this] {
      while (!stop_) {
        server_.work(0.01);
      }
    });
  }
  ~NodeApiServer() {
    stop_ = true;
    thread_.join();
    server_.shutdown();
  }
  std::string uri() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }
  std::string caller() const { return method_.caller; }

 private:
  XmlRpc::XmlRpcServer server_;
  GetPid method_;
  int port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// A socket that listens and never accepts: the kernel completes the connection, nobody answers.
class HungNode {
 public:
  HungNode() {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(fd_, reinterpret_cast<sockaddr *>(&a), sizeof(a));
    listen(fd_, 4);
    socklen_t len = sizeof(a);
    getsockname(fd_, reinterpret_cast<sockaddr *>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~HungNode() { close(fd_); }
  std::string uri() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(NodeQuery, AnAnsweringNodeGivesItsPidAndLearnsWhoAsked) {
  NodeApiServer node;
  EXPECT_EQ(ask_pid(node.uri(), "/hp_supervisor", 2.0), std::optional<int>(4242));
  EXPECT_EQ(node.caller(), "/hp_supervisor");
}

TEST(NodeQuery, AHungNodeIsGivenUpOnAtTheDeadline) {
  HungNode hung;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(ask_pid(hung.uri(), "/hp_supervisor", 0.3), std::nullopt);
  // Not a timing test: without a deadline the call would never return at all.
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20));
}

TEST(NodeQuery, ADeadNodesPortRefuses) {
  int port = 0;
  {
    HungNode gone;  // a port that was free a moment ago, closed again
    port = std::stoi(gone.uri().substr(std::string("http://127.0.0.1:").size()));
  }
  EXPECT_EQ(ask_pid("http://127.0.0.1:" + std::to_string(port) + "/", "/hp_supervisor", 1.0),
            std::nullopt);
}

TEST(NodeQuery, OnlyASuccessfulIntegerAnswerIsAPid) {
  const std::string head =
      "HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n<?xml version=\"1.0\"?>";
  const auto answer = [&](const std::string &code, const std::string &value) {
    return head + "<methodResponse><params><param><value><array><data><value><i4>" + code +
           "</i4></value><value>msg</value><value>" + value +
           "</value></data></array></value></param></params>"
           "</methodResponse>";
  };
  EXPECT_EQ(node_api_int_value(answer("1", "<i4>77</i4>")), std::optional<int>(77));
  EXPECT_EQ(node_api_int_value(answer("-1", "<i4>77</i4>")), std::nullopt);  // a failure code
  EXPECT_EQ(node_api_int_value(answer("1", "<string>77</string>")), std::nullopt);
  EXPECT_EQ(
      node_api_int_value(head + "<methodResponse><fault><value>x</value></fault></methodResponse>"),
      std::nullopt);
  EXPECT_EQ(node_api_int_value(""), std::nullopt);
  EXPECT_EQ(node_api_int_value(answer("1", "<i4>77</i4>").substr(0, 150)),
            std::nullopt);  // cut short
}

TEST(NodeQuery, OnlyAnHttpUriWithAPortIsANodesAddress) {
  const auto at = parse_http_uri("http://vm:36619/");
  ASSERT_TRUE(at);
  EXPECT_EQ(at->host, "vm");
  EXPECT_EQ(at->port, 36619);
  EXPECT_TRUE(parse_http_uri("http://127.0.0.1:8080"));
  EXPECT_FALSE(parse_http_uri("rosrpc://vm:36619/"));
  EXPECT_FALSE(parse_http_uri("http://vm/"));
  EXPECT_FALSE(parse_http_uri("http://vm:0/"));
  EXPECT_FALSE(parse_http_uri("http://vm:99999/"));
  EXPECT_FALSE(parse_http_uri("http://:80/"));
}

TEST(NodeQuery, TheNodesExecutableIsFoundUnderTheFirstPrefixThatHasIt) {
  char tmpl[] = "/tmp/node_query_XXXXXX";
  const std::string root = mkdtemp(tmpl);
  const std::string a = root + "/a", b = root + "/b";
  for (const std::string &d : {a, a + "/lib", a + "/lib/pkg", b, b + "/lib", b + "/lib/pkg"}) {
    mkdir(d.c_str(), 0755);
  }
  std::ofstream(a + "/lib/pkg/not_executable") << "x";
  std::ofstream(b + "/lib/pkg/node") << "#!/bin/sh\n";
  chmod((b + "/lib/pkg/node").c_str(), 0755);
  EXPECT_EQ(find_node_executable(a + ":" + b, "pkg", "node"), b + "/lib/pkg/node");
  EXPECT_EQ(find_node_executable(a + ":" + b, "pkg", "not_executable"), "");
  EXPECT_EQ(find_node_executable("", "pkg", "node"), "");
  EXPECT_EQ(find_node_executable(a, "pkg", "node"), "");
  std::remove((a + "/lib/pkg/not_executable").c_str());
  std::remove((b + "/lib/pkg/node").c_str());
}

TEST(NodeQuery, AProcessRunsUntilItExitsAndAZombieRunsNoMore) {
  EXPECT_TRUE(process_running(getpid()));
  EXPECT_FALSE(process_running(0));
  const pid_t child = fork();
  if (child == 0) {
    _exit(0);
  }
  ASSERT_GT(child, 0);
  // Exited, not yet reaped: a zombie.
  for (int i = 0; i < 1000 && process_running(child); ++i) {
    usleep(1000);
  }
  EXPECT_FALSE(process_running(child));
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_FALSE(process_running(child));
}

TEST(NodeQuery, AProcessThatGoesWhileItsStatIsOpenReadsAsUnknownNotAnError) {
  const pid_t child = fork();
  if (child == 0) {
    pause();
    _exit(0);
  }
  ASSERT_GT(child, 0);
  const std::string path = "/proc/" + std::to_string(child) + "/stat";
  const int fd = open(path.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  EXPECT_TRUE(supervisor::process_state(fd).has_value());  // alive: S, sleeping in pause()
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  // Gone while the file is open: the read fails (ESRCH), where an ifstream threw.
  EXPECT_EQ(supervisor::process_state(fd), std::nullopt);
  close(fd);
}

}  // namespace

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
