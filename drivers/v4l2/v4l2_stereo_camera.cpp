// Grab loop: drain both devices, pair by stamp, convert the newest pair, poll until the deadline.
#include "drivers/v4l2/v4l2_stereo_camera.hpp"

#include <poll.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace rovctl::drivers {

namespace {

std::chrono::nanoseconds from_ms(double ms) {
  return std::chrono::nanoseconds(static_cast<long long>(std::llround(ms * 1e6)));
}

V4l2DeviceConfig device_config(const V4l2CameraParams& p, const std::string& device) {
  V4l2DeviceConfig c;
  c.device = device;
  c.width = p.width_px;
  c.height = p.height_px;
  c.fps = p.fps;
  c.preferred = pixel_format_from_string(p.format).value_or(PixelFormat::yuyv);
  c.buffer_count = p.buffer_count;
  c.controls.auto_exposure = p.auto_exposure;
  c.controls.exposure_time_us = p.exposure_time_us;
  c.controls.gain = p.gain;
  c.controls.white_balance = p.white_balance;
  c.controls.white_balance_temperature_k = p.white_balance_temperature_k;
  return c;
}

// Also true for a udev symlink and the node it points to (same device number).
bool same_device(const std::string& a, const std::string& b) {
  const std::string ra = resolve_video_device(a);
  const std::string rb = resolve_video_device(b);
  struct stat sa {};
  struct stat sb {};
  if (::stat(ra.c_str(), &sa) == 0 && ::stat(rb.c_str(), &sb) == 0) {
    if (S_ISCHR(sa.st_mode) && S_ISCHR(sb.st_mode)) return sa.st_rdev == sb.st_rdev;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  }
  std::error_code ec;
  return std::filesystem::weakly_canonical(ra, ec) == std::filesystem::weakly_canonical(rb, ec);
}

std::size_t held_per_side(int buffer_count) {
  // Two buffers stay with the driver so capture never stalls while frames wait for partners.
  return static_cast<std::size_t>(
      std::clamp<int>(buffer_count - 2, 1, static_cast<int>(FramePairing::kMaxHeldPerSide)));
}

}  // namespace

V4l2StereoCamera::V4l2StereoCamera(const V4l2CameraParams& params, hal::Clock& clock)
    : params_(params),
      clock_(clock),
      left_(device_config(params, params.left_device)),
      right_(device_config(params, params.right_device)),
      pairing_(from_ms(params.pairing_tolerance_ms), held_per_side(params.buffer_count)),
      backoff_(from_ms(params.reopen_backoff_ms), from_ms(params.reopen_backoff_max_ms)) {}

V4l2StereoCamera::~V4l2StereoCamera() { close(); }

bool V4l2StereoCamera::open(std::string& error) {
  close();
  if (!pixel_format_from_string(params_.format)) {
    error = "camera.v4l2.format: '" + params_.format + "' is not one of: yuyv, mjpg";
    return false;
  }
  if (same_device(params_.left_device, params_.right_device)) {
    error = "camera.v4l2: left_device and right_device are the same device (" +
            params_.left_device + ")";
    return false;
  }
  if (!open_devices(error)) return false;
  opened_ = true;
  backoff_.succeeded();
  return true;
}

bool V4l2StereoCamera::open_devices(std::string& error) {
  if (!left_.open(error)) return false;
  if (!right_.open(error)) {
    left_.close();
    return false;
  }
  if (left_.format() != right_.format()) {
    // Each is converted on its own, so this works; it is worth knowing about though.
    last_error_ = "note: left camera streams " + std::string(to_string(left_.format())) +
                  ", right camera " + to_string(right_.format());
  }
  // Known only when both cameras read back a manual exposure; the longer one bounds the smear.
  const auto l = left_.controls().exposure, r = right_.controls().exposure;
  exposure_ = l.count() > 0 && r.count() > 0 ? std::max(l, r) : std::chrono::nanoseconds(0);
  streaming_ = true;
  return true;
}

std::vector<ControlReportLine> V4l2StereoCamera::controls_report() const {
  std::vector<ControlReportLine> lines;
  for (const V4l2Device* d : {&left_, &right_}) {
    for (const ControlReportLine& l : d->controls().lines) {
      lines.push_back({l.level, (d == &left_ ? "left " : "right ") + d->device() + ": " + l.text});
    }
  }
  return lines;
}

void V4l2StereoCamera::close_devices() {
  pairing_.clear();
  Side side{};
  int token = 0;
  while (pairing_.pop_released(side, token)) {
  }  // the buffers go with the devices
  left_.close();
  right_.close();
  streaming_ = false;
}

void V4l2StereoCamera::close() {
  close_devices();
  opened_ = false;
}

std::string V4l2StereoCamera::name() const {
  return "v4l2 stereo: left " + left_.summary() + "; right " + right_.summary();
}

bool V4l2StereoCamera::give_back_released() {
  Side side{};
  int token = 0;
  bool ok = true;
  while (pairing_.pop_released(side, token)) {
    V4l2Device& d = side == Side::left ? left_ : right_;
    ok = d.requeue(token, last_error_) && ok;
  }
  return ok;
}

bool V4l2StereoCamera::drain(V4l2Device& device, Side side) {
  for (;;) {
    V4l2Buffer buffer;
    const DequeueStatus s = device.dequeue(buffer, last_error_);
    if (s == DequeueStatus::empty) return true;
    if (s == DequeueStatus::lost) return false;
    const auto stamp = buffer.monotonic_stamp ? buffer.stamp : clock_.now();
    pairing_.add(side, stamp, buffer.index);
    if (!give_back_released()) return false;
  }
}

hal::GrabStatus V4l2StereoCamera::lose(std::chrono::nanoseconds now) {
  ++stats_.device_losses;
  close_devices();
  backoff_.failed(now);
  return hal::GrabStatus::device_lost;
}

hal::GrabStatus V4l2StereoCamera::grab(hal::StereoFrame& frame) {
  if (!opened_) {
    last_error_ = "camera not open";
    return hal::GrabStatus::device_lost;
  }
  if (!streaming_) {
    const auto now = clock_.now();
    if (!backoff_.due(now)) return hal::GrabStatus::device_lost;
    if (!open_devices(last_error_)) {
      backoff_.failed(now);
      return hal::GrabStatus::device_lost;
    }
    backoff_.succeeded();
    ++stats_.reopens;
  }
  const auto deadline = clock_.now() + from_ms(params_.grab_timeout_ms);
  bool error_seen = false;  // POLLERR with nothing to dequeue: the stream is broken
  for (;;) {
    if (!drain(left_, Side::left) || !drain(right_, Side::right)) return lose(clock_.now());
    stats_.kernel_dropped_left = left_.kernel_dropped();
    stats_.kernel_dropped_right = right_.kernel_dropped();
    if (const auto pair = pairing_.take_newest_pair()) {
      if (!give_back_released()) return lose(clock_.now());
      const V4l2Buffer& l = left_.dequeued(pair->left.token);
      const V4l2Buffer& r = right_.dequeued(pair->right.token);
      const bool converted =
          convert_to_bgr(left_.format(), l.data, l.bytes_used, left_.width(), left_.height(),
                         left_.stride_bytes(), frame.left_bgr, last_error_) &&
          convert_to_bgr(right_.format(), r.data, r.bytes_used, right_.width(), right_.height(),
                         right_.stride_bytes(), frame.right_bgr, last_error_);
      if (!left_.requeue(pair->left.token, last_error_) ||
          !right_.requeue(pair->right.token, last_error_)) {
        return lose(clock_.now());
      }
      if (converted) {
        frame.left_stamp = pair->left.stamp;
        frame.right_stamp = pair->right.stamp;
        frame.sequence = ++sequence_;
        frame.exposure = exposure_;
        return hal::GrabStatus::ok;
      }
      ++stats_.conversion_errors;  // a corrupt MJPG frame: wait for the next pair
    }
    const auto remaining = deadline - clock_.now();
    if (remaining.count() <= 0) {
      ++stats_.timeouts;
      last_error_ = "no stereo pair within " + std::to_string(params_.grab_timeout_ms) + " ms";
      return hal::GrabStatus::timeout;
    }
    pollfd fds[2] = {{left_.fd(), POLLIN, 0}, {right_.fd(), POLLIN, 0}};
    const int timeout_ms =
        static_cast<int>(std::chrono::ceil<std::chrono::milliseconds>(remaining).count());
    const int n = ::poll(fds, 2, timeout_ms);
    if (n < 0 && errno != EINTR) {
      last_error_ = std::string("poll on the cameras: ") + std::strerror(errno);
      return lose(clock_.now());
    }
    const bool broken = std::any_of(std::begin(fds), std::end(fds), [](const pollfd& p) {
      return (p.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0;
    });
    if (broken) {
      // V4L2 also raises POLLERR when no buffer is queued; one more drain tells the two apart.
      if (error_seen) {
        last_error_ = "camera " +
                      ((fds[0].revents & (POLLERR | POLLHUP | POLLNVAL)) != 0 ? left_.device()
                                                                              : right_.device()) +
                      ": stream error (POLLERR)";
        return lose(clock_.now());
      }
      error_seen = true;
    } else {
      error_seen = false;
    }
  }
}

}  // namespace rovctl::drivers
