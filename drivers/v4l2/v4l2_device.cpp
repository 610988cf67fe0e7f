// V4L2 capture through the kernel API: QUERYCAP, ENUM_FMT, S_FMT, S_PARM, the camera controls,
// REQBUFS/QUERYBUF/mmap, QBUF/DQBUF and STREAMON, with the device named in every error.
#include "drivers/v4l2/v4l2_device.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <utility>

namespace rovctl::drivers {

namespace {

std::string errno_text(const char* call) { return std::string(call) + ": " + std::strerror(errno); }

}  // namespace

std::string resolve_video_device(const std::string& device) {
  if (device.find('/') != std::string::npos) return device;
  for (const char* dir : {"/dev/rovctl/", "/dev/v4l/by-id/", "/dev/v4l/by-path/", "/dev/"}) {
    std::error_code ec;
    const std::string candidate = std::string(dir) + device;
    if (std::filesystem::exists(candidate, ec)) return candidate;
  }
  return device;
}

V4l2Device::V4l2Device(V4l2DeviceConfig config, V4l2Ioctl& io)
    : config_(std::move(config)), io_(io) {}

V4l2Device::~V4l2Device() { close(); }

bool V4l2Device::fail(std::string& error, const std::string& what) {
  std::string name = "camera " + config_.device;
  if (!path_.empty() && path_ != config_.device) name += " (" + path_ + ")";
  error = name + ": " + what;
  close();
  return false;
}

bool V4l2Device::open(std::string& error) {
  close();
  path_ = resolve_video_device(config_.device);
  if (path_.find('/') == std::string::npos) {
    path_.clear();
    return fail(error, "no such device (looked for /dev/rovctl/" + config_.device +
                           ", /dev/v4l/by-id/" + config_.device + ", /dev/v4l/by-path/" +
                           config_.device + " and /dev/" + config_.device + ")");
  }
  fd_ = ::open(path_.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    if (errno == ENOENT) return fail(error, "no such device (is the camera plugged in?)");
    if (errno == EACCES) return fail(error, "permission denied (is the user in group 'video'?)");
    return fail(error, errno_text("open"));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISCHR(st.st_mode)) {
    return fail(error, "not a V4L2 device (not a character device)");
  }
  v4l2_capability cap{};
  if (io_.call(fd_, VIDIOC_QUERYCAP, &cap) != 0) {
    return fail(error, "not a V4L2 device (" + errno_text("VIDIOC_QUERYCAP") + ")");
  }
  card_ = reinterpret_cast<const char*>(cap.card);
  const std::uint32_t caps =
      (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? cap.device_caps : cap.capabilities;
  if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0) {
    return fail(error, "\"" + card_ +
                           "\" is not a video capture node (a metadata node? use the camera's "
                           "index-0 node)");
  }
  if ((caps & V4L2_CAP_STREAMING) == 0) {
    return fail(error, "\"" + card_ + "\" does not support streaming I/O (MMAP)");
  }
  if (!negotiate(error)) return false;
  if (!apply_camera_controls(io_, fd_, config_.controls, controls_)) {
    std::string refused;
    for (const ControlReportLine& l : controls_.lines) {
      if (l.level == ControlLevel::fail) refused += (refused.empty() ? "" : "; ") + l.text;
    }
    return fail(error, refused);
  }
  if (!map_buffers(error)) return false;
  v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (io_.call(fd_, VIDIOC_STREAMON, &type) != 0) return fail(error, errno_text("VIDIOC_STREAMON"));
  streaming_ = true;
  have_sequence_ = false;
  return true;
}

bool V4l2Device::negotiate(std::string& error) {
  std::vector<std::uint32_t> offered;
  for (std::uint32_t i = 0;; ++i) {
    v4l2_fmtdesc desc{};
    desc.index = i;
    desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (io_.call(fd_, VIDIOC_ENUM_FMT, &desc) != 0) break;
    offered.push_back(desc.pixelformat);
  }
  const auto chosen = choose_pixel_format(offered, config_.preferred);
  if (!chosen) {
    std::string list;
    for (std::uint32_t f : offered) list += (list.empty() ? "" : ", ") + fourcc_to_string(f);
    return fail(error,
                "offers neither YUYV nor MJPG (offers: " + (list.empty() ? "none" : list) + ")");
  }
  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  fmt.fmt.pix.width = static_cast<std::uint32_t>(config_.width);
  fmt.fmt.pix.height = static_cast<std::uint32_t>(config_.height);
  fmt.fmt.pix.pixelformat = fourcc_of(*chosen);
  fmt.fmt.pix.field = V4L2_FIELD_NONE;
  if (io_.call(fd_, VIDIOC_S_FMT, &fmt) != 0) {
    return fail(error, errno_text("VIDIOC_S_FMT") + " (" + fourcc_to_string(fourcc_of(*chosen)) +
                           " " + std::to_string(config_.width) + "x" +
                           std::to_string(config_.height) + ")");
  }
  // The driver adjusts what it cannot do; a different size would not match the calibration.
  const auto got = pixel_format_from_fourcc(fmt.fmt.pix.pixelformat);
  if (!got || static_cast<int>(fmt.fmt.pix.width) != config_.width ||
      static_cast<int>(fmt.fmt.pix.height) != config_.height) {
    return fail(error, "does not offer " + fourcc_to_string(fourcc_of(*chosen)) + " " +
                           std::to_string(config_.width) + "x" + std::to_string(config_.height) +
                           " (the driver proposes " + fourcc_to_string(fmt.fmt.pix.pixelformat) +
                           " " + std::to_string(fmt.fmt.pix.width) + "x" +
                           std::to_string(fmt.fmt.pix.height) + ")");
  }
  format_ = *got;
  width_ = config_.width;
  height_ = config_.height;
  stride_bytes_ = fmt.fmt.pix.bytesperline;

  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  fps_ = 0.0;
  if (io_.call(fd_, VIDIOC_G_PARM, &parm) == 0 &&
      (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) != 0) {
    parm.parm.capture.timeperframe.numerator = 1;
    parm.parm.capture.timeperframe.denominator = static_cast<std::uint32_t>(config_.fps);
    // Not every driver can set the rate; the frames' own stamps remain authoritative.
    if (io_.call(fd_, VIDIOC_S_PARM, &parm) == 0 && parm.parm.capture.timeperframe.numerator != 0) {
      fps_ = static_cast<double>(parm.parm.capture.timeperframe.denominator) /
             parm.parm.capture.timeperframe.numerator;
    }
  }
  return true;
}

bool V4l2Device::map_buffers(std::string& error) {
  v4l2_requestbuffers req{};
  req.count = static_cast<std::uint32_t>(config_.buffer_count);
  req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  if (io_.call(fd_, VIDIOC_REQBUFS, &req) != 0) return fail(error, errno_text("VIDIOC_REQBUFS"));
  if (req.count < 2) {
    return fail(error, "the driver granted " + std::to_string(req.count) +
                           " capture buffer(s); at least 2 are needed");
  }
  buffers_.assign(req.count, Mapping{});
  dequeued_.assign(req.count, V4l2Buffer{});
  for (std::uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    buf.index = i;
    if (io_.call(fd_, VIDIOC_QUERYBUF, &buf) != 0) {
      return fail(error, errno_text("VIDIOC_QUERYBUF"));
    }
    void* start = ::mmap(nullptr, buf.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_,
                         static_cast<off_t>(buf.m.offset));
    if (start == MAP_FAILED) return fail(error, errno_text("mmap"));
    buffers_[i] = Mapping{start, buf.length};
  }
  for (std::uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    buf.index = i;
    if (io_.call(fd_, VIDIOC_QBUF, &buf) != 0) return fail(error, errno_text("VIDIOC_QBUF"));
  }
  return true;
}

void V4l2Device::close() {
  if (fd_ >= 0 && streaming_) {
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    io_.call(fd_, VIDIOC_STREAMOFF, &type);  // fails harmlessly on an unplugged device
  }
  streaming_ = false;
  for (const Mapping& m : buffers_) {
    if (m.start != nullptr) ::munmap(m.start, m.length);
  }
  if (fd_ >= 0 && !buffers_.empty()) {
    v4l2_requestbuffers req{};
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    io_.call(fd_, VIDIOC_REQBUFS, &req);
  }
  buffers_.clear();
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

DequeueStatus V4l2Device::dequeue(V4l2Buffer& out, std::string& error) {
  if (fd_ < 0) {
    error = "camera " + config_.device + ": not open";
    return DequeueStatus::lost;
  }
  for (;;) {
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    if (io_.call(fd_, VIDIOC_DQBUF, &buf) != 0) {
      if (errno == EAGAIN) return DequeueStatus::empty;
      // ENODEV: unplugged; EIO/EINVAL and the rest: the stream is broken. A reopen cures both.
      error = "camera " + config_.device + ": " + errno_text("VIDIOC_DQBUF");
      return DequeueStatus::lost;
    }
    if (buf.index >= buffers_.size()) {
      error = "camera " + config_.device + ": driver returned buffer index " +
              std::to_string(buf.index) + " of " + std::to_string(buffers_.size());
      return DequeueStatus::lost;
    }
    if (have_sequence_ && buf.sequence > last_sequence_ + 1) {
      kernel_dropped_ += buf.sequence - last_sequence_ - 1;
    }
    have_sequence_ = true;
    last_sequence_ = buf.sequence;
    if ((buf.flags & V4L2_BUF_FLAG_ERROR) != 0 || buf.bytesused == 0) {
      ++corrupt_buffers_;
      if (!requeue(static_cast<int>(buf.index), error)) return DequeueStatus::lost;
      continue;
    }
    out.index = static_cast<int>(buf.index);
    out.data = static_cast<const std::uint8_t*>(buffers_[buf.index].start);
    out.bytes_used = buf.bytesused;
    out.monotonic_stamp =
        (buf.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
    out.stamp = std::chrono::seconds(buf.timestamp.tv_sec) +
                std::chrono::microseconds(buf.timestamp.tv_usec);
    out.sequence = buf.sequence;
    dequeued_[buf.index] = out;
    return DequeueStatus::frame;
  }
}

bool V4l2Device::requeue(int index, std::string& error) {
  if (fd_ < 0 || index < 0 || static_cast<std::size_t>(index) >= buffers_.size()) {
    error = "camera " + config_.device + ": cannot requeue buffer " + std::to_string(index);
    return false;
  }
  v4l2_buffer buf{};
  buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  buf.memory = V4L2_MEMORY_MMAP;
  buf.index = static_cast<std::uint32_t>(index);
  if (io_.call(fd_, VIDIOC_QBUF, &buf) != 0) {
    error = "camera " + config_.device + ": " + errno_text("VIDIOC_QBUF");
    return false;
  }
  return true;
}

std::string V4l2Device::summary() const {
  std::ostringstream s;
  s << config_.device;
  if (!path_.empty() && path_ != config_.device) s << " (" << path_ << ")";
  if (!card_.empty()) s << " \"" << card_ << "\"";
  if (fd_ >= 0) {
    s << ", " << fourcc_to_string(fourcc_of(format_)) << " " << width_ << "x" << height_;
    if (fps_ > 0.0) s << " @ " << fps_ << " fps";
    s << ", " << buffers_.size() << " buffers";
  }
  return s.str();
}

}  // namespace rovctl::drivers
