// A V4L2 device without a camera: the controls of a camera (each with its range, step and
// value, present or not), answering VIDIOC_QUERYCTRL, VIDIOC_S_CTRL and VIDIOC_G_CTRL through the
// same V4l2Ioctl seam the driver calls the kernel through. A control can read back other than
// what was set (a camera that rounds to its own step) or refuse a value (EINVAL, as UVC does).
#pragma once

#include <linux/videodev2.h>

#include <cerrno>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "drivers/v4l2/v4l2_ioctl.hpp"

namespace rovctl::drivers {

struct FakeControl {
  int minimum = 0;
  int maximum = 0;
  int step = 1;
  int value = 0;
  std::set<int> refused;              // values S_CTRL fails with EINVAL
  std::function<int(int)> read_back;  // what G_CTRL reports for a set value; none: as set
};

class FakeV4l2Device final : public V4l2Ioctl {
 public:
  // A UVC-like camera: exposure menu (manual and aperture priority, no full auto), exposure
  // 0.3-20 ms in 100 us, gain 0-255, auto white balance and 2800-6500 K.
  static FakeV4l2Device uvc_camera() {
    FakeV4l2Device d;
    d.controls[V4L2_CID_EXPOSURE_AUTO] = {0,
                                          3,
                                          1,
                                          V4L2_EXPOSURE_APERTURE_PRIORITY,
                                          {V4L2_EXPOSURE_AUTO, V4L2_EXPOSURE_SHUTTER_PRIORITY},
                                          {}};
    d.controls[V4L2_CID_EXPOSURE_ABSOLUTE] = {3, 200, 1, 156, {}, {}};
    d.controls[V4L2_CID_GAIN] = {0, 255, 1, 64, {}, {}};
    d.controls[V4L2_CID_AUTO_WHITE_BALANCE] = {0, 1, 1, 1, {}, {}};
    d.controls[V4L2_CID_WHITE_BALANCE_TEMPERATURE] = {2800, 6500, 10, 4600, {}, {}};
    return d;
  }

  int call(int /*fd*/, unsigned long request, void* arg) override {
    if (request == VIDIOC_QUERYCTRL) {
      auto* q = static_cast<v4l2_queryctrl*>(arg);
      const auto it = controls.find(q->id);
      if (it == controls.end()) return fail(EINVAL);
      q->minimum = it->second.minimum;
      q->maximum = it->second.maximum;
      q->step = it->second.step;
      q->default_value = it->second.value;
      return 0;
    }
    if (request == VIDIOC_S_CTRL) {
      auto* c = static_cast<v4l2_control*>(arg);
      const auto it = controls.find(c->id);
      if (it == controls.end()) return fail(EINVAL);
      FakeControl& f = it->second;
      if (c->value < f.minimum || c->value > f.maximum || f.refused.count(c->value) != 0) {
        return fail(EINVAL);
      }
      sets.emplace_back(c->id, c->value);
      f.value = f.read_back ? f.read_back(c->value) : c->value;
      return 0;
    }
    if (request == VIDIOC_G_CTRL) {
      auto* c = static_cast<v4l2_control*>(arg);
      const auto it = controls.find(c->id);
      if (it == controls.end()) return fail(EINVAL);
      c->value = it->second.value;
      return 0;
    }
    return fail(ENOTTY);
  }

  int value(std::uint32_t id) const { return controls.at(id).value; }

  std::map<std::uint32_t, FakeControl> controls;
  std::vector<std::pair<std::uint32_t, int>> sets;  // every S_CTRL that succeeded, in order

 private:
  static int fail(int e) {
    errno = e;
    return -1;
  }
};

}  // namespace rovctl::drivers
