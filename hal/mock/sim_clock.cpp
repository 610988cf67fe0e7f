// Virtual and real-time pacing of the simulated world.
#include "hal/mock/sim_clock.hpp"

#include <time.h>
#include <cerrno>

namespace rovctl::hal::mock {

namespace {

std::chrono::nanoseconds monotonic_now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
}

}  // namespace

SimClock::SimClock(SimulatedWorld& world, Mode mode) : world_(world), mode_(mode) {
  if (mode_ == Mode::realtime) epoch_ = monotonic_now() - world_.time();
}

std::chrono::nanoseconds SimClock::now() const {
  return mode_ == Mode::virtual_time ? world_.time() : monotonic_now() - epoch_;
}

void SimClock::sleep_until(std::chrono::nanoseconds deadline) {
  // The world only integrates the commands of the last tick, which stand until the next one, so
  // it can be stepped to the deadline before the sleep: in real time its compute then does not
  // delay the wake-up (it would show as tick jitter the vehicle does not have).
  world_.step_to(deadline);
  if (mode_ == Mode::realtime) {
    const std::chrono::nanoseconds wake = epoch_ + deadline;
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(wake.count() / 1'000'000'000);
    ts.tv_nsec = static_cast<long>(wake.count() % 1'000'000'000);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
}

void SimClock::advance(std::chrono::nanoseconds dt) {
  if (mode_ == Mode::virtual_time) world_.step_to(world_.time() + dt);
}

}  // namespace rovctl::hal::mock
