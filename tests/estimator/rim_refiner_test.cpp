// RimRefiner: the pose from the spheres' visible rims, with every sphere whole, with one half
// hidden behind a bar, and with nothing to see.
#include "estimator/rim_refiner.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "estimator/blob_seeder.hpp"
#include "estimator/hue_segmenter.hpp"
#include "estimator/pose_refiner.hpp"
#include "test_scene.hpp"

namespace {

using namespace rovctl;
using namespace rovctl::estimator;
using namespace rovctl::estimator::testing;

struct Labels {
  cv::Mat left, right;
};

Labels segment(const TestScene& scene) {
  HueSegmenter segmenter(scene.marker);
  Labels l;
  segmenter.segment(scene.left_bgr, l.left);
  segmenter.segment(scene.right_bgr, l.right);
  return l;
}

// Where the GA or the centroids typically leave the pose: a few millimetres and degrees off.
Eigen::Isometry3d nudged(const Eigen::Isometry3d& T) {
  Eigen::Isometry3d out = T;
  out.translation() += Eigen::Vector3d(0.003, -0.002, 0.004);
  out.linear() =
      Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, -1).normalized()) * T.linear();
  return out;
}

// Blanks the left half of sphere s in one view, as a vertical bar in front of it would.
void hide_left_half(const hal::CameraModel& camera, const Eigen::Vector3d& centre_cam_m,
                    double radius_m, cv::Mat& labels) {
  Eigen::Vector2d uv;
  ASSERT_TRUE(camera.project(centre_cam_m, uv));
  const double r_px = camera.fx_px * radius_m / centre_cam_m.z();
  const int x0 = static_cast<int>(uv.x() - 2.0 * r_px), x1 = static_cast<int>(uv.x());
  const int y0 = static_cast<int>(uv.y() - 2.0 * r_px), y1 = static_cast<int>(uv.y() + 2.0 * r_px);
  cv::rectangle(labels, cv::Point(x0, y0), cv::Point(x1, y1), cv::Scalar(0), cv::FILLED);
}

TEST(RimRefiner, ConvergesOnTheTruthFromAFewMillimetresOff) {
  TestScene scene;
  RimRefiner refiner(scene.rig, scene.marker);
  std::mt19937_64 rng(11);
  for (int i = 0; i < 8; ++i) {
    const Eigen::Isometry3d truth = random_pose(rng, 0.4, 1.2);
    scene.render(truth, static_cast<std::uint64_t>(i + 1));
    Labels l = segment(scene);
    Eigen::Isometry3d T = nudged(truth);
    RimFit fit;
    ASSERT_TRUE(refiner.refine(l.left, l.right, T, &fit)) << "pose " << i;
    EXPECT_LT(translation_error_mm(T, truth), 1.0) << "pose " << i;
    EXPECT_LT(rotation_error_deg(T, truth), 0.5) << "pose " << i;
    EXPECT_LT(fit.rms_px, 0.8);
    for (const auto& view : fit.support) {
      for (double s : view) EXPECT_GT(s, 0.9) << "pose " << i;
    }
    // The covariance says millimetres, not metres or nothing.
    const double bound_m = 3.0 * std::sqrt(fit.covariance.bottomRightCorner<3, 3>().trace());
    EXPECT_GT(bound_m, 1e-5);
    EXPECT_LT(bound_m, 0.02);
  }
}

TEST(RimRefiner, AHalfHiddenSphereMovesItsCentroidButNotTheRimPose) {
  TestScene scene;
  RimRefiner rims(scene.rig, scene.marker);
  PoseRefiner centroids(scene.rig, scene.marker);
  BlobSeeder blobs(scene.rig, scene.marker);
  const Eigen::Isometry3d truth = hal::make_pose(
      Eigen::Vector3d(0.05, 0.02, 0.8),
      Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.3, 1, 0.1).normalized())));
  scene.render(truth);
  Labels l = segment(scene);
  const hal::MarkerSphere& hidden = scene.marker.spheres[0];
  const Eigen::Vector3d c_left = truth * hidden.centre_marker_m;
  hide_left_half(scene.rig.left, c_left, hidden.radius_m, l.left);
  hide_left_half(scene.rig.right, scene.rig.T_cr_cl * c_left, hidden.radius_m, l.right);

  Eigen::Isometry3d T_centroids = nudged(truth);
  blobs.find(0, l.left);
  blobs.find(1, l.right);
  ASSERT_TRUE(centroids.refine(blobs.blobs(), T_centroids, 100.0));
  Eigen::Isometry3d T_rims = nudged(truth);
  RimFit fit;
  ASSERT_TRUE(rims.refine(l.left, l.right, T_rims, &fit));

  // The centroid of the visible half sits about 0.42 r off; the rims do not care.
  EXPECT_GT(translation_error_mm(T_centroids, truth), 2.0);
  EXPECT_LT(translation_error_mm(T_rims, truth), 1.0);
  EXPECT_LT(rotation_error_deg(T_rims, truth), 0.5);
  for (int v = 0; v < 2; ++v) {
    EXPECT_GT(fit.support[v][0], 0.35) << "view " << v;
    EXPECT_LT(fit.support[v][0], 0.7) << "view " << v;
    EXPECT_GT(fit.support[v][1], 0.9) << "view " << v;
    EXPECT_GT(fit.support[v][2], 0.9) << "view " << v;
  }
}

TEST(RimRefiner, NothingToSeeLeavesThePoseAlone) {
  TestScene scene;
  RimRefiner refiner(scene.rig, scene.marker);
  cv::Mat empty(scene.rig.left.height_px, scene.rig.left.width_px, CV_8UC1, cv::Scalar(0));
  const Eigen::Isometry3d start =
      hal::make_pose(Eigen::Vector3d(0.0, 0.0, 0.7), Eigen::Quaterniond::Identity());
  Eigen::Isometry3d T = start;
  EXPECT_FALSE(refiner.refine(empty, empty, T));
  EXPECT_TRUE(T.isApprox(start));
}

}  // namespace

namespace {

TEST(RimRefiner, ASphereCutByTheImageBorderIsJudgedOnItsRimInsideTheImage) {
  TestScene scene;
  RimRefiner refiner(scene.rig, scene.marker);
  // Green (the rightmost sphere) with its centre 0.4 radii inside the right border of the left
  // image: about a third of its rim lies beyond the border.
  Eigen::Isometry3d truth =
      hal::make_pose(Eigen::Vector3d(0.0, 0.0, 0.6), Eigen::Quaterniond::Identity());
  const hal::MarkerSphere& green = scene.marker.spheres[1];
  ASSERT_EQ(green.colour, hal::ColourClass::green);
  Eigen::Vector2d uv;
  const Eigen::Vector3d centre = truth * green.centre_marker_m;
  ASSERT_TRUE(scene.rig.left.project(centre, uv));
  const double r_px = scene.rig.left.fx_px * green.radius_m / centre.z();
  const double target_u_px = scene.rig.left.width_px - 0.5 - 0.4 * r_px;
  truth.translation().x() += (target_u_px - uv.x()) * centre.z() / scene.rig.left.fx_px;
  scene.render(truth, 5);
  Labels l = segment(scene);
  Eigen::Isometry3d T = nudged(truth);
  RimFit fit;
  ASSERT_TRUE(refiner.refine(l.left, l.right, T, &fit));
  EXPECT_LT(translation_error_mm(T, truth), 1.0);
  EXPECT_LT(rotation_error_deg(T, truth), 0.5);
  // Counted over the whole rim it would be about 2/3: below a confirmed sphere's support.
  for (double s : fit.support[0]) EXPECT_GT(s, 0.85);
}

}  // namespace
