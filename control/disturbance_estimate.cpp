// Integration, limits, settling and the beyond-hold judgement of the current's estimate.
#include "control/disturbance_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rovctl::control {

DisturbanceEstimate::DisturbanceEstimate(const Vector6d& ki, const Vector6d& limit,
                                         const DisturbanceParams& params)
    : p_(params), ki_(ki), configured_limit_(limit), limit_(limit) {}

void DisturbanceEstimate::set_capacity(const Vector6d& capacity) {
  for (int i = 0; i < 6; ++i) {
    limit_[i] = std::min(configured_limit_[i], p_.hold_fraction * std::max(capacity[i], 0.0));
    wrench_[i] = std::clamp(wrench_[i], -limit_[i], limit_[i]);
  }
}

void DisturbanceEstimate::reset() {
  wrench_.setZero();
  held_.setConstant(false);
  rate_stage_nps_.setZero();
  rate_body_nps_.setZero();
  rate_nps_ = 0.0;
  settled_for_s_ = 0.0;
  at_limit_for_s_ = 0.0;
  hold_ratio_ = 0.0;
  rising_ = false;
}

void DisturbanceEstimate::set_axis(int axis, double value) {
  if (ki_[axis] <= 0.0) return;
  wrench_[axis] = std::clamp(value, -limit_[axis], limit_[axis]);
}

void DisturbanceEstimate::turn(const Eigen::Matrix3d& R_body_prevbody) {
  Vector6d turned = wrench_;
  turned.head<3>() = R_body_prevbody * wrench_.head<3>();
  turned.tail<3>() = R_body_prevbody * wrench_.tail<3>();
  for (int i = 0; i < 6; ++i) {
    if (!held_[i]) wrench_[i] = ki_[i] > 0.0 ? std::clamp(turned[i], -limit_[i], limit_[i]) : 0.0;
  }
}

void DisturbanceEstimate::integrate(const Vector6d& error, double dt_s, bool saturated) {
  if (!(dt_s > 0.0)) return;
  const Eigen::Vector2d before = wrench_.head<2>();
  for (int i = 0; i < 6; ++i) {
    if (ki_[i] <= 0.0 || held_[i]) continue;
    const double next = wrench_[i] + ki_[i] * error[i] * dt_s;
    // Conditional integration while the thrusters saturate, then the clamp.
    if (saturated && std::abs(next) > std::abs(wrench_[i])) continue;
    wrench_[i] = std::clamp(next, -limit_[i], limit_[i]);
  }

  // Settling is judged on the integration alone, low-passed as a vector: a turn of the body (and
  // the estimate's heading noise, a few mrad a frame) moves the body-frame push without the
  // current changing, and the norm of a noisy difference would never fall to zero.
  // Two poles: the integrand's rate term puts the estimator's frame-to-frame noise straight into
  // the estimate (kd / kp of it, about 0.2 N under noise with block compression), and that
  // jitter's derivative through one pole stays above any useful settle rate.
  const Eigen::Vector2d rate = (wrench_.head<2>() - before) / dt_s;
  const double alpha = 1.0 - std::exp(-2.0 * M_PI * p_.rate_cutoff_hz * dt_s);
  rate_stage_nps_ += alpha * (rate - rate_stage_nps_);
  rate_body_nps_ += alpha * (rate_stage_nps_ - rate_body_nps_);
  rate_nps_ = rate_body_nps_.norm();

  // Against the limit along the force's own direction: the box of per-axis limits, scaled.
  double ratio = 0.0;
  for (int i = 0; i < 2; ++i) {
    if (ki_[i] > 0.0 && limit_[i] > 0.0) ratio = std::max(ratio, std::abs(wrench_[i]) / limit_[i]);
  }
  hold_ratio_ = ratio;
  const bool at_limit = ratio >= 0.98;
  at_limit_for_s_ = (at_limit || saturated) ? at_limit_for_s_ + dt_s : 0.0;

  // An estimate stopped by its limit or by the thrusters' saturation changes no more, but it has
  // not found the push: it is not settled, and it stays rising until it settles.
  const bool slow = rate_nps_ < p_.settle_rate_nps && at_limit_for_s_ == 0.0;
  settled_for_s_ = slow ? settled_for_s_ + dt_s : 0.0;
  const double force_n = wrench_.head<2>().norm();
  const bool growing =
      force_n > 0.0 && rate_body_nps_.dot(wrench_.head<2>()) / force_n > p_.settle_rate_nps;
  if (growing || at_limit_for_s_ > 0.0) rising_ = true;
  if (settled()) rising_ = false;
}

}  // namespace rovctl::control
