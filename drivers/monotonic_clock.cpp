// CLOCK_MONOTONIC clock; sleeps retry on EINTR with the same absolute deadline.
#include "drivers/monotonic_clock.hpp"

#include <cerrno>
#include <ctime>

namespace rovctl::drivers {

std::chrono::nanoseconds MonotonicClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
}

void MonotonicClock::sleep_until(std::chrono::nanoseconds deadline) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline.count() / 1000000000LL);
  ts.tv_nsec = static_cast<long>(deadline.count() % 1000000000LL);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace rovctl::drivers
