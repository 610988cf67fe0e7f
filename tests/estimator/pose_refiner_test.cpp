// PoseRefiner: the pose from the blobs' centroids, and the centroid noise its covariance is
// scaled by.
#include "estimator/pose_refiner.hpp"

#include <gtest/gtest.h>

#include <random>

#include "test_scene.hpp"

namespace {

using namespace rovctl;
using namespace rovctl::estimator;
using namespace rovctl::estimator::testing;

// Every sphere's centroid where the pose puts it, plus Gaussian noise of sigma_px per coordinate.
BlobSet noisy_blobs(const TestScene& scene, const Eigen::Isometry3d& T, double sigma_px,
                    std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, sigma_px);
  BlobSet blobs{};
  for (int view = 0; view < 2; ++view) {
    for (const hal::MarkerSphere& s : scene.marker.spheres) {
      Eigen::Vector3d c = T * s.centre_marker_m;
      if (view == 1) c = scene.rig.T_cr_cl * c;
      Eigen::Vector2d uv;
      EXPECT_TRUE(PoseRefiner::silhouette_centroid(view == 0 ? scene.rig.left : scene.rig.right, c,
                                                   s.radius_m, uv));
      Blob& b = blobs[view][static_cast<int>(s.colour)];
      b.valid = true;
      b.u_px = uv.x() + noise(rng);
      b.v_px = uv.y() + noise(rng);
    }
  }
  return blobs;
}

// Six centroids give twelve coordinates and the pose takes six of them: the residual's mean
// square over all twelve is half the noise's variance. sigma_free_px divides by the six left free,
// so on average it squares to the noise's variance.
TEST(PoseRefiner, TheCentroidNoiseIsMeasuredOverTheCoordinatesThePoseLeavesFree) {
  TestScene scene;
  PoseRefiner refiner(scene.rig, scene.marker);
  std::mt19937_64 rng(3);
  constexpr double kSigmaPx = 0.8;  // over kCentroidNoisePx, which would floor it
  constexpr int kDraws = 300;
  double sigma2_sum = 0.0, half_rms2_sum = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const Eigen::Isometry3d truth = random_pose(rng, 0.5, 1.0);
    const BlobSet blobs = noisy_blobs(scene, truth, kSigmaPx, rng);
    Eigen::Isometry3d T = truth;
    RefineReport report;
    ASSERT_TRUE(refiner.refine(blobs, T, 10.0, &report)) << "draw " << i;
    ASSERT_EQ(report.centroids, 6);
    sigma2_sum += report.sigma_free_px * report.sigma_free_px;
    half_rms2_sum += report.rms_px * report.rms_px / 2.0;
  }
  const double variance = kSigmaPx * kSigmaPx;
  EXPECT_NEAR(sigma2_sum / kDraws, variance, 0.12 * variance);
  EXPECT_NEAR(half_rms2_sum / kDraws, 0.5 * variance, 0.06 * variance);
}

}  // namespace
