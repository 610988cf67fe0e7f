// Exposure acts on linear light, so the 8-bit image is decoded, scaled and re-encoded through a
// 256-entry table built per frame: one lookup per byte.
#include "hal/mock/camera_response.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, NoisyCamera& n) {
  v.param("noise_gain", n.noise_gain,
          {"-", 0.0, 20.0, "multiplies the trial's image noise (sensor at high gain)"});
  v.param("jpeg_quality", n.jpeg_quality,
          {"-", 1, 100, "JPEG-like quality (IJG scaling of the standard quantisation tables)"});
  v.param("chroma_subsampling", n.chroma_subsampling,
          "compress colour at half resolution (4:2:0), as JPEG and MJPEG cameras do");
}

void describe(ParamVisitor& v, ExposureDrift& e) {
  v.param("gain_min", e.gain_min, {"-", 0.01, 1.0, "most under-exposed gain"});
  v.param("gain_max", e.gain_max, {"-", 1.0, 20.0, "most over-exposed gain (clips)"});
  v.param("period_s", e.period_s, {"s", 0.1, 3600.0, "period of the drift"});
  v.param("phase_deg", e.phase_deg,
          {"deg", -360.0, 360.0, "phase at time 0 (0: geometric mean, rising)"});
  v.param(
      "auto_exposure_ms", e.auto_exposure_ms,
      {"ms", 0.0, 1000.0,
       "exposure time of the cameras' auto exposure in this dim water (with "
       "camera.v4l2.auto_exposure true; false exposes camera.v4l2.exposure_time_us at gain 1)"});
  v.param("vibration_deg", e.vibration_deg,
          {"deg", 0.0, 10.0, "amplitude of the camera mount's vibration in yaw and pitch"});
  v.param("vibration_hz", e.vibration_hz,
          {"Hz", 0.0, 100.0, "frequency of the mount's yaw vibration (pitch: 1.37 times it)"});
}

Eigen::Matrix3d vibration_rotation(const ExposureDrift& e, double time_s) {
  const double a = e.vibration_deg * M_PI / 180.0;
  const double w = 2.0 * M_PI * e.vibration_hz * time_s;
  const double yaw = a * std::sin(w), pitch = a * std::sin(1.37 * w + 1.0);
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

double exposure_gain(const ExposureDrift& e, double time_s) {
  const double lo = std::log(e.gain_min), hi = std::log(e.gain_max);
  const double phase = 2.0 * M_PI * time_s / e.period_s + e.phase_deg * M_PI / 180.0;
  return std::exp(0.5 * (lo + hi) + 0.5 * (hi - lo) * std::sin(phase));
}

namespace {
double srgb_to_linear(double s) {
  return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}
double linear_to_srgb(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}
}  // namespace

ExposureResponse::ExposureResponse() {
  for (int i = 0; i < 256; ++i) to_linear_[i] = static_cast<float>(srgb_to_linear(i / 255.0));
  for (int i = 0; i < 4096; ++i) {
    to_srgb8_[i] = static_cast<std::uint8_t>(
        std::clamp(std::lround(linear_to_srgb(i / 4095.0) * 255.0), 0L, 255L));
  }
}

void ExposureResponse::apply(double gain, cv::Mat& bgr) const {
  std::array<std::uint8_t, 256> table;
  const float g = static_cast<float>(gain);
  for (int i = 0; i < 256; ++i) {
    const int k = static_cast<int>(std::min(1.0f, to_linear_[i] * g) * 4095.0f + 0.5f);
    table[i] = to_srgb8_[k];
  }
  const int n = bgr.cols * bgr.channels();
  for (int v = 0; v < bgr.rows; ++v) {
    std::uint8_t* p = bgr.ptr<std::uint8_t>(v);
    for (int i = 0; i < n; ++i) p[i] = table[p[i]];
  }
}

}  // namespace rovctl::hal::mock
