// Subsampled hash and range of each image; a camera's noise changes every sample of a live image.
#include "app/runtime/frame_monitor.hpp"

#include <algorithm>

namespace rovctl::app {

FrameMonitor::Sample FrameMonitor::sample(const cv::Mat& bgr) {
  Sample s;
  if (bgr.empty() || bgr.type() != CV_8UC3) return s;
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  int lo[3] = {255, 255, 255};
  int hi[3] = {0, 0, 0};
  for (int gy = 0; gy < kGrid; ++gy) {
    const int y = (2 * gy + 1) * bgr.rows / (2 * kGrid);
    const auto* row = bgr.ptr<std::uint8_t>(y);
    for (int gx = 0; gx < kGrid; ++gx) {
      const int x = (2 * gx + 1) * bgr.cols / (2 * kGrid);
      for (int c = 0; c < 3; ++c) {
        const int v = row[3 * x + c];
        hash = (hash ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
        lo[c] = std::min(lo[c], v);
        hi[c] = std::max(hi[c], v);
      }
    }
  }
  s.hash = hash;
  s.range_levels = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  return s;
}

const FrameHealth& FrameMonitor::update(const hal::StereoFrame& frame,
                                        std::chrono::nanoseconds now) {
  const Sample left = sample(frame.left_bgr);
  const Sample right = sample(frame.right_bgr);
  const bool identical =
      have_previous_ && (left.hash == previous_left_ || right.hash == previous_right_);
  health_.identical_frames = identical ? health_.identical_frames + 1 : 0;
  health_.image_dead =
      left.range_levels <= dead_range_levels_ || right.range_levels <= dead_range_levels_;
  health_.frame_age = now - std::max(frame.left_stamp, frame.right_stamp);
  health_.stereo_skew = frame.left_stamp > frame.right_stamp ? frame.left_stamp - frame.right_stamp
                                                             : frame.right_stamp - frame.left_stamp;
  previous_left_ = left.hash;
  previous_right_ = right.hash;
  have_previous_ = true;
  return health_;
}

}  // namespace rovctl::app
