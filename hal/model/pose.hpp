// Pose helpers. Poses are Eigen::Isometry3d named T_a_b: the pose of frame b in frame a.
#pragma once

#include <Eigen/Geometry>

namespace rovctl::hal {

using Pose = Eigen::Isometry3d;

inline constexpr double kRadPerDeg = M_PI / 180.0;

inline Pose make_pose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Pose T = Pose::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

// Rotation angle between two orientations, in [0, pi].
inline double rotation_angle_rad(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb) {
  return Eigen::AngleAxisd(Ra.transpose() * Rb).angle();
}

// T moved by a small step: the rotation vector d(0..2) applied on the left (in T's parent frame),
// d(3..5) added to the translation. The refiners' parametrisation of a pose increment.
inline Pose perturbed(const Pose& T, const Eigen::Matrix<double, 6, 1>& d) {
  Pose out = T;
  const double angle = d.head<3>().norm();
  if (angle > 0.0) {
    out.linear() = Eigen::AngleAxisd(angle, d.head<3>() / angle).toRotationMatrix() * T.linear();
  }
  out.translation() += d.tail<3>();
  return out;
}

}  // namespace rovctl::hal
