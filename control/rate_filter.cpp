// First-order low-pass on the differentiated signal (backward-Euler discretisation, so any
// sampling period is stable).
#include "control/rate_filter.hpp"

#include <cmath>
#include <stdexcept>

namespace rovctl::control {

RateFilter::RateFilter(double cutoff_hz) {
  if (!(cutoff_hz > 0.0) || !std::isfinite(cutoff_hz)) {
    throw std::invalid_argument("rate filter: cut-off must be a positive frequency");
  }
  tau_s_ = 1.0 / (2.0 * M_PI * cutoff_hz);
}

RateFilter::RateFilter(double cutoff_hz, const Vector& max_abs_rate) : RateFilter(cutoff_hz) {
  if (!(max_abs_rate.array() > 0.0).all()) {
    throw std::invalid_argument("rate filter: rate limits must be positive");
  }
  max_abs_rate_ = max_abs_rate;
}

const RateFilter::Vector& RateFilter::update(const Vector& value, double dt_s) {
  if (!primed_) {
    previous_ = value;
    rate_.setZero();
    primed_ = true;
    return rate_;
  }
  if (!(dt_s > 0.0)) return rate_;
  const double alpha = dt_s / (tau_s_ + dt_s);
  const Vector raw = ((value - previous_) / dt_s).cwiseMax(-max_abs_rate_).cwiseMin(max_abs_rate_);
  rate_ += alpha * (raw - rate_);
  previous_ = value;
  return rate_;
}

void RateFilter::reset() {
  primed_ = false;
  previous_.setZero();
  rate_.setZero();
}

}  // namespace rovctl::control
