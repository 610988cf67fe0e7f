// The camera controls rovctl sets at open: auto exposure on or off, the exposure time, the gain
// and the white-balance lock, each queried for presence and range, set, read back and reported
// (what was asked against what the camera says it uses).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "drivers/v4l2/v4l2_ioctl.hpp"

namespace rovctl::drivers {

struct CameraControlSettings {
  bool auto_exposure = true;           // off: exposure_time_us is set (V4L2_EXPOSURE_MANUAL)
  int exposure_time_us = 4000;         // used when auto_exposure is off; the camera works in 100 us
  int gain = -1;                       // V4L2_CID_GAIN in the camera's own units; -1 leaves it
  std::string white_balance = "auto";  // auto | lock (auto white balance off)
  int white_balance_temperature_k = 0;  // with lock: the temperature; 0 locks the current one
};

enum class ControlLevel { pass, warn, fail };
const char* to_string(ControlLevel level);  // "PASS", "WARN", "FAIL"

struct ControlReportLine {
  ControlLevel level = ControlLevel::pass;
  std::string text;  // "exposure: 4.0 ms set, 4.0 ms read back"
};

struct CameraControlReport {
  std::vector<ControlReportLine> lines;
  // The exposure time the camera reads back in manual exposure; 0 when unknown (auto exposure,
  // no exposure control, or a read-back that failed).
  std::chrono::nanoseconds exposure{0};
  bool refused() const;  // a FAIL line: the camera cannot honour the settings
};

// Applies `settings` to the open device `fd` through `io`. A control the camera lacks is a WARN
// (the camera keeps its own setting); a value outside the camera's range is refused (a FAIL
// line naming the key, the value and the camera's range, nothing of it set): the pilot chose the
// exposure from the smear budget and the gain and white balance for the water, and a camera
// that silently used something else would fly with a different image than the one tested.
// Returns false when anything was refused; `report` holds every line either way.
bool apply_camera_controls(V4l2Ioctl& io, int fd, const CameraControlSettings& settings,
                           CameraControlReport& report);

}  // namespace rovctl::drivers
