// The `arduino` node: the HP end of the HA-HP rosserial link, in the spirit of rosserial_server.
// It owns the serial port, asks the device for its topics, publishes and subscribes on the
// device's behalf generically (raw serialized messages with the type and md5sum the device
// announced), answers time and parameter requests, forwards device logs to rosout, and survives
// the port going away: it reports the outage (/pwm usbstatus 0, diagnostics) and reopens.
#ifndef ARDUINO_LINK_ARDUINO_LINK_NODE_H
#define ARDUINO_LINK_ARDUINO_LINK_NODE_H

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "device_payloads.h"
#include "drone_ros_common/inline_queue.h"
#include "drone_ros_common/serial_port.h"
#include "link_params.h"
#include "message_definitions.h"
#include "rosserial_framer.h"

namespace arduino_link {

// Atomics: subscriber callbacks (spinner thread) count too.
struct LinkCounters {
  std::atomic<uint64_t> unknown_topic{0};  // data on an id the device never announced
  std::atomic<uint64_t> bad_payload{0};    // a valid frame whose payload does not decode, or
                                           // announces a topic ROS would refuse
  std::atomic<uint64_t> md5_mismatch{0};   // device and ROS disagree on a type
  std::atomic<uint64_t> tx_failed{0};      // a frame that could not be written
  std::atomic<uint64_t> tx_too_big{0};     // a ROS message larger than the device's buffer
  std::atomic<uint64_t> outages{0};        // link up -> down transitions
  std::atomic<uint64_t> port_opens{0};
  std::atomic<uint64_t> commands_forwarded{0};
  std::atomic<uint64_t> topic_confirmations{0};  // topic requests sent again after an answer
  // Simulated time: answers to the device's time request that would have lagged /clock.
  std::atomic<uint64_t> time_answers_behind_clock{0};
  std::atomic<uint64_t> time_answer_lag_max_ns{0};  // the most ros::Time::now() lagged by
};

class ArduinoLinkNode {
 public:
  ArduinoLinkNode(ros::NodeHandle nh, ros::NodeHandle pnh, const LinkParams &params);
  ~ArduinoLinkNode();
  // Runs until ROS shuts down; never returns on bad bytes or a lost port.
  void run();

 private:
  struct Endpoint {
    std::string name, type, md5;
    const KnownType *known = nullptr;  // null when the type is not compiled in
    // For rosbag; empty (ROS warns once) when the type is not compiled in.
    std::string definition() const { return known != nullptr ? known->definition : std::string(); }
    int32_t buffer_size = 0;
    bool is_pwm = false;
    ros::Publisher pub;
    ros::Subscriber sub;
  };

  void try_open(const ros::WallTime &now);
  void port_gone(const char *why);
  void handle_frame(const Frame &frame);
  void on_publisher_info(const Frame &frame);
  void on_subscriber_info(const Frame &frame);
  void on_time_request();
  ros::Time time_for_device();
  void on_param_request(const Frame &frame);
  void on_log(const Frame &frame);
  void on_device_data(Endpoint &ep, const Frame &frame);
  bool accept_announcement(const Frame &frame, TopicAnnouncement *a);
  static Endpoint endpoint_for(const TopicAnnouncement &a);
  void refuse(const char *what, const std::string &why);
  void on_ros_message(uint16_t topic_id, const topic_tools::ShapeShifter::ConstPtr &msg);
  bool send(uint16_t topic_id, const std::vector<uint8_t> &payload);
  bool send_raw(const std::vector<uint8_t> &bytes);
  void update_link_state(const ros::WallTime &now);
  void confirm_topics_later();
  void publish_lost_pwm();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper &stat);

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  LinkParams params_;
  RosserialFramer framer_;
  diagnostic_updater::Updater updater_;
  ros::Publisher pwm_pub_;  // typed: the node also publishes usbstatus 0 itself

  std::mutex port_mutex_;  // the port is written from subscriber callbacks too
  drone_ros_common::SerialPort port_;
  // The subscribers' callbacks (on_ros_message, the /clock one) run in roscpp's receive thread as
  // each message arrives (inline_queue.h). Before endpoints_ and clock_sub_: it outlives them.
  drone_ros_common::InlineQueue inline_;
  std::mutex endpoints_mutex_;  // subscriber callbacks look up the device's buffer size
  std::map<uint16_t, Endpoint> endpoints_;

  bool link_up_ = false;
  bool negotiated_ = false;
  // ROS time: the wall clock in flight; in lockstep it stands while the simulator holds time.
  ros::Time last_rx_;
  ros::WallTime last_open_attempt_;
  ros::WallTime last_topic_request_;
  // When to ask for topics again to confirm the last answer whole (zero: no need), see run().
  ros::WallTime confirm_topics_at_;
  ros::WallTime lost_since_;
  ros::WallTime last_lost_pwm_;
  double last_gap_s_ = 0.0;
  std::string last_error_;
  LinkCounters counters_;
  // Simulated time only: the newest /clock, set in roscpp's receive thread (see time_for_device).
  std::atomic<uint64_t> newest_clock_ns_{0};
  ros::Subscriber clock_sub_;
};

}  // namespace arduino_link

#endif
