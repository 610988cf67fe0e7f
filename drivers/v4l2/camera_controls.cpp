// Exposure, gain and white balance through VIDIOC_QUERYCTRL, VIDIOC_S_CTRL and VIDIOC_G_CTRL.
// Manual exposure is switched on before the exposure time is set: UVC cameras refuse (or
// ignore) V4L2_CID_EXPOSURE_ABSOLUTE while their auto exposure owns it, and likewise the
// white-balance temperature while auto white balance is on.
#include "drivers/v4l2/camera_controls.hpp"

#include <linux/videodev2.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace rovctl::drivers {

namespace {

constexpr int kExposureUnitUs = 100;  // V4L2_CID_EXPOSURE_ABSOLUTE counts 100 us

std::string ms_text(int units_100us) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", units_100us * kExposureUnitUs / 1000.0);
  return buf;
}

std::string range_text(const v4l2_queryctrl& q, std::string (*show)(int)) {
  return show(q.minimum) + " to " + show(q.maximum);
}

std::string plain(int v) { return std::to_string(v); }
std::string kelvin(int v) { return std::to_string(v) + " K"; }

class Controls {
 public:
  Controls(V4l2Ioctl& io, int fd, CameraControlReport& report) : io_(io), fd_(fd), r_(report) {}

  // Present and not disabled.
  bool query(std::uint32_t id, v4l2_queryctrl& q) {
    q = v4l2_queryctrl{};
    q.id = id;
    return io_.call(fd_, VIDIOC_QUERYCTRL, &q) == 0 && (q.flags & V4L2_CTRL_FLAG_DISABLED) == 0;
  }
  bool set(std::uint32_t id, int value, std::string& why) {
    v4l2_control c{};
    c.id = id;
    c.value = value;
    if (io_.call(fd_, VIDIOC_S_CTRL, &c) == 0) return true;
    why = std::string("VIDIOC_S_CTRL: ") + std::strerror(errno);
    return false;
  }
  bool get(std::uint32_t id, int& value) {
    v4l2_control c{};
    c.id = id;
    if (io_.call(fd_, VIDIOC_G_CTRL, &c) != 0) return false;
    value = c.value;
    return true;
  }
  void line(ControlLevel level, std::string text) { r_.lines.push_back({level, std::move(text)}); }
  CameraControlReport& report() { return r_; }

 private:
  V4l2Ioctl& io_;
  int fd_;
  CameraControlReport& r_;
};

// Sets a ranged control after checking the range; reports set against read back. False when
// the value is refused (out of range, or the camera rejects it).
bool set_ranged(Controls& c, std::uint32_t id, const char* what, const char* key, int value,
                std::string (*show)(int), int* read_back) {
  v4l2_queryctrl q;
  if (!c.query(id, q)) {
    c.line(ControlLevel::warn, std::string(what) + ": the camera has no such control; " + key +
                                   " " + show(value) + " is not set, the camera keeps its own");
    return true;
  }
  if (value < q.minimum || value > q.maximum) {
    c.line(ControlLevel::fail, std::string(what) + ": " + key + " " + show(value) +
                                   " is outside what the camera offers (" + range_text(q, show) +
                                   "): refused");
    return false;
  }
  std::string why;
  if (!c.set(id, value, why)) {
    c.line(ControlLevel::fail, std::string(what) + ": the camera refused " + key + " " +
                                   show(value) + " (" + why + ")");
    return false;
  }
  int got = value;
  if (!c.get(id, got)) {
    c.line(ControlLevel::warn,
           std::string(what) + ": " + show(value) + " set, not read back (VIDIOC_G_CTRL failed)");
    return true;
  }
  if (read_back != nullptr) *read_back = got;
  const std::string text =
      std::string(what) + ": " + show(value) + " set, " + show(got) + " read back";
  c.line(got == value ? ControlLevel::pass : ControlLevel::warn,
         got == value ? text : text + " (the camera uses what it reads back)");
  return true;
}

bool apply_exposure(Controls& c, const CameraControlSettings& s) {
  v4l2_queryctrl mode;
  const int units = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(s.exposure_time_us) / kExposureUnitUs)));
  if (!c.query(V4L2_CID_EXPOSURE_AUTO, mode)) {
    c.line(
        ControlLevel::warn,
        s.auto_exposure
            ? std::string("exposure: the camera has no auto-exposure control; it exposes as "
                          "it likes")
            : "exposure: the camera has no auto-exposure control; camera.v4l2.exposure_time_us " +
                  ms_text(units) + " is not set and the smear budget is not enforced");
    return true;
  }
  std::string why;
  if (s.auto_exposure) {
    // UVC cameras offer aperture priority as their auto mode, others full auto.
    if (!c.set(V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_AUTO, why) &&
        !c.set(V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_APERTURE_PRIORITY, why)) {
      c.line(ControlLevel::warn, "exposure: could not turn auto exposure on (" + why + ")");
      return true;
    }
    c.line(ControlLevel::pass, "exposure: auto (frames carry no exposure time)");
    return true;
  }
  if (!c.set(V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL, why)) {
    c.line(ControlLevel::fail, "exposure: the camera refused manual exposure (" + why +
                                   "): camera.v4l2.auto_exposure false cannot be honoured");
    return false;
  }
  int got = 0;
  const std::size_t before = c.report().lines.size();
  if (!set_ranged(c, V4L2_CID_EXPOSURE_ABSOLUTE, "exposure", "camera.v4l2.exposure_time_us", units,
                  ms_text, &got)) {
    return false;
  }
  if (got > 0) c.report().exposure = std::chrono::microseconds(got * kExposureUnitUs);
  if (c.report().lines.size() > before && units * kExposureUnitUs != s.exposure_time_us) {
    c.report().lines.back().text +=
        " (" + std::to_string(s.exposure_time_us) + " us rounded to the camera's 100 us unit)";
  }
  return true;
}

bool apply_white_balance(Controls& c, const CameraControlSettings& s) {
  v4l2_queryctrl q;
  const bool has_auto = c.query(V4L2_CID_AUTO_WHITE_BALANCE, q);
  std::string why;
  if (s.white_balance == "auto") {
    if (has_auto && !c.set(V4L2_CID_AUTO_WHITE_BALANCE, 1, why)) {
      c.line(ControlLevel::warn,
             "white balance: could not turn auto white balance on (" + why + ")");
      return true;
    }
    c.line(ControlLevel::pass, "white balance: auto");
    return true;
  }
  if (!has_auto) {
    c.line(ControlLevel::warn,
           "white balance: the camera has no auto-white-balance control; camera.v4l2."
           "white_balance lock is not applied");
    return true;
  }
  if (!c.set(V4L2_CID_AUTO_WHITE_BALANCE, 0, why)) {
    c.line(ControlLevel::fail, "white balance: the camera refused to lock it (" + why + ")");
    return false;
  }
  if (s.white_balance_temperature_k > 0) {
    return set_ranged(c, V4L2_CID_WHITE_BALANCE_TEMPERATURE, "white balance",
                      "camera.v4l2.white_balance_temperature_k", s.white_balance_temperature_k,
                      kelvin, nullptr);
  }
  int now = 0;
  c.line(ControlLevel::pass, c.query(V4L2_CID_WHITE_BALANCE_TEMPERATURE, q) &&
                                     c.get(V4L2_CID_WHITE_BALANCE_TEMPERATURE, now)
                                 ? "white balance: locked at the camera's current " + kelvin(now)
                                 : std::string("white balance: locked"));
  return true;
}

}  // namespace

const char* to_string(ControlLevel level) {
  switch (level) {
    case ControlLevel::pass:
      return "PASS";
    case ControlLevel::warn:
      return "WARN";
    case ControlLevel::fail:
      return "FAIL";
  }
  return "?";
}

bool CameraControlReport::refused() const {
  return std::any_of(lines.begin(), lines.end(),
                     [](const ControlReportLine& l) { return l.level == ControlLevel::fail; });
}

bool apply_camera_controls(V4l2Ioctl& io, int fd, const CameraControlSettings& settings,
                           CameraControlReport& report) {
  report = CameraControlReport{};
  Controls c(io, fd, report);
  bool ok = apply_exposure(c, settings);
  if (settings.gain >= 0) {
    ok = set_ranged(c, V4L2_CID_GAIN, "gain", "camera.v4l2.gain", settings.gain, plain, nullptr) &&
         ok;
  }
  ok = apply_white_balance(c, settings) && ok;
  return ok;
}

}  // namespace rovctl::drivers
