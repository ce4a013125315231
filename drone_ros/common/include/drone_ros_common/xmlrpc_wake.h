// Ends roscpp's XML-RPC slices early, so that a node connects to a new peer in milliseconds.
#ifndef DRONE_ROS_COMMON_XMLRPC_WAKE_H
#define DRONE_ROS_COMMON_XMLRPC_WAKE_H

#include <ros/xmlrpc_manager.h>
#include <sys/timerfd.h>
#include <unistd.h>
#include <xmlrpcpp/XmlRpcDispatch.h>
#include <xmlrpcpp/XmlRpcSource.h>

#include <boost/make_shared.hpp>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace drone_ros_common {

// How often each of the project's nodes takes its new connections (roscpp alone: every 0.1 s).
constexpr double kXmlRpcWakePeriodS = 0.01;

// roscpp's XML-RPC thread runs XmlRpcDispatch::work(0.1) in a loop, and only between two calls
// does it hand a new connection's requestTopic to the dispatcher, and act on the answer (open
// the TCPROS link). Each call runs its whole 0.1 s, whatever arrives. So a subscriber takes one
// to two slices to connect to a publisher that appears: a restarted controller's inputs, and its
// commands reaching the arduino node. In lockstep the simulator holds time meanwhile (0.2-0.35 s
// of wall time a restart, a ninth of a 60 s flight at 18.5x); in flight the HA flies the safety
// controller that much longer.
//
// XmlRpcWake is a timerfd among the dispatcher's sources: each tick, handled in the XML-RPC
// thread, ends the current work() (XmlRpcDispatch::exit, which is meant to be called from a
// source's handler), so the loop takes its pending connections every period_s instead. The
// XML-RPC thread wakes 1/period_s times a second for a few microseconds each.
class XmlRpcWake : public ros::ASyncXMLRPCConnection, public XmlRpc::XmlRpcSource {
 public:
  // Adds a wake to this process's XML-RPC thread; it lasts as long as that thread's manager.
  // Throws std::runtime_error if the timer cannot be made (the node then says so and exits).
  static void install(double period_s) {
    if (!(period_s > 0.0) || period_s >= 0.1) {
      throw std::runtime_error("XmlRpcWake: period must be in (0, 0.1) s, not " +
                               std::to_string(period_s));
    }
    ros::XMLRPCManager::instance()->addASyncConnection(boost::make_shared<XmlRpcWake>(period_s));
  }

  explicit XmlRpcWake(double period_s) : XmlRpc::XmlRpcSource(-1, false) {
    const int fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    if (fd < 0) {
      throw std::runtime_error(std::string("XmlRpcWake: timerfd_create: ") + std::strerror(errno));
    }
    itimerspec spec{};
    const auto ns = static_cast<long>(std::lround(period_s * 1e9));
    spec.it_interval.tv_sec = ns / 1000000000L;
    spec.it_interval.tv_nsec = ns % 1000000000L;
    spec.it_value = spec.it_interval;
    if (timerfd_settime(fd, 0, &spec, nullptr) != 0) {
      const int err = errno;
      ::close(fd);
      throw std::runtime_error(std::string("XmlRpcWake: timerfd_settime: ") + std::strerror(err));
    }
    setfd(fd);
  }
  ~XmlRpcWake() override { close(); }
  XmlRpcWake(const XmlRpcWake &) = delete;
  XmlRpcWake &operator=(const XmlRpcWake &) = delete;

  // Called by the XML-RPC thread only, as are the two below.
  void addToDispatch(XmlRpc::XmlRpcDispatch *disp) override {
    dispatch_ = disp;
    disp->addSource(this, XmlRpc::XmlRpcDispatch::ReadableEvent);
  }
  void removeFromDispatch(XmlRpc::XmlRpcDispatch *disp) override {
    disp->removeSource(this);
    dispatch_ = nullptr;
  }
  bool check() override { return false; }  // never done: it stays for the process's life

  unsigned handleEvent(unsigned /*event_type*/) override {
    std::uint64_t ticks = 0;
    (void)!::read(getfd(), &ticks, sizeof ticks);  // EAGAIN (no tick yet) changes nothing
    if (dispatch_ != nullptr) dispatch_->exit();
    return XmlRpc::XmlRpcDispatch::ReadableEvent;
  }

  // The dispatcher closes its sources as the manager shuts down; the destructor may come after.
  void close() override {
    if (getfd() >= 0) {
      ::close(getfd());
      setfd(-1);
    }
  }

 private:
  XmlRpc::XmlRpcDispatch *dispatch_ = nullptr;
};

}  // namespace drone_ros_common

#endif  // DRONE_ROS_COMMON_XMLRPC_WAKE_H
