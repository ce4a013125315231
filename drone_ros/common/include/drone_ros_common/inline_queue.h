// A roscpp callback queue that runs each callback at once, in the thread that hands it over.
#ifndef DRONE_ROS_COMMON_INLINE_QUEUE_H
#define DRONE_ROS_COMMON_INLINE_QUEUE_H

#include <ros/callback_queue_interface.h>

#include <mutex>

namespace drone_ros_common {

// Given to a subscription (SubscribeOptions::callback_queue, NodeHandle::setCallbackQueue), its
// callback runs in roscpp's receive thread as the message arrives, with no spinner thread to
// wake: a lockstep step's last input reached the controller, and a command the arduino node,
// 20-30 us sooner each (a 60 s HiL flight at 100 Hz: 17.9x -> 18.5x real time). Both use it
// under simulated time only: on the wall clock a callback that may wait (a write to a port that
// stops draining, a timer to re-arm) stays on a spinner thread.
//
// The callbacks run one at a time, under mutex(), which a node's other callbacks (timers,
// services: ros::spin()'s) take too, so that the node still runs one callback at a time. Rules
// for what runs here, since roscpp holds the subscription's lock meanwhile and the receive thread
// serves every connection of the process:
// - never start or stop a roscpp timer (the timer thread would wait on a callback that waits on
//   it), never call a service, never wait long;
// - never subscribe or unsubscribe while holding a lock such a callback takes.
// Nothing runs after close(); one running when it is called finishes first.
class InlineQueue : public ros::CallbackQueueInterface {
 public:
  void addCallback(const ros::CallbackInterfacePtr &callback, uint64_t /*owner_id*/) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!closed_) (void)callback->call();  // TryAgain cannot come: no other thread calls it
  }
  void removeByID(uint64_t /*owner_id*/) override {}  // nothing is ever held

  // From the node's destructor, before the state its callbacks use goes.
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  std::mutex &mutex() { return mutex_; }

 private:
  std::mutex mutex_;
  bool closed_ = false;
};

}  // namespace drone_ros_common

#endif  // DRONE_ROS_COMMON_INLINE_QUEUE_H
