// MonotonicClock: CLOCK_MONOTONIC with absolute-deadline sleeps (clock_nanosleep TIMER_ABSTIME),
// so a late wake-up never shifts the following deadlines.
#pragma once

#include "hal/interfaces/clock.hpp"

namespace rovctl::drivers {

class MonotonicClock final : public hal::Clock {
 public:
  std::chrono::nanoseconds now() const override;
  void sleep_until(std::chrono::nanoseconds deadline) override;
};

}  // namespace rovctl::drivers
