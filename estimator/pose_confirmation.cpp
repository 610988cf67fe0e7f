// Confirming an ok estimate by the frame before it (see pose_confirmation.hpp).
#include "estimator/pose_confirmation.hpp"

#include <cmath>

namespace rovctl::estimator {

bool PoseConfirmation::agree(const Eigen::Isometry3d& T_a, double bound_a_m, double bound_a_deg,
                             const Eigen::Isometry3d& T_b, double bound_b_m, double bound_b_deg,
                             std::chrono::nanoseconds dt) const {
  const double dt_s = std::abs(std::chrono::duration<double>(dt).count());
  const double rate_radps = params_.rate_dps * M_PI / 180.0;
  const Eigen::AngleAxisd turn(T_b.linear() * T_a.linear().transpose());
  const double turned_deg = std::abs(turn.angle()) * 180.0 / M_PI;
  // Two independent errors, each within its 99 % bound, differ by at most about the root of the
  // bounds' squares (a sum would let through a 5 deg error beside two 2 deg bounds). The marker's
  // origin moves with the vehicle's speed and, seen from a turning camera, with the turn rate
  // times its range.
  const double moved_m = (T_b.translation() - T_a.translation()).norm();
  const double reach_m = (params_.speed_mps + rate_radps * T_a.translation().norm()) * dt_s +
                         std::hypot(bound_a_m, bound_b_m);
  const double reach_deg = params_.rate_dps * dt_s + std::hypot(bound_a_deg, bound_b_deg);
  return moved_m <= reach_m && turned_deg <= reach_deg;
}

void PoseConfirmation::judge(PoseEstimate& estimate, std::chrono::nanoseconds capture) {
  if (params_.rate_dps <= 0.0) return;
  // Only a pose that passed the frame's own tests (ok before this one) is a reference: a loose
  // bound would confirm anything.
  const bool sound = estimate.ok;
  if (estimate.ok) {
    const auto gap = std::chrono::duration<double, std::milli>(capture - last_capture_).count();
    const bool confirmed =
        have_last_ && gap > 0.0 && gap <= params_.gap_ms &&
        agree(T_last_, bound_last_m_, bound_last_deg_, estimate.T_cl_marker, estimate.error_bound_m,
              estimate.error_bound_deg, capture - last_capture_);
    if (!confirmed) {
      estimate.ok = false;
      estimate.not_ok_reason = NotOkReason::unconfirmed;
    }
  }
  have_last_ = sound;
  if (sound) {
    T_last_ = estimate.T_cl_marker;
    bound_last_m_ = estimate.error_bound_m;
    bound_last_deg_ = estimate.error_bound_deg;
    last_capture_ = capture;
  }
}

}  // namespace rovctl::estimator
