// OperatorLink: what the tick shows the operator and what the operator may ask of it. The tick
// publishes its telemetry every tick and a copy of the camera images every few ticks into
// lock-free latest-value slots; ABORT and START come back as atomic flags the next tick reads.
// The operator's side (the view server, on its own threads) can be slow or gone: the tick never
// waits for it and allocates nothing here after construction.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "app/runtime/telemetry.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/primitives/latest_slot.hpp"

namespace rovctl::app {

// One published camera pair with the telemetry of the tick that saw it (for the overlay).
struct OperatorFrame {
  TelemetryRecord record;
  cv::Mat left_bgr;  // preallocated at the calibrated size; copied into, never reallocated
  cv::Mat right_bgr;
};

class OperatorLink {
 public:
  // `image_period`: how often the tick copies the images (the view's frame rate).
  OperatorLink(const hal::StereoRig& rig, std::chrono::nanoseconds image_period);
  OperatorLink(const OperatorLink&) = delete;
  OperatorLink& operator=(const OperatorLink&) = delete;

  // --- the tick (one writer) ---
  // The record every tick; the images too when an image period has passed since the last copy.
  // No allocation, no lock; images of a size other than the calibration's are not copied.
  void publish(const TelemetryRecord& record, const hal::StereoFrame* frame,
               std::chrono::nanoseconds now) noexcept;
  // True once per request (consumes it).
  bool take_abort() noexcept { return abort_.exchange(false, std::memory_order_acq_rel); }
  bool take_start() noexcept { return start_.exchange(false, std::memory_order_acq_rel); }

  // --- the operator (any thread) ---
  // Returns the tick count published when the request was made (for the response and logs).
  std::uint64_t request_abort() noexcept;
  std::uint64_t request_start() noexcept;
  std::uint64_t last_tick() const noexcept { return last_tick_.load(std::memory_order_relaxed); }

  // --- the view (one reader thread) ---
  LatestSlot<TelemetryRecord>& records() noexcept { return records_; }
  LatestSlot<OperatorFrame>& frames() noexcept { return frames_; }

 private:
  LatestSlot<TelemetryRecord> records_;
  LatestSlot<OperatorFrame> frames_;
  std::chrono::nanoseconds image_period_;
  std::chrono::nanoseconds last_image_{-1};
  std::atomic<bool> abort_{false};
  std::atomic<bool> start_{false};
  std::atomic<std::uint64_t> last_tick_{0};
};

}  // namespace rovctl::app
