// The renderer runs inside the simulated 33 ms tick, so after start-up it must not touch the
// heap in any scenario. hal_tests cannot link app/runtime's counting hooks (the layering keeps
// hal below it): the tests' own malloc counter counts per thread, for this binary only.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "hal/mock/scene_renderer.hpp"
#include "hal/model/pose.hpp"
#include "malloc_counter.hpp"

namespace rovctl::hal::mock {
namespace {

using rovctl::testing::malloc_hooks_installed;
using rovctl::testing::t_allocations;

// What the hooks see, so that a zero below means something.
TEST(RenderAllocation, HooksCountThisThreadsAllocations) {
  if (!malloc_hooks_installed()) GTEST_SKIP() << "AddressSanitizer owns malloc: no counting hooks";
  const std::uint64_t before = t_allocations;
  const cv::Mat m(4, 4, CV_8UC3);  // OpenCV's allocator, in another library: not elided
  EXPECT_GE(t_allocations - before, 1u);
}

class SceneRendererAllocation : public ::testing::TestWithParam<Scenario> {};

TEST_P(SceneRendererAllocation, RenderAllocatesNothingAfterStartUp) {
  if (!malloc_hooks_installed()) GTEST_SKIP() << "AddressSanitizer owns malloc: no counting hooks";
  const StereoRig rig = make_parallel_rig(CameraModel{}, 0.178, 0.03);
  const MarkerModel marker = MarkerModel::standard();
  SceneConditions scene;
  scene.scenario = GetParam();
  scene.seed = 7;
  const SceneRenderer left(rig.left, marker, RenderOptions{}, scene);
  const SceneRenderer right(rig.right, marker, RenderOptions{}, scene);
  cv::Mat l, r;
  // Start-up: the first frame sizes the images (and OpenCV its own state).
  render_stereo(left, right, rig, make_pose({0.0, 0.0, 1.0}, Eigen::Quaterniond::Identity()), 1,
                0.0, l, r);
  const std::uint64_t before = t_allocations;
  // An approach from 1.5 m to 0.3 m over 30 s, turning a little: every moving part moves.
  for (int i = 0; i < 100; ++i) {
    const double s = i / 99.0;
    const Eigen::Isometry3d T =
        make_pose({0.1 * (1.0 - s), -0.05 * (1.0 - s), 1.5 - 1.2 * s},
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * (1.0 - s), Eigen::Vector3d::UnitY())));
    render_stereo(left, right, rig, T, static_cast<std::uint64_t>(i), 0.3 * i, l, r);
  }
  EXPECT_EQ(t_allocations - before, 0u)
      << "heap allocations in 100 stereo renders of scenario " << to_string(GetParam());
}

// A smeared exposure averages its sub-frames in scratch images the caller keeps.
TEST_P(SceneRendererAllocation, ASmearedExposureAllocatesNothingAfterStartUp) {
  if (!malloc_hooks_installed()) GTEST_SKIP() << "AddressSanitizer owns malloc: no counting hooks";
  const StereoRig rig = make_parallel_rig(CameraModel{}, 0.178, 0.03);
  SceneConditions scene;
  scene.scenario = GetParam();
  scene.seed = 7;
  const SceneRenderer left(rig.left, MarkerModel::standard(), RenderOptions{}, scene);
  Eigen::Isometry3d poses[8];
  for (int k = 0; k < 8; ++k) {
    poses[k] = make_pose({0.005 * k, 0.0, 1.0}, Eigen::Quaterniond::Identity());
  }
  cv::Mat out;
  ExposureScratch scratch;
  left.render_exposed(poses, 8, 1, 0.0, out, scratch);
  const std::uint64_t before = t_allocations;
  for (int i = 0; i < 20; ++i) left.render_exposed(poses, 8, 2 + i, 0.1 * i, out, scratch);
  EXPECT_EQ(t_allocations - before, 0u)
      << "heap allocations in 20 smeared renders of scenario " << to_string(GetParam());
}

INSTANTIATE_TEST_SUITE_P(EveryScenario, SceneRendererAllocation,
                         ::testing::Values(Scenario::clear, Scenario::turbid, Scenario::side_light,
                                           Scenario::bubbles, Scenario::occluders, Scenario::noisy,
                                           Scenario::exposure),
                         [](const ::testing::TestParamInfo<Scenario>& p) {
                           return std::string(to_string(p.param));
                         });

}  // namespace
}  // namespace rovctl::hal::mock
