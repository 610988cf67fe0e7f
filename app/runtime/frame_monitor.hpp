// FrameMonitor: the failsafe's view of the images themselves — frozen (identical to the last
// pair, by a hash of a subsample), dead (a constant image), stale and left/right stamp skew.
// Reads a fixed grid of pixels per image: cheap, no allocation.
#pragma once

#include <chrono>
#include <cstdint>

#include "hal/interfaces/stereo_camera.hpp"

namespace rovctl::app {

struct FrameHealth {
  int identical_frames = 0;  // ticks in a row whose left or right image equals the previous one
  bool image_dead = false;   // one or both images span at most the dead range of grey levels
  std::chrono::nanoseconds frame_age{0};    // now - the newer capture stamp
  std::chrono::nanoseconds stereo_skew{0};  // |left stamp - right stamp|
};

class FrameMonitor {
 public:
  // Samples per image: kGrid x kGrid pixels, all three channels.
  static constexpr int kGrid = 32;

  explicit FrameMonitor(int dead_range_levels) : dead_range_levels_(dead_range_levels) {}

  // After a grab that returned ok.
  const FrameHealth& update(const hal::StereoFrame& frame, std::chrono::nanoseconds now);
  const FrameHealth& health() const { return health_; }

 private:
  struct Sample {
    std::uint64_t hash = 0;
    int range_levels = 0;  // largest max - min over the samples of one channel
  };
  static Sample sample(const cv::Mat& bgr);

  int dead_range_levels_;
  bool have_previous_ = false;
  std::uint64_t previous_left_ = 0;
  std::uint64_t previous_right_ = 0;
  FrameHealth health_;
};

}  // namespace rovctl::app
