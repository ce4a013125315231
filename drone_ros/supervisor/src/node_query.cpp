#include "node_query.h"

#include <netdb.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xmlrpcpp/XmlRpcException.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <fcntl.h>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace supervisor {

namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds left until deadline, at least 0.
int ms_left(Clock::time_point deadline) {
  const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

bool wait_ready(int fd, short events, Clock::time_point deadline) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int n = poll(&p, 1, ms_left(deadline));
    if (n > 0) {
      return true;
    }
    if (n == 0 || errno != EINTR) {
      return false;
    }
  }
}

int connect_by(const HttpEndpoint &at, Clock::time_point deadline) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo *found = nullptr;
  if (getaddrinfo(at.host.c_str(), std::to_string(at.port).c_str(), &hints, &found) != 0) {
    return -1;
  }
  int fd = -1;
  for (addrinfo *a = found; a != nullptr && fd < 0; a = a->ai_next) {
    fd = socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) {
      continue;
    }
    if (connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
      break;
    }
    int err = errno;
    socklen_t len = sizeof(err);
    if (err != EINPROGRESS || !wait_ready(fd, POLLOUT, deadline) ||
        getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0 || err != 0) {
      close(fd);
      fd = -1;
    }
  }
  freeaddrinfo(found);
  return fd;
}

std::string xml_escaped(const std::string &s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// The whole answer is in: its headers and as many bytes as their Content-Length says (a server
// that keeps the connection open is not waited out).
bool complete(const std::string &answer) {
  const size_t end = answer.find("\r\n\r\n");
  if (end == std::string::npos) {
    return false;
  }
  std::string headers = answer.substr(0, end);
  for (char &c : headers) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  const std::string key = "\r\ncontent-length:";
  const size_t at = headers.find(key);
  if (at == std::string::npos) {
    return false;
  }
  const unsigned long length = std::strtoul(headers.c_str() + at + key.size(), nullptr, 10);
  return answer.size() >= end + 4 + length;
}

// POST body to the node and read its answer until it closes (XML-RPC over HTTP/1.0) or the
// deadline passes; empty on any failure.
std::string post(const HttpEndpoint &at, const std::string &body, double timeout_s) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::microseconds(static_cast<int64_t>(timeout_s * 1e6));
  const int fd = connect_by(at, deadline);
  if (fd < 0) {
    return std::string();
  }
  std::ostringstream request;
  request << "POST / HTTP/1.0\r\nUser-Agent: hp_supervisor\r\nHost: " << at.host << ':' << at.port
          << "\r\nContent-Type: text/xml\r\nContent-Length: " << body.size() << "\r\n\r\n"
          << body;
  const std::string out = request.str();
  size_t sent = 0;
  while (sent < out.size()) {
    const ssize_t n = send(fd, out.data() + sent, out.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<size_t>(n);
    } else if ((n < 0 && errno != EAGAIN && errno != EINTR) || !wait_ready(fd, POLLOUT, deadline)) {
      close(fd);
      return std::string();
    }
  }
  std::string answer;
  char buf[4096];
  for (;;) {
    const ssize_t n = recv(fd, buf, sizeof(buf), 0);
    if (n > 0) {
      answer.append(buf, static_cast<size_t>(n));
      if (complete(answer)) {
        break;
      }
    } else if (n == 0) {
      break;
    } else if ((errno != EAGAIN && errno != EINTR) || !wait_ready(fd, POLLIN, deadline)) {
      answer.clear();
      break;
    }
  }
  close(fd);
  return answer;
}

}  // namespace

std::optional<HttpEndpoint> parse_http_uri(const std::string &uri) {
  const std::string scheme = "http://";
  if (uri.compare(0, scheme.size(), scheme) != 0) {
    return std::nullopt;
  }
  const size_t host_begin = scheme.size();
  const size_t colon = uri.find(':', host_begin);
  if (colon == std::string::npos || colon == host_begin) {
    return std::nullopt;
  }
  const size_t slash = uri.find('/', colon);
  const std::string port =
      uri.substr(colon + 1, slash == std::string::npos ? std::string::npos : slash - colon - 1);
  if (port.empty() || port.size() > 5 ||
      port.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  const int p = std::stoi(port);
  if (p <= 0 || p > 65535) {
    return std::nullopt;
  }
  return HttpEndpoint{uri.substr(host_begin, colon - host_begin), p};
}

std::optional<int> node_api_int_value(const std::string &http_response) {
  const size_t param = http_response.find("<param>");
  if (param == std::string::npos) {
    return std::nullopt;
  }
  int offset = static_cast<int>(param + std::strlen("<param>"));
  XmlRpc::XmlRpcValue v;
  try {  // XmlRpcValue throws on a type it did not expect
    if (!v.fromXml(http_response, &offset) || v.getType() != XmlRpc::XmlRpcValue::TypeArray ||
        v.size() != 3 || v[0].getType() != XmlRpc::XmlRpcValue::TypeInt ||
        static_cast<int>(v[0]) != 1 || v[2].getType() != XmlRpc::XmlRpcValue::TypeInt) {
      return std::nullopt;
    }
    return static_cast<int>(v[2]);
  } catch (const XmlRpc::XmlRpcException &) {
    return std::nullopt;
  }
}

std::optional<int> ask_pid(const std::string &uri, const std::string &caller_id, double timeout_s) {
  const std::optional<HttpEndpoint> at = parse_http_uri(uri);
  if (!at) {
    return std::nullopt;
  }
  const std::string body =
      "<?xml version=\"1.0\"?><methodCall><methodName>getPid</methodName><params><param><value>"
      "<string>" +
      xml_escaped(caller_id) + "</string></value></param></params></methodCall>";
  return node_api_int_value(post(*at, body, timeout_s));
}

std::optional<char> process_state(int stat_fd) {
  char buf[512];
  const ssize_t n = pread(stat_fd, buf, sizeof(buf) - 1, 0);
  if (n <= 0) {
    return std::nullopt;
  }
  const std::string text(buf, static_cast<size_t>(n));
  const size_t paren = text.rfind(')');
  if (paren == std::string::npos || paren + 2 >= text.size()) {
    return std::nullopt;
  }
  return text[paren + 2];
}

bool process_running(int pid) {
  if (pid <= 0) {
    return false;
  }
  if (kill(pid, 0) != 0) {
    return errno == EPERM;
  }
  const std::string path = "/proc/" + std::to_string(pid) + "/stat";
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    return false;
  }
  const std::optional<char> state = process_state(fd);
  close(fd);
  return state && *state != 'Z';
}

std::string find_node_executable(const std::string &prefix_path, const std::string &package,
                                 const std::string &type) {
  std::istringstream prefixes(prefix_path);
  std::string prefix;
  while (std::getline(prefixes, prefix, ':')) {
    if (prefix.empty()) {
      continue;
    }
    const std::string path = prefix + "/lib/" + package + "/" + type;
    struct stat st {};
    if (stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(path.c_str(), X_OK) == 0) {
      return path;
    }
  }
  return std::string();
}

}  // namespace supervisor
