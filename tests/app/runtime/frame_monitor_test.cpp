// FrameMonitor: a repeated pair counts as frozen, a noisy live pair does not; a black image is
// dead; skew and age come from the stamps.
#include "app/runtime/frame_monitor.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace rovctl::app {
namespace {

using namespace std::chrono_literals;

hal::StereoFrame noisy_frame(int seed) {
  hal::StereoFrame f;
  f.left_bgr.create(480, 640, CV_8UC3);
  f.right_bgr.create(480, 640, CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(f.left_bgr, cv::RNG::UNIFORM, 0, 256);
  rng.fill(f.right_bgr, cv::RNG::UNIFORM, 0, 256);
  return f;
}

TEST(FrameMonitor, RepeatedImagesCountAsFrozen) {
  FrameMonitor m(3);
  hal::StereoFrame f = noisy_frame(1);
  EXPECT_EQ(m.update(f, 1s).identical_frames, 0);
  EXPECT_EQ(m.update(f, 1s + 33ms).identical_frames, 1);
  EXPECT_EQ(m.update(f, 1s + 66ms).identical_frames, 2);
  const hal::StereoFrame fresh = noisy_frame(2);
  EXPECT_EQ(m.update(fresh, 1s + 99ms).identical_frames, 0);
  EXPECT_FALSE(m.health().image_dead);
}

TEST(FrameMonitor, BlackImageIsDeadAndStampsGiveSkewAndAge) {
  FrameMonitor m(3);
  hal::StereoFrame f = noisy_frame(3);
  f.left_stamp = 960ms;
  f.right_stamp = 900ms;
  const FrameHealth& h = m.update(f, 1s);
  EXPECT_FALSE(h.image_dead);
  EXPECT_EQ(h.stereo_skew, 60ms);
  EXPECT_EQ(h.frame_age, 40ms);
  f.right_bgr.setTo(cv::Scalar::all(0));
  EXPECT_TRUE(m.update(f, 1s).image_dead);
}

}  // namespace
}  // namespace rovctl::app
