// Clock: monotonic time and absolute-deadline sleeping, real (clock_nanosleep) or virtual.
#pragma once

#include <chrono>

namespace rovctl::hal {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::chrono::nanoseconds now() const = 0;
  // Sleeps until `deadline` (absolute, on this clock). A virtual clock jumps there.
  virtual void sleep_until(std::chrono::nanoseconds deadline) = 0;
};

}  // namespace rovctl::hal
