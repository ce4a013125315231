#include "arduino_link_node.h"

#include <drone_ros/HomePosition.h>
#include <drone_ros/pwm.h>
#include <ros/names.h>
#include <ros/serialization.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/Time.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <boost/function.hpp>

#include "ha_link_msgs.h"

namespace arduino_link {

namespace {
// rosserial's reserved topic ids (rosserial_msgs/TopicInfo), from the generated constants.
constexpr uint16_t kIdPublisher = ROSSERIAL_MSGS_TOPICINFO_ID_PUBLISHER;
constexpr uint16_t kIdSubscriber = ROSSERIAL_MSGS_TOPICINFO_ID_SUBSCRIBER;
constexpr uint16_t kIdParameterRequest = ROSSERIAL_MSGS_TOPICINFO_ID_PARAMETER_REQUEST;
constexpr uint16_t kIdLog = ROSSERIAL_MSGS_TOPICINFO_ID_LOG;
constexpr uint16_t kIdTime = ROSSERIAL_MSGS_TOPICINFO_ID_TIME;
constexpr int kReadTimeoutMs = 20;
}  // namespace

ArduinoLinkNode::ArduinoLinkNode(ros::NodeHandle nh, ros::NodeHandle pnh, const LinkParams &params)
    : nh_(nh),
      pnh_(pnh),
      params_(params),
      framer_(static_cast<std::size_t>(params.max_payload), params.frame_timeout_s) {
  pwm_pub_ = nh_.advertise<drone_ros::pwm>("pwm", 10);
  updater_.setHardwareID(params_.port);
  updater_.add("HA link", this, &ArduinoLinkNode::diagnose);
  lost_since_ = ros::WallTime::now();
  if (ros::Time::isSimTime()) {
    ros::SubscribeOptions ops;
    ops.init<rosgraph_msgs::Clock>("/clock", 1, [this](const rosgraph_msgs::Clock::ConstPtr &m) {
      newest_clock_ns_ = m->clock.toNSec();  // the latest: a simulation started again goes back
    });
    ops.callback_queue = &inline_;
    clock_sub_ = nh_.subscribe(ops);
  }
}

ArduinoLinkNode::~ArduinoLinkNode() {
  inline_.close();  // no subscriber callback runs on what goes below
  std::lock_guard<std::mutex> lock(port_mutex_);
  if (port_.is_open()) {
    const auto stop = tx_stop_frame();  // tell the device we are going, as rosserial does
    (void)port_.write_all(stop.data(), stop.size());
    port_.close();
  }
}

void ArduinoLinkNode::run() {
  // Under simulated time the node's only callbacks, its subscribers', run in roscpp's receive
  // thread (see on_subscriber_info); on the wall clock this spinner runs them.
  ros::AsyncSpinner spinner(1);
  if (!ros::Time::isSimTime()) spinner.start();
  std::vector<uint8_t> buf(4096);
  std::vector<Frame> frames;
  while (ros::ok()) {
    const ros::WallTime now = ros::WallTime::now();
    if (!port_.is_open()) {
      if ((now - last_open_attempt_).toSec() >= params_.reopen_period_s) try_open(now);
      if (!port_.is_open()) ros::WallDuration(0.02).sleep();
    } else {
      std::size_t got = 0;
      const auto r = port_.read(buf.data(), buf.size(), kReadTimeoutMs, &got);
      const ros::WallTime at = ros::WallTime::now();
      if (r == drone_ros_common::SerialPort::ReadResult::kGone) {
        port_gone("port closed or device unplugged");
      } else {
        frames.clear();
        framer_.feed(buf.data(), got, at.toSec(), &frames);
        for (const Frame &f : frames) {
          last_rx_ = ros::Time::now();
          handle_frame(f);
        }
        if (!link_up_ && (at - last_topic_request_).toSec() >= params_.topic_request_period_s) {
          // A silent or rebooted device: ask again, as rosserial hosts do.
          last_topic_request_ = at;
          (void)send_raw(topic_request_frame());
        } else if (link_up_ && !confirm_topics_at_.isZero() && at >= confirm_topics_at_) {
          // No frame says a device has announced all its topics, and one TopicInfo lost on the
          // wire (a full USB buffer) left a topic unannounced while the others brought the link
          // up, for good: CI's QEMU board lost its two subscribers' and the HA never got a
          // command. Every answer that brings a new topic is confirmed by asking once more; the
          // device answers whole each time, and an answer with nothing new ends it.
          confirm_topics_at_ = ros::WallTime();
          last_topic_request_ = at;
          ++counters_.topic_confirmations;
          (void)send_raw(topic_request_frame());
        }
      }
    }
    update_link_state(ros::WallTime::now());
    updater_.update();
  }
  spinner.stop();
}

void ArduinoLinkNode::try_open(const ros::WallTime &now) {
  last_open_attempt_ = now;
  std::string error;
  bool opened;
  {
    std::lock_guard<std::mutex> lock(port_mutex_);
    opened = port_.open(params_.port, params_.baud, &error);
  }
  if (!opened) {
    if (error != last_error_)
      ROS_WARN("arduino: cannot open %s: %s (retrying)", params_.port.c_str(), error.c_str());
    last_error_ = error;
    return;
  }
  last_error_.clear();
  ++counters_.port_opens;
  ROS_INFO("arduino: opened %s at %d baud, requesting topics", params_.port.c_str(), params_.baud);
  framer_.reset();
  negotiated_ = false;
  last_rx_ = ros::Time::now();
  last_topic_request_ = now;
  (void)send_raw(topic_request_frame());
}

void ArduinoLinkNode::port_gone(const char *why) {
  {
    std::lock_guard<std::mutex> lock(port_mutex_);
    port_.close();
  }
  negotiated_ = false;
  last_open_attempt_ = ros::WallTime::now();
  ROS_WARN("arduino: %s on %s; will reopen", why, params_.port.c_str());
}

void ArduinoLinkNode::handle_frame(const Frame &f) {
  switch (f.topic_id) {
    case kIdPublisher:
      on_publisher_info(f);
      return;
    case kIdSubscriber:
      on_subscriber_info(f);
      return;
    case kIdTime:
      on_time_request();
      return;
    case kIdParameterRequest:
      on_param_request(f);
      return;
    case kIdLog:
      on_log(f);
      return;
    default:
      break;
  }
  // Published under the lock, as before the callbacks went inline: a publish only queues the
  // message for roscpp's receive thread, so it never waits on a callback that waits on the lock.
  std::lock_guard<std::mutex> lock(endpoints_mutex_);
  auto it = endpoints_.find(f.topic_id);
  if (it == endpoints_.end() || !it->second.pub) {
    ++counters_.unknown_topic;
    return;
  }
  on_device_data(it->second, f);
}

void ArduinoLinkNode::refuse(const char *what, const std::string &why) {
  ++counters_.bad_payload;
  // Throttled: a device stuck repeating a bad frame must not flood rosout; the counter has all.
  ROS_WARN_THROTTLE(5.0, "arduino: dropped the device's %s: %s (counted as bad_payload)", what,
                    why.c_str());
}

bool ArduinoLinkNode::accept_announcement(const Frame &f, TopicAnnouncement *a) {
  std::string why;
  if (!decode_topic_announcement(f.payload, a, &why)) {
    refuse("topic announcement", why);
    return false;
  }
  // roscpp throws on a name it cannot resolve; ask it first rather than abort the node.
  if (!ros::names::validate(a->name, why)) {
    refuse("topic announcement", "topic name '" + a->name + "': " + why);
    return false;
  }
  return true;
}

ArduinoLinkNode::Endpoint ArduinoLinkNode::endpoint_for(const TopicAnnouncement &a) {
  Endpoint ep;
  ep.name = a.name;
  ep.type = a.type;
  ep.md5 = a.md5;
  ep.buffer_size = a.buffer_size;
  ep.known = find_known_type(ep.type, ep.md5);
  return ep;
}

void ArduinoLinkNode::on_publisher_info(const Frame &f) {
  TopicAnnouncement info;
  if (!accept_announcement(f, &info)) return;
  negotiated_ = true;
  Endpoint ep = endpoint_for(info);
  // Declared before the lock, so destroyed after it: an id the device used for a subscriber has
  // one to let go, and that waits for the subscription's lock, held while on_ros_message waits
  // for endpoints_mutex_.
  Endpoint older;
  std::lock_guard<std::mutex> lock(endpoints_mutex_);
  auto it = endpoints_.find(info.topic_id);
  if (it != endpoints_.end() && it->second.pub && it->second.name == ep.name &&
      it->second.md5 == ep.md5) {
    return;  // the same device came back: keep the publisher, subscribers see no gap in topology
  }
  try {
    if (ep.type == ros::message_traits::DataType<drone_ros::pwm>::value() &&
        nh_.resolveName(ep.name) == pwm_pub_.getTopic()) {
      if (ep.md5 != ros::message_traits::MD5Sum<drone_ros::pwm>::value()) {
        ++counters_.md5_mismatch;
        ROS_ERROR("arduino: device's drone_ros/pwm md5 %s differs from ours; not publishing it",
                  ep.md5.c_str());
        return;
      }
      ep.is_pwm = true;
      ep.pub = pwm_pub_;
    } else {
      // Home is sent rarely (on a change, every few seconds): latched, so a node started or
      // restarted later (the controller after an HP restart) has it at once.
      const bool latch = ep.type == ros::message_traits::DataType<drone_ros::HomePosition>::value();
      topic_tools::ShapeShifter shape;
      shape.morph(ep.md5, ep.type, ep.definition(), latch ? "true" : "false");
      ep.pub = shape.advertise(nh_, ep.name, 10, latch);
    }
  } catch (const ros::Exception &e) {
    // Whatever else roscpp refuses (validated names can still clash with remappings, say).
    refuse("publisher", ep.name + ": " + e.what());
    return;
  }
  if (!ep.pub) {  // roscpp logs why without throwing, e.g. the topic is taken by another type
    refuse("publisher", ep.name + ": ROS did not advertise it");
    return;
  }
  ROS_INFO("arduino: device publishes %s [%s] as id %u", ep.name.c_str(), ep.type.c_str(),
           info.topic_id);
  older = std::move(endpoints_[info.topic_id]);
  endpoints_[info.topic_id] = ep;
  confirm_topics_later();
}

void ArduinoLinkNode::confirm_topics_later() {
  confirm_topics_at_ = ros::WallTime::now() + ros::WallDuration(params_.topic_request_period_s);
}

void ArduinoLinkNode::on_subscriber_info(const Frame &f) {
  TopicAnnouncement info;
  if (!accept_announcement(f, &info)) return;
  negotiated_ = true;
  const uint16_t id = info.topic_id;
  {
    std::lock_guard<std::mutex> lock(endpoints_mutex_);
    auto existing = endpoints_.find(id);
    if (existing != endpoints_.end() && existing->second.sub &&
        existing->second.name == info.name && existing->second.md5 == info.md5) {
      existing->second.buffer_size = info.buffer_size;
      return;
    }
  }
  // The new entry goes in first, so that a message on the new subscription finds its own md5;
  // the older subscriber (a re-announced id) is let go and the new one made outside
  // endpoints_mutex_: roscpp holds a subscription's own lock while it hands on_ros_message a
  // message, and on_ros_message takes endpoints_mutex_.
  Endpoint ep = endpoint_for(info);
  {
    Endpoint older;
    {
      std::lock_guard<std::mutex> lock(endpoints_mutex_);
      older = std::move(endpoints_[id]);
      endpoints_[id] = ep;
    }
  }
  ros::Subscriber sub;
  try {
    ros::SubscribeOptions ops;
    ops.init<topic_tools::ShapeShifter>(
        ep.name, 10,
        [this, id](const topic_tools::ShapeShifter::ConstPtr &msg) { on_ros_message(id, msg); });
    ops.transport_hints = ros::TransportHints().tcpNoDelay();  // a command must not wait for Nagle
    // Simulated time: a command goes to the port as it arrives (inline_queue.h). On the wall
    // clock the spinner writes it, so that a port that stops draining (a write waits up to
    // 100 ms) never holds up roscpp's receive thread, which also sends what the node publishes.
    if (ros::Time::isSimTime()) ops.callback_queue = &inline_;
    sub = nh_.subscribe(ops);
  } catch (const ros::Exception &e) {
    refuse("subscriber", ep.name + ": " + e.what());
    return;
  }
  ROS_INFO("arduino: device subscribes to %s [%s] as id %u", ep.name.c_str(), ep.type.c_str(), id);
  {
    std::lock_guard<std::mutex> lock(endpoints_mutex_);
    endpoints_[id].sub = sub;
  }
  confirm_topics_later();
}

void ArduinoLinkNode::on_ros_message(uint16_t topic_id,
                                     const topic_tools::ShapeShifter::ConstPtr &msg) {
  int32_t buffer_size = 0;
  {
    std::lock_guard<std::mutex> lock(endpoints_mutex_);
    auto it = endpoints_.find(topic_id);
    if (it == endpoints_.end()) return;
    if (msg->getMD5Sum() != it->second.md5) {
      ++counters_.md5_mismatch;
      ROS_WARN_THROTTLE(5.0, "arduino: %s carries %s, the device expects md5 %s; dropped",
                        it->second.name.c_str(), msg->getDataType().c_str(),
                        it->second.md5.c_str());
      return;
    }
    buffer_size = it->second.buffer_size;
  }
  std::vector<uint8_t> payload(msg->size());
  ros::serialization::OStream out(payload.data(), static_cast<uint32_t>(payload.size()));
  msg->write(out);
  if (buffer_size > 0 && payload.size() > static_cast<std::size_t>(buffer_size)) {
    ++counters_.tx_too_big;
    return;
  }
  if (send(topic_id, payload)) ++counters_.commands_forwarded;
}

void ArduinoLinkNode::on_device_data(Endpoint &ep, const Frame &f) {
  if (ep.is_pwm) {
    drone_ros::pwm pwm;
    try {
      ros::serialization::IStream in(const_cast<uint8_t *>(f.payload.data()),
                                     static_cast<uint32_t>(f.payload.size()));
      ros::serialization::deserialize(in, pwm);
      if (in.getLength() != 0) throw ros::serialization::StreamOverrunException("trailing bytes");
    } catch (const ros::Exception &) {
      refuse("message", "not one drone_ros/pwm on " + ep.name);
      return;
    }
    pwm.usbstatus = 1;  // this field is the node's to set: the frame just arrived over the link
    ep.pub.publish(pwm);
    return;
  }
  // A type the node knows is checked before ROS subscribers see it: they would fail to
  // deserialize it one by one, each in its own way.
  if (ep.known != nullptr && !ep.known->decodes(f.payload.data(), f.payload.size())) {
    refuse("message", "not one " + ep.type + " on " + ep.name);
    return;
  }
  topic_tools::ShapeShifter shape;
  shape.morph(ep.md5, ep.type, ep.definition(), "false");
  ros::serialization::IStream in(const_cast<uint8_t *>(f.payload.data()),
                                 static_cast<uint32_t>(f.payload.size()));
  shape.read(in);
  ep.pub.publish(shape);
}

// The device sets its clock by this answer and stamps what it publishes with it. Under simulated
// time ros::Time::now() is the last /clock roscpp's own thread has taken from its queue: on a
// loaded machine a lockstep simulator may be 0.2 s further on by then, and the device's stamps
// would lag the flight by that until its next sync. The same message reaches our subscription
// first, in the receive thread, so its newest /clock is never older.
ros::Time ArduinoLinkNode::time_for_device() {
  const ros::Time now = ros::Time::now();
  const uint64_t newest_ns = newest_clock_ns_.load();
  if (newest_ns <= now.toNSec()) return now;
  counters_.time_answers_behind_clock++;
  const uint64_t lag_ns = newest_ns - now.toNSec();
  if (lag_ns > counters_.time_answer_lag_max_ns.load()) counters_.time_answer_lag_max_ns = lag_ns;
  ros::Time t;
  t.fromNSec(newest_ns);
  return t;
}

void ArduinoLinkNode::on_time_request() {
  const ros::Time now = time_for_device();
  std_msgs_Time t;
  t.data.sec = now.sec;
  t.data.nsec = now.nsec;
  std::vector<uint8_t> payload(8);
  std::size_t n = 0;
  if (std_msgs_Time_serialize(&t, payload.data(), payload.size(), &n)) (void)send(kIdTime, payload);
}

void ArduinoLinkNode::on_param_request(const Frame &f) {
  std::string name;
  if (!decode_param_request(f.payload, &name)) {
    refuse("parameter request", "not a rosserial_msgs/RequestParam request");
    return;
  }
  ParamValues values;  // stays empty, rosserial's "not set", unless the parameter can be sent
  XmlRpc::XmlRpcValue value;
  std::string why;
  bool have = false;
  if (!ros::names::validate(name, why)) {  // getParam would throw on it
    refuse("parameter request", "name '" + name + "': " + why);
  } else {
    try {
      have = nh_.getParam(name, value);
    } catch (const ros::Exception &e) {
      why = e.what();
    }
    if (!have)
      ROS_WARN("arduino: device asked for parameter %s, which is not set %s", name.c_str(),
               why.c_str());
  }
  if (have) {
    std::vector<XmlRpc::XmlRpcValue> items;
    if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      for (int i = 0; i < value.size(); ++i) items.push_back(value[i]);
    } else {
      items.push_back(value);
    }
    for (auto &v : items) {
      switch (v.getType()) {
        case XmlRpc::XmlRpcValue::TypeInt:
          values.ints.push_back(static_cast<int>(v));
          break;
        case XmlRpc::XmlRpcValue::TypeBoolean:
          values.ints.push_back(static_cast<bool>(v) ? 1 : 0);
          break;
        case XmlRpc::XmlRpcValue::TypeDouble:
          values.floats.push_back(static_cast<float>(static_cast<double>(v)));
          break;
        case XmlRpc::XmlRpcValue::TypeString:
          values.strings.push_back(static_cast<std::string>(v));
          break;
        default:
          break;  // structs, dates, binary: rosserial has no way to carry them
      }
    }
  }
  std::vector<uint8_t> payload;
  if (!encode_param_reply(values, static_cast<std::size_t>(params_.max_payload), &payload, &why)) {
    ROS_WARN("arduino: parameter %s cannot go to the device (%s); answering not set", name.c_str(),
             why.c_str());
    (void)encode_param_reply(ParamValues{}, static_cast<std::size_t>(params_.max_payload), &payload,
                             &why);
  }
  (void)send(kIdParameterRequest, payload);  // always answer: ros_lib waits for a reply
}

void ArduinoLinkNode::on_log(const Frame &f) {
  DeviceLog log;
  if (!decode_device_log(f.payload, &log)) {
    refuse("log", "not a rosserial_msgs/Log");
    return;
  }
  // rosserial's levels in order (ROSDEBUG 0 .. FATAL 4); a level from a newer device is FATAL.
  static const ros::console::levels::Level kLevels[] = {
      ros::console::levels::Debug, ros::console::levels::Info, ros::console::levels::Warn,
      ros::console::levels::Error, ros::console::levels::Fatal};
  const auto level =
      log.level <= ROSSERIAL_MSGS_LOG_FATAL ? kLevels[log.level] : ros::console::levels::Fatal;
  ROS_LOG(level, ROSCONSOLE_DEFAULT_NAME, "[HA] %s", log.text.c_str());
}

bool ArduinoLinkNode::send(uint16_t topic_id, const std::vector<uint8_t> &payload) {
  return send_raw(encode_frame(topic_id, payload.data(), payload.size()));
}

bool ArduinoLinkNode::send_raw(const std::vector<uint8_t> &bytes) {
  std::lock_guard<std::mutex> lock(port_mutex_);
  if (!port_.is_open() || !port_.write_all(bytes.data(), bytes.size())) {
    ++counters_.tx_failed;
    return false;
  }
  return true;
}

void ArduinoLinkNode::update_link_state(const ros::WallTime &now) {
  framer_.poll(now.toSec());
  const bool up = port_.is_open() && negotiated_ &&
                  (ros::Time::now() - last_rx_).toSec() < params_.link_timeout_s;
  if (up && !link_up_) {
    last_gap_s_ = (now - lost_since_).toSec();
    ROS_INFO("arduino: HA link up (gap %.3f s)", last_gap_s_);
  } else if (!up && link_up_) {
    lost_since_ = now;
    ++counters_.outages;
    ROS_ERROR("arduino: HA link lost (%s)", port_.is_open() ? "no frames" : "port gone");
    negotiated_ = negotiated_ && port_.is_open();
  }
  link_up_ = up;
  if (!link_up_ && (now - last_lost_pwm_).toSec() >= 1.0 / params_.lost_pwm_rate_hz) {
    last_lost_pwm_ = now;
    publish_lost_pwm();
  }
}

void ArduinoLinkNode::publish_lost_pwm() {
  drone_ros::pwm pwm;
  pwm.header.stamp = ros::Time::now();
  pwm.usbstatus = 0;  // everything else is unknown: zeros, as the original node sent
  pwm_pub_.publish(pwm);
}

void ArduinoLinkNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper &stat) {
  using diagnostic_msgs::DiagnosticStatus;
  if (link_up_) {
    stat.summary(DiagnosticStatus::OK, "HA link up");
  } else {
    stat.summaryf(DiagnosticStatus::ERROR, "HA link lost for %.1f s",
                  (ros::WallTime::now() - lost_since_).toSec());
  }
  const FramerCounters &fc = framer_.counters();
  stat.add("port", params_.port);
  stat.add("port_open", port_.is_open());
  stat.add("outages", counters_.outages.load());
  stat.add("topic_confirmations", counters_.topic_confirmations.load());
  stat.add("last_gap_s", last_gap_s_);
  stat.add("port_opens", counters_.port_opens.load());
  stat.add("frames_ok", fc.frames_ok);
  stat.add("bytes_skipped", fc.bytes_skipped);
  stat.add("bad_protocol", fc.bad_protocol);
  stat.add("bad_length_checksum", fc.bad_length_checksum);
  stat.add("oversized", fc.oversized);
  stat.add("bad_checksum", fc.bad_checksum);
  stat.add("frame_timeouts", fc.timeouts);
  stat.add("unknown_topic", counters_.unknown_topic.load());
  stat.add("bad_payload", counters_.bad_payload.load());
  stat.add("md5_mismatch", counters_.md5_mismatch.load());
  stat.add("tx_failed", counters_.tx_failed.load());
  stat.add("tx_too_big", counters_.tx_too_big.load());
  stat.add("commands_forwarded", counters_.commands_forwarded.load());
  if (ros::Time::isSimTime()) {
    stat.add("time_answers_behind_clock", counters_.time_answers_behind_clock.load());
    stat.add("time_answer_lag_max_s",
             1e-9 * static_cast<double>(counters_.time_answer_lag_max_ns.load()));
  }
}

}  // namespace arduino_link
