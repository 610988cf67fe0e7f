// The ArduSub bus behind the bus I/O thread, as `rovctl run` flies it: arming waits on the I/O
// thread for ArduSub's ACK, a lost HEARTBEAT reaches the tick's write() as a fault (the failsafe's
// bus_fault), and close() sends the final neutral + disarm through the thread, acknowledged.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "app/runtime/bus_io_thread.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "drivers/mavlink/fake_ardusub.hpp"
#include "drivers/monotonic_clock.hpp"

namespace rovctl::app {
namespace {

using namespace std::chrono_literals;
using drivers::testing::FakeArduSub;

TEST(BusIoThreadArdusub, LostHeartbeatIsAFaultAtTheTickAndCloseDisarms) {
  FakeArduSub peer;
  drivers::ArdusubParams p;
  p.link = "udpout:127.0.0.1:" + std::to_string(peer.port());
  p.link_timeout_ms = 300;
  p.ack_timeout_ms = 1000;  // generous under load; the fake answers at once
  drivers::ArdusubThrusterBus bus(p, hal::ThrusterLayout::bluerov2_heavy());
  drivers::MonotonicClock clock;
  drivers::BusTimingParams timing;
  timing.close_timeout_ms = 3000;
  timing.watchdog_ms = 2000;
  timing.degraded_ms = 1000;
  BusIoThread io(bus, clock, timing);
  std::string error;
  ASSERT_TRUE(io.open(error)) << error;
  ASSERT_EQ(io.arm(true), hal::BusStatus::ok);
  EXPECT_TRUE(peer.armed);
  hal::ThrusterCommand c;
  c.count = 8;
  EXPECT_NE(io.write(c), hal::BusStatus::fault);

  peer.beating = false;
  hal::BusStatus s = io.write(c);
  const auto end = std::chrono::steady_clock::now() + 5s;
  while (s != hal::BusStatus::fault && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(10ms);
    s = io.write(c);
  }
  EXPECT_EQ(s, hal::BusStatus::fault);
  EXPECT_EQ(bus.fault(), drivers::ArdusubFault::link_lost);

  io.close();
  EXPECT_TRUE(io.safe_acknowledged());  // the fake still answers the disarm
  EXPECT_FALSE(peer.armed);
}

}  // namespace
}  // namespace rovctl::app
