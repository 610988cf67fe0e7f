// The estimate as the pose tracker takes it (see pose_measurement.hpp).
#include "app/runtime/pose_measurement.hpp"

#include <cmath>

namespace rovctl::app {

control::PoseMeasurement pose_measurement(const estimator::PoseEstimate& estimate,
                                          const hal::MarkerModel& marker, double rim_support) {
  control::PoseMeasurement m;
  m.sound = estimate.recognised &&
            (estimate.ok || estimate.not_ok_reason == estimator::NotOkReason::unconfirmed);
  m.T_cl_marker = estimate.T_cl_marker;
  m.bound_m = estimate.error_bound_m;
  m.bound_deg = estimate.error_bound_deg;
  if (m.sound || !estimate.recognised || !estimate.rims_sharp ||
      !estimate.T_cl_marker_rims.matrix().allFinite()) {
    return m;
  }
  m.T_cl_marker = estimate.T_cl_marker_rims;
  for (std::size_t s = 0; s < marker.spheres.size() && m.points < m.kMaxPoints; ++s) {
    if (estimate.rim_support[0][s] >= rim_support && estimate.rim_support[1][s] >= rim_support) {
      m.points_marker_m[m.points++] = marker.spheres[s].centre_marker_m;
    }
  }
  return m;
}

}  // namespace rovctl::app
