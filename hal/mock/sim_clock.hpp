// SimClock: the application's clock in simulation. Sleeping until a deadline steps the simulated
// world to it — at once in virtual time, and in real time (hardware in the loop) also really
// sleeping until then, so the scheduler's code is the same as on the vehicle.
#pragma once

#include <chrono>
#include <ctime>

#include "hal/interfaces/clock.hpp"
#include "hal/mock/simulated_world.hpp"

namespace rovctl::hal::mock {

class SimClock final : public Clock {
 public:
  enum class Mode { virtual_time, realtime };

  // In real time, time 0 is the construction instant on CLOCK_MONOTONIC; the world is expected
  // to be at (or reset to) time 0 then.
  SimClock(SimulatedWorld& world, Mode mode);

  std::chrono::nanoseconds now() const override;
  // The world steps to `deadline`; in real time, clock_nanosleep(TIMER_ABSTIME) on
  // CLOCK_MONOTONIC then waits for it, so the world's compute is not part of the wake-up.
  void sleep_until(std::chrono::nanoseconds deadline) override;
  // Simulated computing time (virtual mode): the world moves on by `dt` while the application
  // "works". In real time the work takes real time and this does nothing.
  void advance(std::chrono::nanoseconds dt);

  Mode mode() const { return mode_; }

 private:
  SimulatedWorld& world_;
  Mode mode_;
  std::chrono::nanoseconds epoch_{0};  // CLOCK_MONOTONIC at construction (real time)
};

}  // namespace rovctl::hal::mock
