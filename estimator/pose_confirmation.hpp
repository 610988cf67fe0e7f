// The loop's second look at an ok estimate: confirmed only when the frame before had a sound
// pose it agrees with, within both error bounds and as far as the vehicle can move in between.
#pragma once

#include <chrono>

#include <Eigen/Geometry>

#include "estimator/estimator_params.hpp"
#include "estimator/pose_estimator.hpp"

namespace rovctl::estimator {

// A single frame's fit can be sure and wrong (a rim fitted to a fading sphere, 10-14 deg off with
// a 1.4 deg bound), but not two frames in a row the same way: like an EKF's innovation gate, a
// pose that moved further than the bounds and the vehicle allow is not trusted, and neither is
// one with nothing to be checked against. Holds one pose; allocates nothing.
class PoseConfirmation {
 public:
  explicit PoseConfirmation(const ConfirmationParams& params) : params_(params) {}

  // Judges `estimate` (taken at `capture`): an ok one the last sound pose does not confirm
  // becomes not ok, `unconfirmed`. Then remembers it if it was ok by its own frame's tests (even
  // if unconfirmed: the next frame tells which of the two was wrong), and forgets the last
  // otherwise.
  void judge(PoseEstimate& estimate, std::chrono::nanoseconds capture);

  // Whether b, `dt` after a, is where a rigid marker seen by a vehicle within the rate and speed
  // limits can be, each pose off by at most its error bound.
  bool agree(const Eigen::Isometry3d& T_a, double bound_a_m, double bound_a_deg,
             const Eigen::Isometry3d& T_b, double bound_b_m, double bound_b_deg,
             std::chrono::nanoseconds dt) const;

 private:
  ConfirmationParams params_;
  bool have_last_ = false;
  Eigen::Isometry3d T_last_ = Eigen::Isometry3d::Identity();
  double bound_last_m_ = 0.0;
  double bound_last_deg_ = 0.0;
  std::chrono::nanoseconds last_capture_{0};
};

}  // namespace rovctl::estimator
