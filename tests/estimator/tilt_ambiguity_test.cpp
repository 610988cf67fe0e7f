// tilt_ambiguity: the mirrored tilt keeps the spheres' image seen along the line of sight, turns
// the marker by twice its tilt, and is its own inverse.
#include "estimator/tilt_ambiguity.hpp"

#include <gtest/gtest.h>

#include "hal/model/pose.hpp"

namespace {

using namespace rovctl;
using rovctl::estimator::mirrored_tilt;

Eigen::Isometry3d tilted(double yaw_deg, double pitch_deg) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(pitch_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  return hal::make_pose(Eigen::Vector3d(-0.3, -0.45, 1.26), q);
}

TEST(TiltAmbiguity, KeepsTheImageAcrossTheLineOfSight) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  const Eigen::Isometry3d T = tilted(-24.0, 19.0);
  const Eigen::Isometry3d M = mirrored_tilt(T, marker);
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), cm = Eigen::Vector3d::Zero();
  for (const auto& s : marker.spheres) {
    c += T * s.centre_marker_m / 3.0;
    cm += M * s.centre_marker_m / 3.0;
  }
  EXPECT_LT((c - cm).norm(), 1e-12);  // turned about the spheres' centroid
  const Eigen::Vector3d sight = c.normalized();
  double depth_change_m = 0.0;
  for (const auto& s : marker.spheres) {
    const Eigen::Vector3d d = T * s.centre_marker_m - c, dm = M * s.centre_marker_m - c;
    const Eigen::Vector3d across = d - d.dot(sight) * sight, across_m = dm - dm.dot(sight) * sight;
    EXPECT_LT((across - across_m).norm(), 1e-12);
    // Along the line of sight each sphere swaps to the other side of the centroid.
    EXPECT_NEAR(d.dot(sight), -dm.dot(sight), 1e-12);
    depth_change_m = std::max(depth_change_m, std::abs(d.dot(sight) - dm.dot(sight)));
  }
  EXPECT_GT(depth_change_m, 0.02);  // a different pose, not T again
  EXPECT_GT(hal::rotation_angle_rad(T.linear(), M.linear()), 20.0 * M_PI / 180.0);
}

TEST(TiltAmbiguity, MirroringTwiceGivesThePoseBack) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  const Eigen::Isometry3d T = tilted(15.0, -30.0);
  const Eigen::Isometry3d back = mirrored_tilt(mirrored_tilt(T, marker), marker);
  EXPECT_LT(hal::rotation_angle_rad(T.linear(), back.linear()), 1e-9);
  EXPECT_LT((T.translation() - back.translation()).norm(), 1e-12);
}

TEST(TiltAmbiguity, ATriangleFacingTheCameraHasNoOtherTilt) {
  hal::MarkerModel marker = hal::MarkerModel::standard();
  // The triangle's normal along the line of sight through its centroid.
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& s : marker.spheres) c += s.centre_marker_m / 3.0;
  const Eigen::Vector3d n =
      (marker.spheres[1].centre_marker_m - marker.spheres[0].centre_marker_m)
          .cross(marker.spheres[2].centre_marker_m - marker.spheres[0].centre_marker_m)
          .normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond::FromTwoVectors(n, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.0, 0.0, 1.0) - T.linear() * c;
  const Eigen::Isometry3d M = mirrored_tilt(T, marker);
  EXPECT_LT(hal::rotation_angle_rad(T.linear(), M.linear()), 1e-6);
  marker.spheres.pop_back();
  EXPECT_TRUE(mirrored_tilt(tilted(20.0, 0.0), marker).isApprox(tilted(20.0, 0.0)));
}

}  // namespace
