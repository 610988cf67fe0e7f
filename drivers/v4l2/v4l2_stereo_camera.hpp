// StereoCamera over two free-running V4L2 cameras: pairs their frames by kernel capture stamp,
// delivers only the newest pair, and reopens a lost camera with back-off.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "drivers/camera_params.hpp"
#include "drivers/v4l2/frame_pairing.hpp"
#include "drivers/v4l2/reopen_backoff.hpp"
#include "drivers/v4l2/v4l2_device.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/stereo_camera.hpp"

namespace rovctl::drivers {

struct V4l2CameraStats {
  PairingStats pairing;
  std::uint64_t timeouts = 0;
  std::uint64_t device_losses = 0;
  std::uint64_t reopens = 0;            // successful reopens after a loss
  std::uint64_t conversion_errors = 0;  // pairs dropped because a frame did not convert
  std::uint64_t kernel_dropped_left = 0;
  std::uint64_t kernel_dropped_right = 0;
};

class V4l2StereoCamera final : public hal::StereoCamera {
 public:
  // `clock` times the grab timeout and the reopen back-off; on the vehicle it is the
  // MonotonicClock, the same time base as the kernel's buffer stamps. A buffer without a
  // monotonic kernel stamp is stamped with clock.now() when it is dequeued.
  V4l2StereoCamera(const V4l2CameraParams& params, hal::Clock& clock);
  ~V4l2StereoCamera() override;

  bool open(std::string& error) override;
  // ok; timeout when no pair came within grab_timeout_ms; device_lost when a camera vanished
  // (and on every grab until a reopen, tried with back-off from inside grab(), succeeds).
  // Allocation-free in steady state, except that MJPG decoding allocates libjpeg's state.
  hal::GrabStatus grab(hal::StereoFrame& frame) override;
  void close() override;
  std::string name() const override;

  const V4l2CameraStats& stats() const { return stats_; }
  // Why the last grab was not ok (empty after an ok grab is not guaranteed).
  const std::string& last_error() const { return last_error_; }
  // Both cameras' control lines as the last open set them ("left exposure: 4.0 ms set, ...").
  std::vector<ControlReportLine> controls_report() const;

 private:
  bool open_devices(std::string& error);
  void close_devices();
  // Dequeues everything the device has ready into the pairing; false on device loss.
  bool drain(V4l2Device& device, Side side);
  bool give_back_released();
  hal::GrabStatus lose(std::chrono::nanoseconds now);

  V4l2CameraParams params_;
  hal::Clock& clock_;
  V4l2Device left_;
  V4l2Device right_;
  FramePairing pairing_;
  ReopenBackoff backoff_;
  bool opened_ = false;  // open() succeeded and close() was not called since
  bool streaming_ = false;
  std::uint64_t sequence_ = 0;
  std::chrono::nanoseconds exposure_{0};  // read back at open; 0: unknown
  V4l2CameraStats stats_;
  std::string last_error_;
};

}  // namespace rovctl::drivers
