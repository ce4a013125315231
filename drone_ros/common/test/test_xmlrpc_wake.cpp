// drone_ros_common::XmlRpcWake on a dispatcher like roscpp's XML-RPC thread runs: a long work()
// slice ends at the wake's tick, ticks keep ending slices, the dispatcher's shutdown closes it
// once, and a period that would not shorten a slice is refused.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "drone_ros_common/xmlrpc_wake.h"

namespace {

using drone_ros_common::XmlRpcWake;

double work_s(XmlRpc::XmlRpcDispatch *disp, double slice_s) {
  const auto t0 = std::chrono::steady_clock::now();
  disp->work(slice_s);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The slice roscpp asks for is 0.1 s; one of a minute shows the end is the wake's, not the slice's.
TEST(XmlRpcWake, AMinuteLongSliceEndsAtTheFirstTick) {
  XmlRpcWake wake(0.01);
  XmlRpc::XmlRpcDispatch disp;
  wake.addToDispatch(&disp);
  EXPECT_LT(work_s(&disp, 60.0), 30.0);
  wake.removeFromDispatch(&disp);
}

// Each tick read leaves the timer armed: the next slice ends too, and so does the tenth.
TEST(XmlRpcWake, EverySliceEndsWhileItIsInTheDispatcher) {
  XmlRpcWake wake(0.01);
  XmlRpc::XmlRpcDispatch disp;
  wake.addToDispatch(&disp);
  for (int i = 0; i < 10; ++i) EXPECT_LT(work_s(&disp, 60.0), 30.0) << "slice " << i;
  wake.removeFromDispatch(&disp);
}

// XMLRPCManager's shutdown clears the dispatcher, which closes every source; the wake's own
// destructor runs later and must not close that descriptor number again (another file may have it).
TEST(XmlRpcWake, TheDispatchersShutdownClosesItOnce) {
  XmlRpcWake wake(0.01);
  XmlRpc::XmlRpcDispatch disp;
  wake.addToDispatch(&disp);
  ASSERT_GE(wake.getfd(), 0);
  disp.clear();
  EXPECT_EQ(wake.getfd(), -1);
  EXPECT_TRUE(disp._sources.empty());
}

TEST(XmlRpcWake, NeverAskedToBeRemoved) {
  XmlRpcWake wake(0.01);
  EXPECT_FALSE(wake.check());
}

// install() is the only way the nodes make one: it refuses before touching roscpp.
TEST(XmlRpcWake, APeriodThatWouldNotShortenASliceIsRefused) {
  EXPECT_THROW(XmlRpcWake::install(0.0), std::runtime_error);
  EXPECT_THROW(XmlRpcWake::install(-0.01), std::runtime_error);
  EXPECT_THROW(XmlRpcWake::install(0.1), std::runtime_error);
  EXPECT_THROW(XmlRpcWake::install(std::numeric_limits<double>::quiet_NaN()), std::runtime_error);
}

}  // namespace

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
