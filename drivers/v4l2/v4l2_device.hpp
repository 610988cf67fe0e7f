// One V4L2 capture device: opens it by path or stable udev name, negotiates the pixel format,
// streams into a small ring of MMAP buffers and hands out the buffers the kernel has filled.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "drivers/v4l2/camera_controls.hpp"
#include "drivers/v4l2/pixel_format.hpp"
#include "drivers/v4l2/v4l2_ioctl.hpp"

namespace rovctl::drivers {

struct V4l2DeviceConfig {
  std::string device;  // "/dev/video0", "/dev/rovctl/cam-left", or a bare name: "cam-left"
  int width = 640;
  int height = 480;
  int fps = 30;
  PixelFormat preferred = PixelFormat::yuyv;  // the other supported format is the fallback
  int buffer_count = 4;                       // MMAP ring size requested (the driver may add)
  CameraControlSettings controls;             // exposure, gain, white balance, set at open
};

// A buffer the kernel has filled; valid until it is given back with requeue().
struct V4l2Buffer {
  int index = -1;
  const std::uint8_t* data = nullptr;
  std::size_t bytes_used = 0;
  std::chrono::nanoseconds stamp{0};  // CLOCK_MONOTONIC when `monotonic_stamp`
  bool monotonic_stamp = false;
  std::uint32_t sequence = 0;  // the driver's frame counter
};

enum class DequeueStatus { frame, empty, lost };

// A bare name (no '/') is looked up as /dev/rovctl/NAME (deploy/99-rovctl-cameras.rules),
// /dev/v4l/by-id/NAME, /dev/v4l/by-path/NAME, then /dev/NAME. Returns the first that exists, or
// the path unchanged (open() then reports it missing).
std::string resolve_video_device(const std::string& device);

class V4l2Device {
 public:
  // Every ioctl goes through `io` (the kernel's unless a test gives a fake).
  explicit V4l2Device(V4l2DeviceConfig config, V4l2Ioctl& io = system_v4l2_ioctl());
  ~V4l2Device();
  V4l2Device(const V4l2Device&) = delete;
  V4l2Device& operator=(const V4l2Device&) = delete;

  // Opens, negotiates, sets the camera controls, maps the buffer ring and starts streaming. On
  // failure returns false with an `error` that names the device (and what it offers when the
  // format is the problem, or the control and the camera's range when a control is refused).
  bool open(std::string& error);
  // Stops streaming and unmaps; safe on a device that has disappeared.
  void close();
  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }

  // Non-blocking: the next filled buffer (`frame`), none ready (`empty`), or the device is gone
  // (`lost`, with `error`). Buffers the driver flags as corrupt are requeued and skipped.
  DequeueStatus dequeue(V4l2Buffer& buffer, std::string& error);
  // Gives a dequeued buffer back to the driver. False (with `error`) when the device is gone.
  bool requeue(int index, std::string& error);
  // The buffer as last dequeued under `index` (valid while it is not requeued).
  const V4l2Buffer& dequeued(int index) const { return dequeued_[static_cast<std::size_t>(index)]; }

  const std::string& device() const { return config_.device; }  // as configured
  const std::string& path() const { return path_; }             // as opened
  PixelFormat format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t stride_bytes() const { return stride_bytes_; }
  std::size_t buffer_count() const { return buffers_.size(); }
  // Frames the driver dropped (gaps in its sequence counter) and corrupt buffers skipped.
  std::uint64_t kernel_dropped() const { return kernel_dropped_; }
  std::uint64_t corrupt_buffers() const { return corrupt_buffers_; }
  // "/dev/rovctl/cam-left (/dev/video0, "HD USB Camera"), MJPG 640x480 @ 30 fps, 4 buffers"
  std::string summary() const;
  // What open() did with the camera controls (set against read back, WARN for a missing one).
  const CameraControlReport& controls() const { return controls_; }

 private:
  bool fail(std::string& error, const std::string& what);
  bool negotiate(std::string& error);
  bool map_buffers(std::string& error);

  struct Mapping {
    void* start = nullptr;
    std::size_t length = 0;
  };

  V4l2DeviceConfig config_;
  V4l2Ioctl& io_;
  CameraControlReport controls_;
  std::string path_;
  std::string card_;
  int fd_ = -1;
  bool streaming_ = false;
  PixelFormat format_ = PixelFormat::yuyv;
  int width_ = 0;
  int height_ = 0;
  std::size_t stride_bytes_ = 0;
  double fps_ = 0.0;
  std::vector<Mapping> buffers_;
  std::vector<V4l2Buffer> dequeued_;  // by buffer index
  bool have_sequence_ = false;
  std::uint32_t last_sequence_ = 0;
  std::uint64_t kernel_dropped_ = 0;
  std::uint64_t corrupt_buffers_ = 0;
};

}  // namespace rovctl::drivers
