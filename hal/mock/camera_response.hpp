// What the simulated camera's electronics do to the rendered 8-bit image, whatever the scene: a
// high gain with lossy compression (noisy) and an auto-exposure that drifts (exposure).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// A cheap camera at high gain streaming JPEG (an IP camera in a housing, or an MJPEG USB camera
// short of bandwidth): the noise grows with the gain, and 8x8-block DCT quantisation with 4:2:0
// chroma subsampling blurs colour edges and leaves block seams.
struct NoisyCamera {
  double noise_gain = 3.0;  // multiplies the trial's image noise (1-5 grey levels -> 3-15)
  int jpeg_quality = 50;    // IJG quality scaling of the JPEG Annex K tables
  bool chroma_subsampling = true;
};

void describe(ParamVisitor& v, NoisyCamera& n);

// The exposure scenario: a camera left on auto exposure in dim water on a vibrating mount. The
// exposure gain follows a slow sinusoid in log space between gain_min (under-exposed) and
// gain_max (over-exposed, highlights and bright colours clip), as an auto-exposure hunting under
// changing light does, and the auto exposure lasts auto_exposure_ms, smearing the marker as the
// mount turns. A manual exposure (camera.v4l2.auto_exposure false) holds the gain at 1 and
// exposes for camera.v4l2.exposure_time_us instead; the vibration is the same.
struct ExposureDrift {
  double gain_min = 0.3;
  double gain_max = 2.5;
  double period_s = 30.0;
  double phase_deg = 0.0;          // 0: starts at the geometric mean and rises first
  double auto_exposure_ms = 33.0;  // what the auto exposure settles on: the whole frame period
  // The camera mount's vibration: the rig turns in yaw and pitch by this amplitude, about the
  // left camera, at vibration_hz (pitch at 1.37 times it, out of phase, so the two never beat
  // in step). 1.5 deg at 8 Hz turns at up to 75 deg/s in yaw and 103 in pitch: beyond 1.35
  // sphere diameters of smear at 1.5 m through a 33 ms exposure, a third of one through 4 ms.
  double vibration_deg = 1.5;
  double vibration_hz = 8.0;
};

void describe(ParamVisitor& v, ExposureDrift& e);

double exposure_gain(const ExposureDrift& e, double time_s);
// The mount's rotation at `time_s`, as it turns what the left camera sees: p_cam' = R p_cam.
Eigen::Matrix3d vibration_rotation(const ExposureDrift& e, double time_s);

// Scales the light an 8-bit sRGB image records by `gain` (in linear light, clipping at white).
class ExposureResponse {
 public:
  ExposureResponse();
  // In place; no heap allocation.
  void apply(double gain, cv::Mat& bgr) const;

 private:
  std::array<float, 256> to_linear_{};
  std::array<std::uint8_t, 4096> to_srgb8_{};
};

}  // namespace rovctl::hal::mock
