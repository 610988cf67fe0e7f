// VirtualClock: simulated time that advances only when slept on, so a simulation runs as fast
// as the machine allows while the scheduler's code stays the same as on the vehicle.
#pragma once

#include <atomic>

#include "hal/interfaces/clock.hpp"

namespace rovctl::hal::mock {

class VirtualClock final : public Clock {
 public:
  std::chrono::nanoseconds now() const override { return std::chrono::nanoseconds(now_ns_.load()); }
  void sleep_until(std::chrono::nanoseconds deadline) override {
    if (deadline.count() > now_ns_.load()) now_ns_.store(deadline.count());
  }
  // Simulated work: time spent computing (e.g. the estimator's measured CPU time).
  void advance(std::chrono::nanoseconds dt) { now_ns_.fetch_add(dt.count()); }

 private:
  std::atomic<long long> now_ns_{0};
};

}  // namespace rovctl::hal::mock
