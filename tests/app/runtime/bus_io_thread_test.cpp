// BusIoThread against a fake bus that is slow or hangs: the caller never waits, stale commands
// never reach the bus, the heartbeat gap turns the status degraded then fault, and close() says
// whether the final neutral and disarm were acknowledged.
#include "app/runtime/bus_io_thread.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/monotonic_clock.hpp"

namespace rovctl::app {
namespace {

using namespace std::chrono_literals;

// Time the test sets; the I/O thread reads it too.
class ManualClock final : public hal::Clock {
 public:
  std::chrono::nanoseconds now() const override { return std::chrono::nanoseconds(ns_.load()); }
  void sleep_until(std::chrono::nanoseconds deadline) override { ns_ = deadline.count(); }
  void advance(std::chrono::nanoseconds d) { ns_ += d.count(); }

 private:
  std::atomic<std::int64_t> ns_{1'000'000'000};
};

// A bus that answers after `delay`, or, while held, not until released (or `hang_limit`, as a
// real bus's response timeout would end the wait).
class FakeBus final : public hal::ThrusterBus {
 public:
  bool open(std::string&) override { return true; }
  hal::BusStatus arm(bool armed) override {
    const bool answered = answer();
    std::lock_guard<std::mutex> lock(m_);
    arms_.push_back(armed);
    return answered ? hal::BusStatus::ok : hal::BusStatus::fault;
  }
  hal::BusStatus write(const hal::ThrusterCommand& c) override {
    {
      std::lock_guard<std::mutex> lock(m_);
      written_.push_back(c.thrust_fraction[0]);
    }
    return answer() ? hal::BusStatus::ok : hal::BusStatus::degraded;
  }
  hal::BusStatus read(hal::ThrusterTelemetry& t) override {
    t.count = 1;
    t.speed_rpm[0] = 42.0;
    t.valid = true;
    return hal::BusStatus::ok;
  }
  void close() override { closed_ = true; }
  std::string name() const override { return "fake bus"; }

  void hold() {
    std::lock_guard<std::mutex> lock(m_);
    held_ = true;
  }
  void release() {
    {
      std::lock_guard<std::mutex> lock(m_);
      held_ = false;
    }
    cv_.notify_all();
  }
  std::vector<double> written() {
    std::lock_guard<std::mutex> lock(m_);
    return written_;
  }
  std::vector<bool> arms() {
    std::lock_guard<std::mutex> lock(m_);
    return arms_;
  }
  std::chrono::milliseconds delay{0};
  std::chrono::milliseconds hang_limit{300};
  bool closed_ = false;

 private:
  // True when answered: after the delay, or once released before hang_limit.
  bool answer() {
    std::this_thread::sleep_for(delay);
    std::unique_lock<std::mutex> lock(m_);
    return cv_.wait_for(lock, hang_limit, [&] { return !held_; });
  }
  std::mutex m_;
  std::condition_variable cv_;
  bool held_ = false;
  std::vector<double> written_;
  std::vector<bool> arms_;
};

hal::ThrusterCommand thrust(double f) {
  hal::ThrusterCommand c;
  c.thrust_fraction[0] = f;
  c.count = 1;
  return c;
}

drivers::BusTimingParams timing() {
  drivers::BusTimingParams t;
  t.watchdog_ms = 200;
  t.degraded_ms = 100;
  t.command_deadline_ms = 50;
  t.close_timeout_ms = 150;
  return t;
}

template <class Pred>
bool eventually(Pred pred, std::chrono::milliseconds limit = 5s) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(1ms);
  }
  return pred();
}

TEST(BusIoThread, WritesNeverWaitForASlowBus) {
  FakeBus bus;
  bus.delay = 100ms;  // three times the tick
  drivers::MonotonicClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  ASSERT_EQ(io.arm(true), hal::BusStatus::ok);  // arming waits for the answer, once
  std::chrono::nanoseconds longest{0};
  for (int i = 0; i < 20; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    io.write(thrust(0.1 * (i % 5)));
    hal::ThrusterTelemetry t;
    io.read(t);
    longest = std::max<std::chrono::nanoseconds>(longest, std::chrono::steady_clock::now() - t0);
    std::this_thread::sleep_for(5ms);
  }
  // A blocking bus would take >= 100 ms here; the margin is for a preempted test thread (ASan,
  // ctest -j2 on two cores), not for the bus.
  EXPECT_LT(longest, 50ms);
  io.close();
  // Busy 100 ms per write while 20 came in 5 ms apart: most were superseded, none queued up.
  EXPECT_LT(io.stats().written, 10u);
  EXPECT_GT(io.stats().superseded, 5u);
}

TEST(BusIoThread, StaleCommandsAreDroppedNeverReplayed) {
  FakeBus bus;
  bus.hang_limit = 5s;
  ManualClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  bus.hold();  // the peer hangs inside the next write
  io.write(thrust(0.5));
  ASSERT_TRUE(eventually([&] { return bus.written().size() == 1; }));
  io.write(thrust(0.6));
  io.write(thrust(0.7));  // the newest, but it will be 60 ms old when the bus is free
  clock.advance(60ms);
  bus.release();
  // Let the thread finish the hung write and take 0.7 (the drop happens as it takes it) before
  // anything newer arrives; otherwise 0.7 would only be superseded.
  hal::ThrusterTelemetry t;
  ASSERT_TRUE(eventually([&] {
    io.read(t);
    return t.valid;
  }));
  std::this_thread::sleep_for(100ms);
  // A fresh command after the stale one goes out: the thread did not stop.
  ASSERT_TRUE(eventually([&] {
    io.write(thrust(0.2));
    return bus.written().size() >= 2;
  }));
  io.close();
  const std::vector<double> w = bus.written();
  EXPECT_EQ(w[0], 0.5);
  EXPECT_EQ(w[1], 0.2);  // never 0.6 or 0.7
  EXPECT_EQ(std::count(w.begin(), w.end(), 0.6), 0);
  EXPECT_EQ(std::count(w.begin(), w.end(), 0.7), 0);
  EXPECT_EQ(io.stats().dropped_stale, 1u);
}

TEST(BusIoThread, HeartbeatGapTurnsStatusDegradedThenFault) {
  FakeBus bus;
  bus.hang_limit = 5s;
  ManualClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  io.write(thrust(0.1));
  hal::ThrusterTelemetry t;
  // The telemetry is read after the write was answered: the bus is idle again.
  ASSERT_TRUE(eventually([&] {
    io.read(t);
    return t.valid;
  }));
  EXPECT_EQ(io.heartbeat_age(), 0ns);  // answered at this (manual) instant
  bus.hold();
  clock.advance(10ms);
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::ok);                // the peer hangs on this one
  ASSERT_TRUE(eventually([&] { return bus.written().size() == 2; }));  // inside the bus call
  clock.advance(95ms);  // 105 ms since the last answer
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::degraded);
  clock.advance(100ms);  // 205 ms: the controller's watchdog has stopped the thrusters
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::fault);
  EXPECT_EQ(io.read(t), hal::BusStatus::fault);
  ASSERT_NE(io.fault_reason(), nullptr);
  EXPECT_EQ(std::string(io.fault_reason()).rfind("bus not answering: a request waiting ", 0), 0u)
      << io.fault_reason();
  EXPECT_NE(
      std::string(io.fault_reason()).find("no acknowledgement for 205 ms (limits 100 / 200 ms)"),
      std::string::npos)
      << io.fault_reason();
  bus.release();
  io.close();
}

// The tick held off the CPU (this machine's stall, not the bus's): within the watchdog the
// controller never saw a gap, so the status stays ok; past it the reason says whose stall it was.
TEST(BusIoThread, AStallOfTheTickIsToldApartFromTheBus) {
  FakeBus bus;
  ManualClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  io.write(thrust(0.1));
  ASSERT_TRUE(eventually([&] { return io.heartbeat_age() == 0ns && bus.written().size() == 1; }));
  clock.advance(150ms);  // no tick for 150 ms: over degraded_ms, under watchdog_ms
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::ok);
  ASSERT_TRUE(eventually([&] { return io.heartbeat_age() == 0ns && bus.written().size() == 2; }));
  clock.advance(250ms);  // past watchdog_ms: the controller's watchdog has stopped the thrusters
  bus.hold();            // (so that this write's own answer cannot race the status)
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::fault);
  ASSERT_NE(io.fault_reason(), nullptr);
  EXPECT_STREQ(io.fault_reason(),
               "tick late 250 ms (a stall of this machine): no command acknowledged for 250 ms, "
               "past watchdog_ms 200");
  bus.release();
  ASSERT_TRUE(eventually([&] { return io.heartbeat_age() == 0ns && bus.written().size() == 3; }));
  EXPECT_EQ(io.write(thrust(0.1)), hal::BusStatus::ok);  // caught up at the next tick
  io.close();
}

TEST(BusIoThread, CloseReportsTheFinalDisarmAcknowledged) {
  FakeBus bus;
  drivers::MonotonicClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  ASSERT_EQ(io.arm(true), hal::BusStatus::ok);
  io.write(thrust(0.4));
  io.close();
  EXPECT_TRUE(io.safe_acknowledged());
  ASSERT_FALSE(bus.arms().empty());
  EXPECT_FALSE(bus.arms().back());  // the last thing the bus heard: disarm
  EXPECT_TRUE(bus.closed_);
  EXPECT_EQ(io.write(thrust(0.4)), hal::BusStatus::fault);  // closed
}

TEST(BusIoThread, CloseWithAHungPeerIsBoundedAndNotAcknowledged) {
  FakeBus bus;
  bus.hang_limit = 300ms;  // the bus's own response timeout
  drivers::MonotonicClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  ASSERT_EQ(io.arm(true), hal::BusStatus::ok);
  bus.hold();
  io.write(thrust(0.4));
  const auto t0 = std::chrono::steady_clock::now();
  io.close();
  const auto took = std::chrono::steady_clock::now() - t0;
  EXPECT_FALSE(io.safe_acknowledged());
  // close_timeout_ms, then the thread's transaction in flight and the disarm it still owes.
  EXPECT_LT(took, 1500ms);
  EXPECT_TRUE(bus.closed_);
  EXPECT_FALSE(bus.arms().back());  // the disarm was still attempted
}

TEST(BusIoThread, TelemetryComesBackFromTheIoThread) {
  FakeBus bus;
  drivers::MonotonicClock clock;
  BusIoThread io(bus, clock, timing());
  std::string error;
  ASSERT_TRUE(io.open(error));
  hal::ThrusterTelemetry t;
  io.read(t);
  EXPECT_FALSE(t.valid);  // nothing read yet
  io.write(thrust(0.1));
  ASSERT_TRUE(eventually([&] {
    io.read(t);
    return t.valid;
  }));
  EXPECT_EQ(t.speed_rpm[0], 42.0);
  io.close();
}

}  // namespace
}  // namespace rovctl::app
