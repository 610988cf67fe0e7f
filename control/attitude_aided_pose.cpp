// The partial view's pose aided by the attitude sensor. No allocation.
#include "control/attitude_aided_pose.hpp"

namespace rovctl::control {

AttitudeAidedPose::AttitudeAidedPose(const Eigen::Isometry3d& T_body_cl,
                                     std::chrono::nanoseconds max_age)
    : R_body_cl_(T_body_cl.linear()), max_age_(max_age) {}

void AttitudeAidedPose::remember(std::chrono::nanoseconds now,
                                 const Eigen::Quaterniond& q_world_body,
                                 const Eigen::Isometry3d& T_cl_marker) {
  R_world_marker_ =
      q_world_body.normalized().toRotationMatrix() * R_body_cl_ * T_cl_marker.linear();
  remembered_at_ = now;
  have_ = true;
}

bool AttitudeAidedPose::aid(std::chrono::nanoseconds now, const Eigen::Quaterniond& q_world_body,
                            const Eigen::Isometry3d& T_cl_marker_partial,
                            const Eigen::Vector3d* points_marker_m, int n,
                            Eigen::Isometry3d& T_cl_marker_aided) const {
  if (!have_ || n <= 0 || n > kMaxPoints || now - remembered_at_ > max_age_ ||
      now < remembered_at_) {
    return false;
  }
  const Eigen::Matrix3d R_cl_marker = R_body_cl_.transpose() *
                                      q_world_body.normalized().toRotationMatrix().transpose() *
                                      R_world_marker_;
  // With the rotation fixed, the least-squares translation is the mean of the points' offsets.
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    t += T_cl_marker_partial * points_marker_m[i] - R_cl_marker * points_marker_m[i];
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_cl_marker;
  T.translation() = t / static_cast<double>(n);
  if (!T.matrix().allFinite()) return false;
  T_cl_marker_aided = T;
  return true;
}

}  // namespace rovctl::control
