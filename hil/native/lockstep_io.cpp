// The simulator's per-step ROS I/O in lockstep, in C++ (libhil_lockstep_io.so, driven from
// hil/lockstep_io.py through ctypes): a roscpp node inside the simulator's process publishes
// /clock and /hil/lockstep and counts the messages each step waits for. In rospy these were a
// third of the simulator's CPU, and every message woke a Python thread that then had to win the
// GIL back from the stepping thread. Here they arrive in roscpp's network thread, are counted
// there without being decoded, and a waiting step is woken by a condition variable; ctypes lets go
// of the GIL for as long as a call into this library lasts.
//
// The controller's /to_hil (the guidance's waypoint index, every controller step) is read here
// too, and only its changes kept: a rospy subscription decoded it in a Python thread each step,
// which took the GIL from the stepping thread while the step's HA period and truth were due.
//
// One node per process, made by hio_init and ended by hio_shutdown; every other call before
// hio_init or after hio_shutdown returns 0 and does nothing.
#include <drone_ros/LockstepStep.h>
#include <drone_ros/hil_data.h>
#include <drone_ros_common/inline_queue.h>
#include <drone_ros_common/xmlrpc_wake.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <topic_tools/shape_shifter.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace {

// The topics counted, by the index hil/lockstep_io.py names them with.
enum Counted : int { kVn = 0, kStatus, kPwm, kHome, kServoOp, kToHil, kCountedTopics };

// Waypoint changes kept: a mission has at most a few hundred, a restart starts the count again;
// changes past this many are not kept (no flight comes near it).
constexpr size_t kWaypointLogMax = 4096;

struct WaypointChange {
  uint64_t stamp_us;
  int32_t index;
};

class LockstepIo {
 public:
  explicit LockstepIo(const std::array<std::string, kCountedTopics> &topics) {
    ros::NodeHandle nh;
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
    lockstep_pub_ = nh.advertise<drone_ros::LockstepStep>("hil/lockstep", 10);
    for (int i = 0; i < kCountedTopics; ++i) {
      ros::SubscribeOptions ops;
      ops.init<topic_tools::ShapeShifter>(
          topics[static_cast<size_t>(i)], 1000,
          [this, i](const topic_tools::ShapeShifter::ConstPtr &m) { on_message(i, *m); });
      ops.callback_queue = &queue_;
      ops.transport_hints = ros::TransportHints().tcpNoDelay();
      subs_.push_back(nh.subscribe(ops));
    }
  }

  uint64_t count(int topic) {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_[static_cast<size_t>(topic)];
  }

  bool wait_count(int topic, uint64_t at_least, double timeout_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration<double>(timeout_s > 0.0 ? timeout_s : 0.0);
    return changed_.wait_until(lock, deadline,
                               [&] { return counts_[static_cast<size_t>(topic)] >= at_least; });
  }

  // The newest message of a topic as ROS serialized it; its size (0: none yet), copied only
  // if it fits in capacity bytes.
  size_t latest(int topic, uint8_t *out, size_t capacity) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::vector<uint8_t> &bytes = latest_[static_cast<size_t>(topic)];
    if (out != nullptr && bytes.size() <= capacity) {
      std::memcpy(out, bytes.data(), bytes.size());
    }
    return bytes.size();
  }

  // The guidance's waypoint index at each change, stamped with the controller step that made it
  // (the message's header): the same log whenever the step reads it. Its size; copied up to
  // capacity entries.
  size_t waypoints(uint64_t *stamps_us, int32_t *indexes, size_t capacity) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < waypoints_.size() && i < capacity; ++i) {
      stamps_us[i] = waypoints_[i].stamp_us;
      indexes[i] = waypoints_[i].index;
    }
    return waypoints_.size();
  }

  void publish_step(uint64_t t_us, const uint32_t declared[9]) {
    const ros::Time stamp(static_cast<uint32_t>(t_us / 1000000u),
                          static_cast<uint32_t>((t_us % 1000000u) * 1000u));
    rosgraph_msgs::Clock clock;
    clock.clock = stamp;
    clock_pub_.publish(clock);
    drone_ros::LockstepStep step;
    step.clock = stamp;
    step.ins = declared[0];
    step.attitude = declared[1];
    step.gps_position = declared[2];
    step.gps_velocity = declared[3];
    step.imu_pqr_acceleration = declared[4];
    step.pwm = declared[5];
    step.decision_status = declared[6];
    step.home = declared[7];
    step.way = declared[8];
    lockstep_pub_.publish(step);
  }

 private:
  void on_message(int topic, const topic_tools::ShapeShifter &m) {
    const auto t = static_cast<size_t>(topic);
    if (topic == kToHil) {
      on_guidance(*m.instantiate<drone_ros::hil_data>());
      return;
    }
    std::vector<uint8_t> bytes;  // read only where a byte of it matters: a counted topic is counted
    if (topic == kPwm || topic == kServoOp) {
      bytes.resize(m.size());
      ros::serialization::OStream stream(bytes.data(), static_cast<uint32_t>(bytes.size()));
      m.write(stream);
    }
    // The arduino node's own /pwm while its link is down (usbstatus 0, its last byte) runs on
    // the wall clock: only the HA's reports count.
    if (topic == kPwm && (bytes.empty() || bytes.back() == 0u)) {
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_[t];
      if (topic == kServoOp) {
        latest_[t].swap(bytes);
      }
    }
    changed_.notify_all();
  }

  void on_guidance(const drone_ros::hil_data &m) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_[kToHil];
    if ((waypoints_.empty() || waypoints_.back().index != m.waypoint_index) &&
        waypoints_.size() < kWaypointLogMax) {
      waypoints_.push_back({m.header.stamp.toNSec() / 1000u, m.waypoint_index});
    }
  }

  // Counting a message in roscpp's network thread needs no second thread, and waking one cost a
  // hand-off per message.
  drone_ros_common::InlineQueue queue_;
  ros::Publisher clock_pub_;
  ros::Publisher lockstep_pub_;
  std::vector<ros::Subscriber> subs_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::array<uint64_t, kCountedTopics> counts_{};
  std::array<std::vector<uint8_t>, kCountedTopics> latest_{};
  std::vector<WaypointChange> waypoints_;
};

std::unique_ptr<LockstepIo> g_io;

}  // namespace

extern "C" {

// A node named `name` in namespace `ns` (the simulator's own), counting the topics given in
// Counted's order (names as the simulator resolved them). 1 once it is up.
int hio_init(const char *ns, const char *name, const char *const topics[kCountedTopics]) {
  if (g_io || ns == nullptr || name == nullptr || topics == nullptr) {
    return 0;
  }
  std::array<std::string, kCountedTopics> names;
  for (int i = 0; i < kCountedTopics; ++i) {
    if (topics[i] == nullptr) {
      return 0;
    }
    names[static_cast<size_t>(i)] = topics[i];
  }
  ros::M_string remappings;
  remappings["__ns"] = ns;
  // rospy has SIGINT; the simulator logs through rospy, so no /rosout publisher here either.
  ros::init(remappings, name, ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  try {
    g_io.reset(new LockstepIo(names));
    drone_ros_common::XmlRpcWake::install(drone_ros_common::kXmlRpcWakePeriodS);
  } catch (const std::exception &e) {
    ROS_ERROR("hil_lockstep_io: %s", e.what());
    g_io.reset();
    return 0;
  }
  return 1;
}

uint64_t hio_count(int topic) {
  return g_io && topic >= 0 && topic < kCountedTopics ? g_io->count(topic) : 0u;
}

int hio_wait_count(int topic, uint64_t at_least, double timeout_s) {
  return g_io && topic >= 0 && topic < kCountedTopics &&
                 g_io->wait_count(topic, at_least, timeout_s)
             ? 1
             : 0;
}

size_t hio_latest(int topic, uint8_t *out, size_t capacity) {
  return g_io && topic >= 0 && topic < kCountedTopics ? g_io->latest(topic, out, capacity) : 0u;
}

size_t hio_waypoints(uint64_t *stamps_us, int32_t *indexes, size_t capacity) {
  return g_io && (capacity == 0 || (stamps_us != nullptr && indexes != nullptr))
             ? g_io->waypoints(stamps_us, indexes, capacity)
             : 0u;
}

// /clock to t_us, then /hil/lockstep declaring, in LockstepStep's order, the messages of each
// topic delivered since the last step. 1 if published.
int hio_publish_step(uint64_t t_us, const uint32_t declared[9]) {
  if (!g_io || declared == nullptr) {
    return 0;
  }
  g_io->publish_step(t_us, declared);
  return 1;
}

void hio_shutdown(void) {
  if (g_io) {
    ros::shutdown();  // first: no callback runs in the network thread while the node goes
    g_io.reset();
  }
}

}  // extern "C"
