// The estimator end to end on rendered pairs of the shipped distorted, toe-in, non-rectified rig.
#include "estimator/pose_estimator.hpp"

#include <gtest/gtest.h>

#include <string>

#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

using testing::random_pose;
using testing::rotation_error_deg;
using testing::TestScene;
using testing::translation_error_mm;

TEST(PoseEstimator, ImprovedModeFindsThePoseInTheFirstFrame) {
  TestScene scene;
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 12; ++trial) {
    const Eigen::Isometry3d truth = random_pose(rng);
    scene.render(truth, trial);
    PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, trial);
    const PoseEstimate e = est.update(scene.left_bgr, scene.right_bgr);
    EXPECT_TRUE(e.recognised) << trial;
    EXPECT_GE(e.fitness, 0.9) << trial;
    EXPECT_EQ(e.generations, 9);
    EXPECT_LT(translation_error_mm(e.T_cl_marker, truth), 2.0) << trial;
    EXPECT_LT(rotation_error_deg(e.T_cl_marker, truth), 1.0) << trial;
  }
}

TEST(PoseEstimator, FaithfulModeClimbsAndIsReproducible) {
  TestScene scene;
  const Eigen::Isometry3d truth =
      hal::make_pose({0.05, 0.01, 0.45}, Eigen::Quaterniond::Identity());
  scene.render(truth);
  EstimatorParams p;
  p.mode = "faithful";
  PoseEstimator a(scene.rig, scene.marker, p, 5), b(scene.rig, scene.marker, p, 5);
  double first = 0.0, last = 0.0;
  for (int f = 0; f < 150; ++f) {
    const PoseEstimate ea = a.update(scene.left_bgr, scene.right_bgr);
    const PoseEstimate eb = b.update(scene.left_bgr, scene.right_bgr);
    ASSERT_EQ(ea.fitness, eb.fitness);
    ASSERT_TRUE(ea.T_cl_marker.isApprox(eb.T_cl_marker));
    ASSERT_GE(ea.fitness, last);  // elitism on a static pair
    if (f == 0) first = ea.fitness;
    last = ea.fitness;
  }
  EXPECT_GT(last, first);
}

// The estimator runs inside the tick: a wrong image is reported in the estimate, never thrown.
TEST(PoseEstimator, WrongImageSizeIsReportedNotThrown) {
  TestScene scene;
  PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 1);
  cv::Mat small(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_FALSE(est.segment(small, small));
  PoseEstimate e;
  EXPECT_NO_THROW(e = est.estimate());
  EXPECT_FALSE(e.recognised);
  ASSERT_NE(e.input_error, nullptr);
  EXPECT_NE(std::string(e.input_error).find("size"), std::string::npos);
  cv::Mat grey(scene.rig.left.height_px, scene.rig.left.width_px, CV_8UC1, cv::Scalar(0));
  EXPECT_FALSE(est.update(grey, grey).input_error == nullptr);
  // A good pair afterwards is estimated as usual.
  scene.render(hal::make_pose({0.0, 0.0, 0.5}, Eigen::Quaterniond::Identity()));
  EXPECT_EQ(est.update(scene.left_bgr, scene.right_bgr).input_error, nullptr);
}

TEST(PoseEstimator, InconsistentParamsThrow) {
  TestScene scene;
  EstimatorParams p;
  p.search.z_min_m = 2.0;
  EXPECT_THROW(PoseEstimator(scene.rig, scene.marker, p, 1), std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::estimator
