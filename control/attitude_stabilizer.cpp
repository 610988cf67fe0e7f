// PD on roll and pitch with the gyro's rates as the derivative (no differentiation of noise).
#include "control/attitude_stabilizer.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rovctl::control {

Eigen::Vector2d AttitudeStabilizer::roll_pitch(const Eigen::Quaterniond& q_world_body) {
  const Eigen::Matrix3d R = q_world_body.normalized().toRotationMatrix();
  return {std::atan2(R(2, 1), R(2, 2)), -std::asin(std::clamp(R(2, 0), -1.0, 1.0))};
}

bool AttitudeStabilizer::update(const hal::SensorReadings& r, Eigen::Vector2d& moment_nm) const {
  moment_nm.setZero();
  if (!p_.enabled || !r.attitude_valid || !r.q_world_body.coeffs().allFinite() ||
      !r.omega_body_radps.allFinite() || r.q_world_body.norm() < 1e-6) {
    return false;
  }
  const Eigen::Vector2d angle = roll_pitch(r.q_world_body);
  const double m = p_.max_moment_nm;
  moment_nm.x() = std::clamp(
      -p_.roll_kp_nm_per_rad * angle.x() - p_.roll_kd_nms_per_rad * r.omega_body_radps.x(), -m, m);
  moment_nm.y() = std::clamp(
      -p_.pitch_kp_nm_per_rad * angle.y() - p_.pitch_kd_nms_per_rad * r.omega_body_radps.y(), -m,
      m);
  return true;
}

}  // namespace rovctl::control
