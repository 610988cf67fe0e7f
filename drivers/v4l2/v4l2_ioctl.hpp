// The seam between the V4L2 driver and the kernel: every ioctl the driver issues goes through a
// V4l2Ioctl, so tests can stand a fake device (controls with ranges, missing controls, read-back
// that differs) where a camera would be.
#pragma once

namespace rovctl::drivers {

class V4l2Ioctl {
 public:
  virtual ~V4l2Ioctl() = default;
  // As ::ioctl: 0 on success, -1 with errno set on failure.
  virtual int call(int fd, unsigned long request, void* arg) = 0;
};

// The kernel's ::ioctl, retried on EINTR. One shared instance: it has no state.
V4l2Ioctl& system_v4l2_ioctl();

}  // namespace rovctl::drivers
