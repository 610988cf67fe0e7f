// OperatorLink: what the tick shows the operator and what the operator may ask of it. The tick
// publishes its telemetry every tick and a copy of the camera images every few ticks into
// lock-free latest-value slots; ABORT and START come back as atomic requests the next tick reads,
// each with a deadline: a request no tick took by then is dropped, never applied late. The
// operator's side (the view server, on its own threads) can be slow or gone: the tick never
// waits for it and allocates nothing here after construction.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <opencv2/core/mat.hpp>

#include "app/runtime/telemetry.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/primitives/latest_slot.hpp"

namespace rovctl::app {

enum class OperatorCommand { abort, start };

// What became of one ABORT or START.
struct OperatorCommandResult {
  bool taken = false;      // a tick took it (and acted on it as its state allows)
  std::uint64_t tick = 0;  // the tick that took it
};

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
  // True once per request, and only before its deadline: a request found past it is dropped
  // (counted in stale_dropped()), because an operator who saw it fail must not see it run later.
  bool take_abort() noexcept { return take(abort_); }
  bool take_start() noexcept { return take(start_); }

  // --- the operator (any thread) ---
  // Hands `command` to the tick and waits until a tick takes it or `deadline` passes; then it is
  // withdrawn and no later tick applies it. Polls every `poll` (this thread, never the tick's).
  OperatorCommandResult submit(OperatorCommand command,
                               std::chrono::steady_clock::time_point deadline,
                               std::chrono::microseconds poll = std::chrono::microseconds(500));
  // Posts without waiting, for callers that run the tick themselves: taken by a tick within
  // `max_age`, else dropped. Returns the tick count published when the request was made.
  std::uint64_t request_abort(std::chrono::milliseconds max_age = std::chrono::seconds(1)) noexcept;
  std::uint64_t request_start(std::chrono::milliseconds max_age = std::chrono::seconds(1)) noexcept;
  std::uint64_t last_tick() const noexcept { return last_tick_.load(std::memory_order_relaxed); }
  // Requests a tick found past their deadline (the operator thread had given up on them).
  std::uint64_t stale_dropped() const noexcept {
    return stale_dropped_.load(std::memory_order_relaxed);
  }

  // --- the view (one reader thread) ---
  LatestSlot<TelemetryRecord>& records() noexcept { return records_; }
  LatestSlot<OperatorFrame>& frames() noexcept { return frames_; }

 private:
  LatestSlot<TelemetryRecord> records_;
  LatestSlot<OperatorFrame> frames_;
  std::chrono::nanoseconds image_period_;
  std::chrono::nanoseconds last_image_{-1};
  // One request at a time per command: `pending` holds its id (0: none) and `deadline_ns` its
  // steady-clock deadline; the tick answers through `taken` / `dropped` (the id it resolved).
  struct Request {
    std::atomic<std::uint64_t> pending{0};
    std::atomic<std::int64_t> deadline_ns{0};
    std::atomic<std::uint64_t> taken{0};
    std::atomic<std::uint64_t> dropped{0};
    std::atomic<std::uint64_t> taken_tick{0};
  };
  bool take(Request& r) noexcept;
  std::uint64_t post(Request& r, std::chrono::steady_clock::time_point deadline) noexcept;
  Request& request(OperatorCommand c) noexcept {
    return c == OperatorCommand::abort ? abort_ : start_;
  }

  Request abort_;
  Request start_;
  std::atomic<std::uint64_t> next_id_{0};
  std::mutex submit_mutex_;  // operator threads only: one submit at a time
  std::atomic<std::uint64_t> stale_dropped_{0};
  std::atomic<std::uint64_t> last_tick_{0};
};

}  // namespace rovctl::app
