#include "arduino_link_node.h"

#include <drone_ros/pwm.h>
#include <ros/serialization.h>
#include <std_msgs/Time.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <boost/function.hpp>

#include "ha_link_msgs.h"
#include "message_definitions.h"

namespace arduino_link {

namespace {
// rosserial's reserved topic ids (rosserial_msgs/TopicInfo), from the generated constants.
constexpr uint16_t kIdPublisher = ROSSERIAL_MSGS_TOPICINFO_ID_PUBLISHER;
constexpr uint16_t kIdSubscriber = ROSSERIAL_MSGS_TOPICINFO_ID_SUBSCRIBER;
constexpr uint16_t kIdParameterRequest = ROSSERIAL_MSGS_TOPICINFO_ID_PARAMETER_REQUEST;
constexpr uint16_t kIdLog = ROSSERIAL_MSGS_TOPICINFO_ID_LOG;
constexpr uint16_t kIdTime = ROSSERIAL_MSGS_TOPICINFO_ID_TIME;
constexpr int kReadTimeoutMs = 20;

std::string to_string(const HaRosString &s) { return std::string(s.data, s.len); }
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
}

ArduinoLinkNode::~ArduinoLinkNode() {
  std::lock_guard<std::mutex> lock(port_mutex_);
  if (port_.is_open()) {
    const auto stop = tx_stop_frame();  // tell the device we are going, as rosserial does
    (void)port_.write_all(stop.data(), stop.size());
    port_.close();
  }
}

void ArduinoLinkNode::run() {
  ros::AsyncSpinner spinner(1);  // subscriber callbacks write to the port without waiting for us
  spinner.start();
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
          last_rx_ = at;
          handle_frame(f);
        }
        if (!link_up_ && (at - last_topic_request_).toSec() >= params_.topic_request_period_s) {
          // A silent or rebooted device: ask again, as rosserial hosts do.
          last_topic_request_ = at;
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
    if (error != last_error_) ROS_WARN("arduino: cannot open %s: %s (retrying)", params_.port.c_str(), error.c_str());
    last_error_ = error;
    return;
  }
  last_error_.clear();
  ++counters_.port_opens;
  ROS_INFO("arduino: opened %s at %d baud, requesting topics", params_.port.c_str(), params_.baud);
  framer_.reset();
  negotiated_ = false;
  last_rx_ = now;
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
    case kIdPublisher: on_publisher_info(f); return;
    case kIdSubscriber: on_subscriber_info(f); return;
    case kIdTime: on_time_request(); return;
    case kIdParameterRequest: on_param_request(f); return;
    case kIdLog: on_log(f); return;
    default: break;
  }
  std::lock_guard<std::mutex> lock(endpoints_mutex_);
  auto it = endpoints_.find(f.topic_id);
  if (it == endpoints_.end() || !it->second.pub) {
    ++counters_.unknown_topic;
    return;
  }
  on_device_data(it->second, f);
}

void ArduinoLinkNode::on_publisher_info(const Frame &f) {
  rosserial_msgs_TopicInfo info;
  std::size_t used = 0;
  if (!rosserial_msgs_TopicInfo_deserialize(&info, f.payload.data(), f.payload.size(), &used) ||
      used != f.payload.size()) {
    ++counters_.bad_payload;
    return;
  }
  negotiated_ = true;
  Endpoint ep;
  ep.name = to_string(info.topic_name);
  ep.type = to_string(info.message_type);
  ep.md5 = to_string(info.md5sum);
  ep.buffer_size = info.buffer_size;
  std::lock_guard<std::mutex> lock(endpoints_mutex_);
  auto it = endpoints_.find(info.topic_id);
  if (it != endpoints_.end() && it->second.pub && it->second.name == ep.name && it->second.md5 == ep.md5) {
    return;  // the same device came back: keep the publisher, subscribers see no gap in topology
  }
  if (ep.type == ros::message_traits::DataType<drone_ros::pwm>::value() && nh_.resolveName(ep.name) == pwm_pub_.getTopic()) {
    if (ep.md5 != ros::message_traits::MD5Sum<drone_ros::pwm>::value()) {
      ++counters_.md5_mismatch;
      ROS_ERROR("arduino: device's drone_ros/pwm md5 %s differs from ours; not publishing it", ep.md5.c_str());
      return;
    }
    ep.is_pwm = true;
    ep.pub = pwm_pub_;
  } else {
    topic_tools::ShapeShifter shape;
    ep.definition = known_definition(ep.type, ep.md5);
    shape.morph(ep.md5, ep.type, ep.definition, "false");
    ep.pub = shape.advertise(nh_, ep.name, 10);
  }
  ROS_INFO("arduino: device publishes %s [%s] as id %u", ep.name.c_str(), ep.type.c_str(), info.topic_id);
  endpoints_[info.topic_id] = ep;
}

void ArduinoLinkNode::on_subscriber_info(const Frame &f) {
  rosserial_msgs_TopicInfo info;
  std::size_t used = 0;
  if (!rosserial_msgs_TopicInfo_deserialize(&info, f.payload.data(), f.payload.size(), &used) ||
      used != f.payload.size()) {
    ++counters_.bad_payload;
    return;
  }
  negotiated_ = true;
  const uint16_t id = info.topic_id;
  std::lock_guard<std::mutex> lock(endpoints_mutex_);
  Endpoint &ep = endpoints_[id];
  const std::string name = to_string(info.topic_name);
  const std::string md5 = to_string(info.md5sum);
  ep.buffer_size = info.buffer_size;
  if (ep.sub && ep.name == name && ep.md5 == md5) return;
  ep.name = name;
  ep.type = to_string(info.message_type);
  ep.md5 = md5;
  boost::function<void(const topic_tools::ShapeShifter::ConstPtr &)> cb =
      [this, id](const topic_tools::ShapeShifter::ConstPtr &msg) { on_ros_message(id, msg); };
  // TCP_NODELAY: a servo command must not wait for Nagle.
  ep.sub = nh_.subscribe<topic_tools::ShapeShifter>(ep.name, 10, cb, ros::VoidConstPtr(),
                                                   ros::TransportHints().tcpNoDelay());
  ROS_INFO("arduino: device subscribes to %s [%s] as id %u", ep.name.c_str(), ep.type.c_str(), id);
}

void ArduinoLinkNode::on_ros_message(uint16_t topic_id, const topic_tools::ShapeShifter::ConstPtr &msg) {
  int32_t buffer_size = 0;
  {
    std::lock_guard<std::mutex> lock(endpoints_mutex_);
    auto it = endpoints_.find(topic_id);
    if (it == endpoints_.end()) return;
    if (msg->getMD5Sum() != it->second.md5) {
      ++counters_.md5_mismatch;
      ROS_WARN_THROTTLE(5.0, "arduino: %s carries %s, the device expects md5 %s; dropped",
                        it->second.name.c_str(), msg->getDataType().c_str(), it->second.md5.c_str());
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
      ros::serialization::IStream in(const_cast<uint8_t *>(f.payload.data()), static_cast<uint32_t>(f.payload.size()));
      ros::serialization::deserialize(in, pwm);
      if (in.getLength() != 0) throw ros::serialization::StreamOverrunException("trailing bytes");
    } catch (const ros::Exception &) {
      ++counters_.bad_payload;
      return;
    }
    pwm.usbstatus = 1;  // this field is the node's to set: the frame just arrived over the link
    ep.pub.publish(pwm);
    return;
  }
  topic_tools::ShapeShifter shape;
  shape.morph(ep.md5, ep.type, ep.definition, "false");
  ros::serialization::IStream in(const_cast<uint8_t *>(f.payload.data()), static_cast<uint32_t>(f.payload.size()));
  shape.read(in);
  ep.pub.publish(shape);
}

void ArduinoLinkNode::on_time_request() {
  const ros::Time now = ros::Time::now();
  std_msgs_Time t;
  t.data.sec = now.sec;
  t.data.nsec = now.nsec;
  std::vector<uint8_t> payload(8);
  std::size_t n = 0;
  if (std_msgs_Time_serialize(&t, payload.data(), payload.size(), &n)) (void)send(kIdTime, payload);
}

void ArduinoLinkNode::on_param_request(const Frame &f) {
  rosserial_msgs_RequestParamRequest req;
  std::size_t used = 0;
  if (!rosserial_msgs_RequestParamRequest_deserialize(&req, f.payload.data(), f.payload.size(), &used) ||
      used != f.payload.size()) {
    ++counters_.bad_payload;
    return;
  }
  const std::string name = to_string(req.name);
  rosserial_msgs_RequestParamResponse resp{};
  std::vector<std::string> strings;  // owns the text resp.strings point to
  XmlRpc::XmlRpcValue value;
  if (!nh_.getParam(name, value)) {
    ROS_WARN("arduino: device asked for parameter %s, which is not set", name.c_str());
  } else {
    std::vector<XmlRpc::XmlRpcValue> items;
    if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
      for (int i = 0; i < value.size(); ++i) items.push_back(value[i]);
    } else {
      items.push_back(value);
    }
    for (auto &v : items) {
      if (v.getType() == XmlRpc::XmlRpcValue::TypeString) strings.push_back(static_cast<std::string>(v));
    }
    bool fits = true;
    for (auto &v : items) {
      switch (v.getType()) {
        case XmlRpc::XmlRpcValue::TypeInt:
          fits = fits && resp.ints_count < HA_MSGS_VAR_ARRAY_CAP;
          if (fits) resp.ints[resp.ints_count++] = static_cast<int>(v);
          break;
        case XmlRpc::XmlRpcValue::TypeBoolean:
          fits = fits && resp.ints_count < HA_MSGS_VAR_ARRAY_CAP;
          if (fits) resp.ints[resp.ints_count++] = static_cast<bool>(v) ? 1 : 0;
          break;
        case XmlRpc::XmlRpcValue::TypeDouble:
          fits = fits && resp.floats_count < HA_MSGS_VAR_ARRAY_CAP;
          if (fits) resp.floats[resp.floats_count++] = static_cast<float>(static_cast<double>(v));
          break;
        default:
          break;
      }
    }
    fits = fits && strings.size() <= HA_MSGS_VAR_ARRAY_CAP;
    if (!fits) {
      ROS_WARN("arduino: parameter %s has more than %u values per type; the device cannot hold it", name.c_str(),
               HA_MSGS_VAR_ARRAY_CAP);
      resp = rosserial_msgs_RequestParamResponse{};
      strings.clear();
    }
    for (const auto &s : strings) resp.strings[resp.strings_count++] = HaRosString{s.data(), static_cast<uint32_t>(s.size())};
  }
  std::vector<uint8_t> payload(static_cast<std::size_t>(params_.max_payload));
  std::size_t n = 0;
  if (rosserial_msgs_RequestParamResponse_serialize(&resp, payload.data(), payload.size(), &n)) {
    payload.resize(n);
    (void)send(kIdParameterRequest, payload);
  }
}

void ArduinoLinkNode::on_log(const Frame &f) {
  rosserial_msgs_Log log;
  std::size_t used = 0;
  if (!rosserial_msgs_Log_deserialize(&log, f.payload.data(), f.payload.size(), &used) || used != f.payload.size()) {
    ++counters_.bad_payload;
    return;
  }
  const std::string text = "[HA] " + to_string(log.msg);
  switch (log.level) {
    case ROSSERIAL_MSGS_LOG_ROSDEBUG: ROS_DEBUG("%s", text.c_str()); break;
    case ROSSERIAL_MSGS_LOG_INFO: ROS_INFO("%s", text.c_str()); break;
    case ROSSERIAL_MSGS_LOG_WARN: ROS_WARN("%s", text.c_str()); break;
    case ROSSERIAL_MSGS_LOG_ERROR: ROS_ERROR("%s", text.c_str()); break;
    default: ROS_FATAL("%s", text.c_str()); break;  // FATAL, or a level from a newer device
  }
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
  const bool up = port_.is_open() && negotiated_ && (now - last_rx_).toSec() < params_.link_timeout_s;
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
    stat.summaryf(DiagnosticStatus::ERROR, "HA link lost for %.1f s", (ros::WallTime::now() - lost_since_).toSec());
  }
  const FramerCounters &fc = framer_.counters();
  stat.add("port", params_.port);
  stat.add("port_open", port_.is_open());
  stat.add("outages", counters_.outages.load());
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
}

}  // namespace arduino_link
