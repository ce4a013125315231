// hp_supervisor: the HP side's end of the HA's reset line, in software (README.md).
//
// On a rising edge of DecisionStatus.restart_requested it ends the controller process and starts
// a new one under the same name: found through the master (lookupNode, then the node's own
// getPid with a 0.5 s deadline; a hung node does not answer, so the PID it gave while it still
// answered is used), SIGTERM, SIGKILL after ~kill_grace_s, then ~boot_delay_s of ROS time and a
// new process, this node's child. In C++ since the simulator became fast enough for its rospy
// /clock subscription to show: a hundred times a simulated second, a tenth of a lockstep flight's
// wall time.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <drone_ros/DecisionStatus.h>
#include <drone_ros_common/node_main.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "node_query.h"

namespace {

constexpr double kAskTimeoutS = 0.5;
constexpr double kLearnPeriodS = 0.2;

struct Params {
  std::string node;  // resolved
  std::string package;
  std::string type;
  double kill_grace_s = 1.0;
  double boot_delay_s = 0.0;
};

bool load(const ros::NodeHandle &pnh, Params *p, std::string *error) {
  // The controller is the aircraft's (controller_<aircraft>): hp_supervisor.launch names it, and
  // no aircraft is assumed here.
  std::string node;
  if (!pnh.getParam("node", node) || !pnh.getParam("type", p->type)) {
    *error = "~node and ~type (the controller's node name and executable) must be given";
    return false;
  }
  pnh.param<std::string>("package", p->package, "drone_ros");
  pnh.param("kill_grace_s", p->kill_grace_s, 1.0);
  pnh.param("boot_delay_s", p->boot_delay_s, 0.0);
  if (node.empty() || p->package.empty() || p->type.empty()) {
    *error = "~node, ~package and ~type must not be empty";
    return false;
  }
  if (!(p->kill_grace_s >= 0.0 && p->kill_grace_s <= 60.0) ||
      !(p->boot_delay_s >= 0.0 && p->boot_delay_s <= 600.0)) {
    *error = "~kill_grace_s must be in [0, 60] s and ~boot_delay_s in [0, 600] s";
    return false;
  }
  p->node = ros::names::resolve(node);
  return true;
}

void sleep_s(double s) {
  std::this_thread::sleep_for(std::chrono::microseconds(static_cast<int64_t>(s * 1e6)));
}

std::string uri_host(const std::string &uri) {
  const std::optional<supervisor::HttpEndpoint> at = supervisor::parse_http_uri(uri);
  return at ? at->host : std::string();
}

bool local(const std::string &uri) {
  const std::string host = uri_host(uri);
  char name[256] = {0};
  gethostname(name, sizeof(name) - 1);
  return host == "localhost" || host == "127.0.0.1" || host == name ||
         host == ros::network::getHost();
}

// The node's XML-RPC URI from the master, or empty.
std::string node_uri(const std::string &node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeString) {
    return std::string();
  }
  return static_cast<std::string>(payload);
}

class Supervisor {
 public:
  Supervisor(ros::NodeHandle &nh, const Params &p) : p_(p) {
    diag_pub_ = nh.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 1);
    // On the wall clock: a status a second, whatever simulated time does.
    diag_timer_ = nh.createSteadyTimer(
        ros::WallDuration(1.0), [this](const ros::SteadyTimerEvent &) { publish_diagnostics(); });
    learner_ = std::thread([this] { learn_pids(); });
    status_sub_ = nh.subscribe("decision_status", 10, &Supervisor::on_status, this);
    ROS_INFO("hp_supervisor: restarts %s when the HA asks (boot delay %.1f s)", p_.node.c_str(),
             p_.boot_delay_s);
  }

  ~Supervisor() {
    stopping_ = true;
    if (learner_.joinable()) {
      learner_.join();
    }
    if (restarter_.joinable()) {
      restarter_.join();
    }
    stop_children();
  }

 private:
  void on_status(const drone_ros::DecisionStatus::ConstPtr &msg) {
    const bool rising = msg->restart_requested && !requested_;
    requested_ = msg->restart_requested;
    if (!rising) {
      return;
    }
    bool idle = false;
    if (!busy_.compare_exchange_strong(idle, true)) {
      ROS_WARN("hp_supervisor: restart requested while one is under way; ignored");
      return;
    }
    if (restarter_.joinable()) {
      restarter_.join();  // the last one has ended: busy_ was clear
    }
    restarter_ = std::thread([this] {
      restart();
      busy_ = false;
    });
  }

  // Remembers the node's PID while it answers: a hung node cannot be asked.
  void learn_pids() {
    while (!stopping_ && ros::ok()) {
      try {
        learn_pid();
      } catch (const std::exception &e) {
        ROS_WARN_THROTTLE(10.0, "hp_supervisor: learning %s's PID: %s", p_.node.c_str(), e.what());
      } catch (...) {
        ROS_WARN_THROTTLE(10.0, "hp_supervisor: learning %s's PID failed", p_.node.c_str());
      }
      reap_children();
      sleep_s(kLearnPeriodS);
    }
  }

  void learn_pid() {
    const std::string uri = node_uri(p_.node);
    if (!uri.empty() && uri != known_uri() && local(uri)) {
      const std::optional<int> pid =
          supervisor::ask_pid(uri, ros::this_node::getName(), kAskTimeoutS);
      if (pid) {
        std::lock_guard<std::mutex> lock(mutex_);
        known_uri_ = uri;
        known_pid_ = *pid;
      }
    }
  }

  std::string known_uri() {
    std::lock_guard<std::mutex> lock(mutex_);
    return known_uri_;
  }

  int find_pid() {
    const std::string uri = node_uri(p_.node);
    if (uri.empty()) {
      return -1;
    }
    if (!local(uri)) {
      ROS_WARN("hp_supervisor: %s runs on %s, not here: cannot restart it", p_.node.c_str(),
               uri.c_str());
      set_last_stop("not stopped: runs on " + uri);
      return -1;
    }
    const std::optional<int> pid =
        supervisor::ask_pid(uri, ros::this_node::getName(), kAskTimeoutS);
    if (pid) {
      return *pid;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    return known_uri_ == uri ? known_pid_
                             : -1;  // it does not answer (hung): the PID it had when it did
  }

  void stop_running() {
    const int pid = find_pid();
    if (pid <= 0 || !supervisor::process_running(pid)) {
      ROS_WARN("hp_supervisor: %s is not running (crashed)", p_.node.c_str());
      std::lock_guard<std::mutex> lock(mutex_);
      if (last_stop_.empty()) {  // not set by find_pid: not a node elsewhere
        last_stop_ = "not running (crashed)";
      }
      return;
    }
    ROS_WARN("hp_supervisor: stopping %s (pid %d)", p_.node.c_str(), pid);
    kill(pid, SIGTERM);
    set_last_stop("SIGTERM");
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::microseconds(static_cast<int64_t>(p_.kill_grace_s * 1e6));
    while (std::chrono::steady_clock::now() < deadline && supervisor::process_running(pid)) {
      reap_children();
      sleep_s(0.01);
    }
    if (supervisor::process_running(pid)) {
      ROS_WARN("hp_supervisor: %s did not stop within %.1f s (hung): SIGKILL", p_.node.c_str(),
               p_.kill_grace_s);
      kill(pid, SIGKILL);
      set_last_stop("SIGKILL (hung)");
      while (supervisor::process_running(pid)) {
        reap_children();
        sleep_s(0.01);
      }
    }
  }

  void start_new() {
    const char *prefixes = std::getenv("CMAKE_PREFIX_PATH");
    const std::string exe =
        supervisor::find_node_executable(prefixes ? prefixes : "", p_.package, p_.type);
    if (exe.empty()) {
      ROS_ERROR("hp_supervisor: no executable %s in %s", p_.type.c_str(), p_.package.c_str());
      std::lock_guard<std::mutex> lock(mutex_);
      failure_ = "no executable " + p_.type + " in " + p_.package;
      return;
    }
    const std::string ns = ros::names::parentNamespace(p_.node);
    const std::string name = p_.node.substr(p_.node.rfind('/') + 1);
    const std::string name_arg = "__name:=" + name, ns_arg = "__ns:=" + ns;
    const pid_t child = fork();
    if (child == 0) {
      execl(exe.c_str(), exe.c_str(), name_arg.c_str(), ns_arg.c_str(),
            static_cast<char *>(nullptr));
      _exit(127);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (child < 0) {
      failure_ = "restart failed: fork: " + std::string(std::strerror(errno));
      ROS_ERROR("hp_supervisor: restarting %s failed: %s", p_.node.c_str(), failure_.c_str());
      return;
    }
    children_.push_back(child);
    started_pid_ = child;
    failure_.clear();
    ++restarts_;
    ROS_WARN("hp_supervisor: started %s again (pid %d, restart %d)", p_.node.c_str(), child,
             restarts_);
  }

  void restart() {
    // A restart that died unseen would leave the HA flying on: it says why, in /diagnostics too.
    try {
      set_last_stop("");
      stop_running();
      if (p_.boot_delay_s > 0.0) {
        ros::Duration(p_.boot_delay_s).sleep();
      }
      if (ros::ok() && !stopping_) {
        start_new();
      }
    } catch (const std::exception &e) {
      fail_restart(e.what());
    } catch (...) {
      fail_restart("an exception that is not a std::exception");
    }
  }

  void fail_restart(const std::string &why) {
    ROS_ERROR("hp_supervisor: restarting %s failed: %s", p_.node.c_str(), why.c_str());
    std::lock_guard<std::mutex> lock(mutex_);
    failure_ = "restart failed: " + why;
  }

  void set_last_stop(const std::string &s) {
    std::lock_guard<std::mutex> lock(mutex_);
    last_stop_ = s;
  }

  // A reaped child's PID is free for the system to give again: it leaves children_, so that no
  // signal of stop_children() reaches whatever process gets that PID next.
  void reap_children() {
    int status = 0;
    pid_t gone;
    while ((gone = waitpid(-1, &status, WNOHANG)) > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      children_.erase(std::remove(children_.begin(), children_.end(), gone), children_.end());
    }
  }

  void stop_children() {
    std::vector<pid_t> children;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      children = children_;
    }
    for (pid_t c : children) {
      kill(c, SIGTERM);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    for (pid_t c : children) {
      while (supervisor::process_running(c) && std::chrono::steady_clock::now() < deadline) {
        reap_children();
        sleep_s(0.01);
      }
      if (supervisor::process_running(c)) {
        kill(c, SIGKILL);
      }
    }
    reap_children();
  }

  void publish_diagnostics() {
    diagnostic_msgs::DiagnosticStatus st;
    st.name = "hp_supervisor: " + p_.node;
    st.hardware_id = "HP computer";
    std::lock_guard<std::mutex> lock(mutex_);
    if (!failure_.empty()) {
      st.level = diagnostic_msgs::DiagnosticStatus::ERROR;
      st.message = "cannot restart: " + failure_;
    } else if (busy_) {
      st.level = diagnostic_msgs::DiagnosticStatus::WARN;
      st.message = "restarting";
    } else {
      st.level = diagnostic_msgs::DiagnosticStatus::OK;
      st.message = "supervising (" + std::to_string(restarts_) + " restarts)";
    }
    const auto kv = [](const std::string &k, const std::string &v) {
      diagnostic_msgs::KeyValue x;
      x.key = k;
      x.value = v;
      return x;
    };
    st.values = {kv("restarts", std::to_string(restarts_)),
                 kv("last stop", last_stop_.empty() ? "-" : last_stop_),
                 kv("started pid", started_pid_ > 0 ? std::to_string(started_pid_) : "-")};
    diagnostic_msgs::DiagnosticArray arr;
    arr.header.stamp = ros::Time::now();
    arr.status.push_back(st);
    diag_pub_.publish(arr);
  }

  const Params p_;
  ros::Publisher diag_pub_;
  ros::SteadyTimer diag_timer_;
  ros::Subscriber status_sub_;
  std::thread learner_;
  std::thread restarter_;
  std::atomic<bool> busy_{false};
  std::atomic<bool> stopping_{false};
  bool requested_ = false;
  std::mutex mutex_;  // guards what follows
  std::string known_uri_;
  int known_pid_ = -1;
  std::vector<pid_t> children_;
  std::string last_stop_;
  std::string failure_;
  int started_pid_ = -1;
  int restarts_ = 0;
};

}  // namespace

int main(int argc, char **argv) {
  return drone_ros_common::node_main<Params>(
      argc, argv, "hp_supervisor", load,
      [](ros::NodeHandle &nh, ros::NodeHandle &, const Params &p) {
        Supervisor supervisor(nh, p);
        ros::spin();
        return 0;
      });
}
