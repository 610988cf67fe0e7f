// The attitude carried by the body rates and pulled toward the sensor's (see attitude_filter.hpp).
#include "control/attitude_filter.hpp"

#include <cmath>

#include "hal/primitives/duration_seconds.hpp"

namespace rovctl::control {
namespace {

// The rotation a body turning at omega makes in dt_s, as a quaternion.
Eigen::Quaterniond turn(const Eigen::Vector3d& omega_radps, double dt_s) {
  const Eigen::Vector3d r = omega_radps * dt_s;
  const double angle = r.norm();
  if (!(angle > 0.0)) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle));
}

}  // namespace

AttitudeFilter::AttitudeFilter(double correction_s, std::chrono::nanoseconds max_gap)
    : correction_s_(correction_s), max_gap_(max_gap) {}

bool AttitudeFilter::update(std::chrono::nanoseconds now, bool valid,
                            const Eigen::Quaterniond& q_world_body,
                            const Eigen::Vector3d& omega_body_radps) {
  if (!valid || !q_world_body.coeffs().allFinite() || q_world_body.norm() < 0.5) {
    have_ = false;
    return false;
  }
  const Eigen::Quaterniond measured = q_world_body.normalized();
  const bool rates = omega_body_radps.allFinite();
  const std::chrono::nanoseconds gap = now - at_;
  if (!have_ || gap.count() < 0 || gap > max_gap_ || correction_s_ <= 0.0) {
    q_ = measured;
  } else {
    const double dt_s = hal::seconds(gap);
    // The body rates are the mean of the last and this read's (trapezoid): both body frame.
    const Eigen::Vector3d omega = rates ? 0.5 * (omega_radps_ + omega_body_radps) : omega_radps_;
    q_ = (q_ * turn(omega, dt_s)).normalized();
    const double share = 1.0 - std::exp(-dt_s / correction_s_);
    q_ = q_.slerp(share, measured).normalized();
  }
  omega_radps_ = rates ? omega_body_radps : Eigen::Vector3d::Zero();
  at_ = now;
  have_ = true;
  return true;
}

Eigen::Quaterniond AttitudeFilter::q_world_body_at(std::chrono::nanoseconds at) const {
  return (q_ * turn(omega_radps_, hal::seconds(at - at_))).normalized();
}

}  // namespace rovctl::control
