// Filtered derivative: the difference quotient of successive samples through a first-order
// low-pass, so the D term sees a rate, not the raw jitter of noisy pose estimates.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace rovctl::control {

class RateFilter {
 public:
  using Vector = Eigen::Matrix<double, 6, 1>;

  explicit RateFilter(double cutoff_hz);
  // max_abs_rate: each axis's difference quotient is clamped to +-this before the low-pass, so
  // one outlier sample (a pose estimate off by decimetres) cannot pass as a rate the vehicle
  // could never have; infinity = no limit. Throws std::invalid_argument if not positive.
  RateFilter(double cutoff_hz, const Vector& max_abs_rate);

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
  Vector max_abs_rate_ = Vector::Constant(std::numeric_limits<double>::infinity());
  bool primed_ = false;
  Vector previous_ = Vector::Zero();
  Vector rate_ = Vector::Zero();
};

}  // namespace rovctl::control
