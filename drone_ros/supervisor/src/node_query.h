// Asking a ROS node about itself over its own XML-RPC API, always with a deadline: a hung node
// (SIGSTOP, a deadlock) accepts the connection in the kernel and never answers, and roscpp's own
// XML-RPC client would wait for it forever. hp_supervisor finds the controller's process this way.
// ROS-free but for XmlRpcValue, the parser of the answer, so it is tested alone.
#pragma once

#include <optional>
#include <string>

namespace supervisor {

struct HttpEndpoint {
  std::string host;
  int port = 0;
};

// "http://host:port/" (a node's XML-RPC URI) -> host and port; nullopt if it is not one.
std::optional<HttpEndpoint> parse_http_uri(const std::string &uri);

// The integer value of an XML-RPC answer of the ROS node API ([code, status message, value]);
// nullopt unless the answer parses, its code is 1 (success) and its value is an integer.
std::optional<int> node_api_int_value(const std::string &http_response);

// The node's own answer to getPid(caller_id), or nullopt: gone (connection refused), hung (no
// answer within timeout_s) or a failure code.
std::optional<int> ask_pid(const std::string &uri, const std::string &caller_id, double timeout_s);

// The executable `type` of package `package` as catkin installs a node (<prefix>/lib/<package>/
// <type>) under the first prefix of prefix_path (CMAKE_PREFIX_PATH's form: prefixes joined by
// ':') that has it; empty if none does.
std::string find_node_executable(const std::string &prefix_path, const std::string &package,
                                 const std::string &type);

// Whether process pid still runs: not gone and not a zombie (a dead child of roslaunch or of
// the supervisor until it is reaped).
bool process_running(int pid);

// The state letter of an open /proc/<pid>/stat (R, S, Z, ...); nullopt when it cannot be read,
// as once the process has gone (ESRCH). Read with read(2): libstdc++'s streams throw from that
// error whatever their exception mask, and an ifstream here ended hp_supervisor with SIGABRT as
// the HA asked for its first restart in a HiL flight.
std::optional<char> process_state(int stat_fd);

}  // namespace supervisor
