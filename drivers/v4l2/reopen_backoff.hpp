// When to try reopening a lost camera: exponential back-off between attempts, reset on success,
// so an unplugged camera is retried quickly at first without hammering the USB bus.
#pragma once

#include <chrono>

namespace rovctl::drivers {

class ReopenBackoff {
 public:
  // First retry `initial` after the loss, each failure doubles the wait up to `max`.
  ReopenBackoff(std::chrono::nanoseconds initial, std::chrono::nanoseconds max);

  // The device was lost (or a reopen failed) at `now`.
  void failed(std::chrono::nanoseconds now);
  // A reopen succeeded: the next loss starts again from `initial`.
  void succeeded();
  bool due(std::chrono::nanoseconds now) const { return now >= next_attempt_; }
  std::chrono::nanoseconds next_attempt() const { return next_attempt_; }
  std::chrono::nanoseconds current_wait() const { return wait_; }

 private:
  std::chrono::nanoseconds initial_;
  std::chrono::nanoseconds max_;
  std::chrono::nanoseconds wait_{0};  // 0: no failure since the last success
  std::chrono::nanoseconds next_attempt_{0};
};

}  // namespace rovctl::drivers
