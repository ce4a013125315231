// drone_ros_common::InlineQueue, as the controller and the arduino node use it: a callback runs
// at once in the thread that hands it over, callbacks never overlap (nor with code holding the
// queue's lock), and after close() nothing runs, while close() waits for the one running.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <thread>
#include <vector>

#include "drone_ros_common/inline_queue.h"

namespace {

class Fn : public ros::CallbackInterface {
 public:
  explicit Fn(std::function<void()> f) : f_(std::move(f)) {}
  CallResult call() override {
    f_();
    return Success;
  }

 private:
  std::function<void()> f_;
};

ros::CallbackInterfacePtr fn(std::function<void()> f) {
  return boost::make_shared<Fn>(std::move(f));
}

TEST(InlineQueue, AMessageRunsItsCallbackAtOnceInTheThreadThatReceivedIt) {
  drone_ros_common::InlineQueue q;
  std::thread::id ran_in;
  int calls = 0;
  q.addCallback(fn([&] {
                  ran_in = std::this_thread::get_id();
                  ++calls;
                }),
                1);
  EXPECT_EQ(calls, 1);  // before addCallback returned: nothing left for a spinner
  EXPECT_EQ(ran_in, std::this_thread::get_id());
}

TEST(InlineQueue, CallbacksFromTwoThreadsAndATimerHoldingTheLockNeverOverlap) {
  drone_ros_common::InlineQueue q;
  std::atomic<int> inside{0};
  std::atomic<int> overlaps{0};
  int total = 0;  // not atomic: the lock alone keeps it whole
  auto body = [&] {
    if (inside.fetch_add(1) != 0) ++overlaps;
    ++total;
    inside.fetch_sub(1);
  };
  auto feed = [&] {
    for (int i = 0; i < 20000; ++i) q.addCallback(fn(body), 1);
  };
  std::thread a(feed), b(feed);
  for (int i = 0; i < 20000; ++i) {  // a timer or service of the same node: takes mutex()
    std::lock_guard<std::mutex> lock(q.mutex());
    body();
  }
  a.join();
  b.join();
  EXPECT_EQ(overlaps.load(), 0);
  EXPECT_EQ(total, 60000);
}

TEST(InlineQueue, AfterCloseNothingRunsAndCloseWaitsForTheCallbackRunning) {
  drone_ros_common::InlineQueue q;
  std::promise<void> entered, release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> finished{false};
  std::thread receiver([&] {
    q.addCallback(fn([&] {
                    entered.set_value();
                    released.wait();
                    finished = true;
                  }),
                  1);
  });
  entered.get_future().wait();
  auto closing = std::async(std::launch::async, [&] { q.close(); });
  EXPECT_EQ(closing.wait_for(std::chrono::milliseconds(100)), std::future_status::timeout);
  release.set_value();
  closing.wait();
  EXPECT_TRUE(finished);  // the node's state outlived the callback that used it
  receiver.join();
  int late = 0;
  q.addCallback(fn([&] { ++late; }), 1);
  EXPECT_EQ(late, 0);
}

}  // namespace

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
