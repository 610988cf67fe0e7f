// The real V4L2 ioctl: ::ioctl, retried when a signal interrupts it.
#include "drivers/v4l2/v4l2_ioctl.hpp"

#include <sys/ioctl.h>

#include <cerrno>

namespace rovctl::drivers {

namespace {

class SystemV4l2Ioctl final : public V4l2Ioctl {
 public:
  int call(int fd, unsigned long request, void* arg) override {
    int r = 0;
    do {
      r = ::ioctl(fd, request, arg);
    } while (r == -1 && errno == EINTR);
    return r;
  }
};

}  // namespace

V4l2Ioctl& system_v4l2_ioctl() {
  static SystemV4l2Ioctl instance;
  return instance;
}

}  // namespace rovctl::drivers
