// The tick's side of the operator view: plain copies into slots sized at start-up.
#include "app/runtime/operator_link.hpp"

#include <opencv2/core.hpp>

namespace rovctl::app {

OperatorLink::OperatorLink(const hal::StereoRig& rig, std::chrono::nanoseconds image_period)
    : frames_([&rig](OperatorFrame& f) {
        f.left_bgr.create(rig.left.height_px, rig.left.width_px, CV_8UC3);
        f.right_bgr.create(rig.right.height_px, rig.right.width_px, CV_8UC3);
        f.left_bgr.setTo(cv::Scalar::all(0));
        f.right_bgr.setTo(cv::Scalar::all(0));
      }),
      image_period_(image_period) {}

void OperatorLink::publish(const TelemetryRecord& record, const hal::StereoFrame* frame,
                           std::chrono::nanoseconds now) noexcept {
  records_.back() = record;
  records_.publish();
  last_tick_.store(record.tick, std::memory_order_relaxed);
  // A clock that went back (the next simulated trial starts at 0) starts the period afresh.
  if (frame == nullptr ||
      (last_image_.count() >= 0 && now >= last_image_ && now - last_image_ < image_period_)) {
    return;
  }
  OperatorFrame& out = frames_.back();
  // copyTo into a Mat of the same size and type reuses its buffer; any other size is skipped
  // rather than reallocated on the tick.
  if (frame->left_bgr.size() != out.left_bgr.size() ||
      frame->right_bgr.size() != out.right_bgr.size() || frame->left_bgr.type() != CV_8UC3 ||
      frame->right_bgr.type() != CV_8UC3) {
    return;
  }
  frame->left_bgr.copyTo(out.left_bgr);
  frame->right_bgr.copyTo(out.right_bgr);
  out.record = record;
  frames_.publish();
  last_image_ = now;
}

std::uint64_t OperatorLink::request_abort() noexcept {
  abort_.store(true, std::memory_order_release);
  return last_tick();
}

std::uint64_t OperatorLink::request_start() noexcept {
  start_.store(true, std::memory_order_release);
  return last_tick();
}

}  // namespace rovctl::app
