// AttitudeAidedPose: a partial view's rotation from the attitude sensor, its translation from the
// spheres that are seen.
#include "control/attitude_aided_pose.hpp"

#include <gtest/gtest.h>

#include <array>
#include <chrono>

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

// Camera looking along body x (z forward, x right, y down), 0.2 m ahead of the body origin.
Eigen::Isometry3d body_cl() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  T.translation() = Eigen::Vector3d(0.2, 0.0, 0.1);
  return T;
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

Eigen::Quaterniond heading(double yaw_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
}

const std::array<Eigen::Vector3d, 3> kSpheres = {Eigen::Vector3d(-0.06, 0.0, 0.0),
                                                 Eigen::Vector3d(0.06, 0.0, 0.0),
                                                 Eigen::Vector3d(0.0, 0.09, -0.04)};

// The vehicle, seen whole at one heading, turns by 3 deg; the marker's true pose in the camera
// turns the other way. The estimator's two-sphere pose is 20 deg off about the line through the
// two spheres it sees, which keeps them where they are: the aided pose is the truth again.
TEST(AttitudeAidedPose, TheSeenSpheresAndTheAttitudeGiveBackTheTruth) {
  const Eigen::Isometry3d T_body_cl = body_cl();
  AttitudeAidedPose aided(T_body_cl, 5s);
  const Eigen::Isometry3d T_cl_marker_0 = pose(0.01, 0.02, 0.6, 0.02);
  aided.remember(1s, heading(0.3), T_cl_marker_0);

  // Turning the body by +d about world z turns the marker in the camera by -d about camera y
  // (the camera's y is body z).
  const double d = 3.0 * M_PI / 180.0;
  Eigen::Isometry3d truth = T_cl_marker_0;
  truth.linear() =
      Eigen::AngleAxisd(-d, Eigen::Vector3d::UnitY()).toRotationMatrix() * T_cl_marker_0.linear();
  truth.translation() = Eigen::Vector3d(0.03, 0.01, 0.55);
  // Wrong by 20 deg about the line through spheres 0 and 1 (marker x through y = 0, z = 0).
  Eigen::Isometry3d partial = truth;
  partial.linear() =
      truth.linear() * Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()).toRotationMatrix();
  ASSERT_NEAR((partial * kSpheres[0] - truth * kSpheres[0]).norm(), 0.0, 1e-12);
  ASSERT_GT((partial * kSpheres[2] - truth * kSpheres[2]).norm(), 0.02);

  Eigen::Isometry3d out;
  ASSERT_TRUE(aided.aid(2s, heading(0.3 + d), partial, kSpheres.data(), 2, out));
  EXPECT_LT((out.translation() - truth.translation()).norm(), 1e-9);
  EXPECT_LT(Eigen::AngleAxisd(out.linear().transpose() * truth.linear()).angle(), 1e-9);
}

TEST(AttitudeAidedPose, NothingRememberedTooOldOrNoPointsGivesNoPose) {
  AttitudeAidedPose aided(body_cl(), 5s);
  const Eigen::Isometry3d T = pose(0.0, 0.0, 0.6, 0.0);
  Eigen::Isometry3d out = pose(9.0, 9.0, 9.0, 0.0);
  EXPECT_FALSE(aided.aid(1s, heading(0.0), T, kSpheres.data(), 2, out)) << "nothing remembered";
  aided.remember(1s, heading(0.0), T);
  EXPECT_TRUE(aided.aid(6s, heading(0.0), T, kSpheres.data(), 2, out));
  EXPECT_FALSE(aided.aid(6s + 1ms, heading(0.0), T, kSpheres.data(), 2, out)) << "too old";
  EXPECT_FALSE(aided.aid(2s, heading(0.0), T, kSpheres.data(), 0, out)) << "no sphere seen";
  EXPECT_FALSE(aided.aid(2s, Eigen::Quaterniond(NAN, NAN, NAN, NAN), T, kSpheres.data(), 2, out));
  EXPECT_TRUE(out.matrix().allFinite()) << "a failed aid left its output as it was";
  aided.forget();
  EXPECT_FALSE(aided.aid(2s, heading(0.0), T, kSpheres.data(), 2, out)) << "forgotten";
}

}  // namespace
}  // namespace rovctl::control
