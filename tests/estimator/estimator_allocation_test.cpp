// The estimator runs inside the 33 ms tick: after start-up no frame may touch the heap, whether
// the marker is in view, gone (every look runs, the GA starts afresh) or back.
#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/core.hpp>

#include "estimator/pose_estimator.hpp"
#include "malloc_counter.hpp"
#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

using rovctl::testing::malloc_hooks_installed;
using rovctl::testing::t_allocations;

TEST(EstimatorAllocation, FramesAllocateNothingAfterStartUpWithOrWithoutTheMarker) {
  if (!malloc_hooks_installed()) GTEST_SKIP() << "AddressSanitizer owns malloc: no counting hooks";
  testing::TestScene scene;
  scene.render(hal::make_pose({0.05, 0.01, 0.6}, Eigen::Quaterniond::Identity()));
  const cv::Mat empty_left = scene.empty_image();
  const cv::Mat empty_right = scene.empty_image();
  PoseEstimator est(scene.rig, scene.marker, EstimatorParams{}, 3);
  // Start-up: one frame of each kind sizes what OpenCV sizes on first use.
  est.update(scene.left_bgr, scene.right_bgr);
  est.update(empty_left, empty_right);

  {
    const std::uint64_t probe_before = t_allocations;
    const cv::Mat probe(4, 4, CV_8UC3);  // OpenCV's allocator, in another library: not elided
    ASSERT_GE(t_allocations - probe_before, 1u) << "the hooks should count this thread";
  }
  const std::uint64_t before = t_allocations;
  int restarts = 0, ok = 0;
  for (int frame = 0; frame < 24; ++frame) {
    const bool marker = (frame / 8) % 2 == 1;  // 8 frames without, 8 with, 8 without
    const PoseEstimate e =
        marker ? est.update(scene.left_bgr, scene.right_bgr) : est.update(empty_left, empty_right);
    restarts += e.ga_restarted ? 1 : 0;
    ok += e.ok ? 1 : 0;
  }
  EXPECT_EQ(t_allocations - before, 0u) << "heap allocations in 24 estimator frames";
  EXPECT_GE(restarts, 4) << "the frames without the marker should have restarted the GA";
  EXPECT_EQ(ok, 8);
}

}  // namespace
}  // namespace rovctl::estimator
