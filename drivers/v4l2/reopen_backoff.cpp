// Exponential reopen back-off.
#include "drivers/v4l2/reopen_backoff.hpp"

#include <algorithm>

namespace rovctl::drivers {

ReopenBackoff::ReopenBackoff(std::chrono::nanoseconds initial, std::chrono::nanoseconds max)
    : initial_(initial), max_(std::max(initial, max)) {}

void ReopenBackoff::failed(std::chrono::nanoseconds now) {
  wait_ = wait_.count() == 0 ? initial_ : std::min(wait_ * 2, max_);
  next_attempt_ = now + wait_;
}

void ReopenBackoff::succeeded() {
  wait_ = std::chrono::nanoseconds(0);
  next_attempt_ = std::chrono::nanoseconds(0);
}

}  // namespace rovctl::drivers
