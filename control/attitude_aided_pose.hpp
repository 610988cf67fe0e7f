// A partial view's marker pose, its rotation carried by the attitude sensor from the last full
// view: the station does not turn, so the marker's attitude in the world is known once seen whole.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <chrono>

namespace rovctl::control {

// Two spheres leave the marker free to turn about the line through them, and the estimator's
// pose on them was 5-40 deg off in yaw while the spheres themselves sat within millimetres. With
// the rotation from the attitude sensor, the seen spheres fix the translation.
class AttitudeAidedPose {
 public:
  static constexpr int kMaxPoints = 3;

  // max_age: how long a full view's world attitude of the marker is trusted (the attitude
  // sensor's heading drifts).
  AttitudeAidedPose(const Eigen::Isometry3d& T_body_cl, std::chrono::nanoseconds max_age);

  // A full view (every sphere in both views) at the vehicle attitude q_world_body.
  void remember(std::chrono::nanoseconds now, const Eigen::Quaterniond& q_world_body,
                const Eigen::Isometry3d& T_cl_marker);
  void forget() { have_ = false; }

  // The partial view's pose with the remembered rotation; the translation puts the marker points
  // `points_marker_m[i]` (those seen, n of them, 1..kMaxPoints) where T_cl_marker_partial put
  // them. False when nothing is remembered, the memory is older than max_age, or n is 0.
  bool aid(std::chrono::nanoseconds now, const Eigen::Quaterniond& q_world_body,
           const Eigen::Isometry3d& T_cl_marker_partial, const Eigen::Vector3d* points_marker_m,
           int n, Eigen::Isometry3d& T_cl_marker_aided) const;

 private:
  Eigen::Matrix3d R_body_cl_;
  std::chrono::nanoseconds max_age_;
  bool have_ = false;
  std::chrono::nanoseconds remembered_at_{0};
  Eigen::Matrix3d R_world_marker_ = Eigen::Matrix3d::Identity();
};

}  // namespace rovctl::control
