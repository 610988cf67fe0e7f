// Filtered derivative: the difference quotient of successive samples through a first-order
// low-pass, so the D term sees a rate, not the raw jitter of noisy pose estimates.
#pragma once

#include <Eigen/Core>

namespace rovctl::control {

class RateFilter {
 public:
  using Vector = Eigen::Matrix<double, 6, 1>;

  explicit RateFilter(double cutoff_hz);

  // The filtered d(value)/dt after this sample, `dt_s` after the previous one. The first sample
  // (after construction or reset) only primes the filter: the rate stays zero. A non-positive dt
  // leaves the state untouched. No allocation.
  const Vector& update(const Vector& value, double dt_s);
  void reset();

  const Vector& rate() const { return rate_; }
  bool primed() const { return primed_; }
  double time_constant_s() const { return tau_s_; }

 private:
  double tau_s_;
  bool primed_ = false;
  Vector previous_ = Vector::Zero();
  Vector rate_ = Vector::Zero();
};

}  // namespace rovctl::control
