// The estimate as the pose tracker takes it (see pose_measurement.hpp).
#include "app/runtime/pose_measurement.hpp"

#include <cmath>

namespace rovctl::app {

control::PoseMeasurement pose_measurement(const estimator::PoseEstimate& estimate,
                                          const hal::MarkerModel& marker, double sphere_support) {
  control::PoseMeasurement m;
  m.sound = estimate.recognised &&
            (estimate.ok || estimate.not_ok_reason == estimator::NotOkReason::unconfirmed);
  m.T_cl_marker = estimate.T_cl_marker;
  m.bound_m = estimate.error_bound_m;
  m.bound_deg = estimate.error_bound_deg;
  if (m.sound || !estimate.recognised || !estimate.T_cl_marker.matrix().allFinite()) return m;
  for (std::size_t s = 0; s < marker.spheres.size() && m.points < m.kMaxPoints; ++s) {
    if (estimate.sphere_scores[0][s] >= sphere_support &&
        estimate.sphere_scores[1][s] >= sphere_support) {
      m.points_marker_m[m.points++] = marker.spheres[s].centre_marker_m;
    }
  }
  return m;
}

}  // namespace rovctl::app
