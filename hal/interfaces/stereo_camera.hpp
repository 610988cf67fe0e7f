// StereoCamera: the interface every camera backend (V4L2, replay, mock) implements.
#pragma once

#include <chrono>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>

namespace rovctl::hal {

struct StereoFrame {
  cv::Mat left_bgr;                        // CV_8UC3, reused between grabs: backends write in place
  cv::Mat right_bgr;                       // CV_8UC3
  std::chrono::nanoseconds left_stamp{0};  // capture time, on the Clock the application runs on
  std::chrono::nanoseconds right_stamp{0};
  std::uint64_t sequence = 0;
  // How long both images were exposed; 0 when not known (auto exposure, a replay).
  std::chrono::nanoseconds exposure{0};
  bool exposure_known() const { return exposure.count() > 0; }
};

enum class GrabStatus { ok, timeout, device_lost, end_of_stream };
const char* to_string(GrabStatus s);

class StereoCamera {
 public:
  virtual ~StereoCamera() = default;
  // Opens the devices; returns false and fills `error` (naming the device) on failure.
  virtual bool open(std::string& error) = 0;
  // The newest stereo pair. Must not allocate once `frame` has the right size.
  virtual GrabStatus grab(StereoFrame& frame) = 0;
  virtual void close() = 0;
  virtual std::string name() const = 0;
};

}  // namespace rovctl::hal
