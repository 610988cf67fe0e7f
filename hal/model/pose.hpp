// Pose helpers. Poses are Eigen::Isometry3d named T_a_b: the pose of frame b in frame a.
#pragma once

#include <Eigen/Geometry>

namespace rovctl::hal {

using Pose = Eigen::Isometry3d;

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

}  // namespace rovctl::hal
