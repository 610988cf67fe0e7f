// pose_measurement: the estimator's verdict as the tracker takes it.
#include "app/runtime/pose_measurement.hpp"

#include <gtest/gtest.h>

namespace rovctl::app {
namespace {

estimator::PoseEstimate recognised(bool ok, estimator::NotOkReason reason) {
  estimator::PoseEstimate e;
  e.recognised = true;
  e.ok = ok;
  e.not_ok_reason = reason;
  e.T_cl_marker.translation() = Eigen::Vector3d(0.0, 0.0, 0.8);
  e.error_bound_m = 0.003;
  e.error_bound_deg = 1.5;
  e.sphere_scores = {{{0.9, 0.9, 0.9}, {0.9, 0.9, 0.9}}};
  return e;
}

// Ok, or held back only by the frame-to-frame confirmation: sound, with the estimate's bounds.
TEST(PoseMeasurement, OkOrOnlyUnconfirmedIsSound) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  for (const auto& [ok, reason] : {std::pair{true, estimator::NotOkReason::none},
                                   std::pair{false, estimator::NotOkReason::unconfirmed}}) {
    const control::PoseMeasurement m = pose_measurement(recognised(ok, reason), marker, 0.5);
    EXPECT_TRUE(m.sound);
    EXPECT_EQ(m.bound_m, 0.003);
    EXPECT_EQ(m.bound_deg, 1.5);
    EXPECT_EQ(m.points, 0);
  }
  estimator::PoseEstimate unseen = recognised(true, estimator::NotOkReason::none);
  unseen.recognised = false;
  EXPECT_FALSE(pose_measurement(unseen, marker, 0.5).sound);
}

// A partial view: the spheres whose rims a sharp rims' fit confirms in both views, placed by that
// fit; without a sharp rims' fit, none.
TEST(PoseMeasurement, APartialViewGivesTheSpheresItsRimsConfirmInBothViews) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  estimator::PoseEstimate e = recognised(false, estimator::NotOkReason::partial_view);
  e.rim_support = {{{0.9, 0.1, 0.8}, {0.9, 0.9, 0.2}}};
  e.rims_sharp = true;
  e.T_cl_marker_rims.translation() = Eigen::Vector3d(0.01, 0.0, 0.79);
  const control::PoseMeasurement m = pose_measurement(e, marker, 0.5);
  EXPECT_FALSE(m.sound);
  ASSERT_EQ(m.points, 1);
  EXPECT_EQ(m.points_marker_m[0], marker.spheres[0].centre_marker_m);
  EXPECT_EQ(m.T_cl_marker.translation(), e.T_cl_marker_rims.translation());
  e.rim_support = {{{0.9, 0.9, 0.9}, {0.9, 0.9, 0.9}}};
  EXPECT_EQ(pose_measurement(e, marker, 0.5).points, 3);
  e.rims_sharp = false;
  EXPECT_EQ(pose_measurement(e, marker, 0.5).points, 0);
}

}  // namespace
}  // namespace rovctl::app
