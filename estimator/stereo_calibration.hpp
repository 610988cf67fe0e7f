// Reads the stereo rig from OpenCV's stereo calibration YAML (cv::FileStorage after
// cv::stereoCalibrate: K1, D1, K2, D2, R, T and the image size) and writes it back.
#pragma once

#include <limits>
#include <string>

#include "hal/model/stereo_rig.hpp"

namespace cv {
class FileStorage;
}

namespace rovctl::estimator {

// Throws std::invalid_argument naming the file, the line (where the key is given) and the missing,
// malformed or repeated key.
hal::StereoRig load_stereo_calibration(const std::string& file);
// The 1-based line where `file` gives the top-level `key`, 0 when it does not.
int calibration_key_line(const std::string& file, const std::string& key);
void save_stereo_calibration(const std::string& file, const hal::StereoRig& rig);
// The rig's K1, D1, K2, D2, R and T into an open FileStorage, as the loader reads them: what
// save_stereo_calibration() writes, and `rovctl calibrate` with its figures beside them.
void write_stereo_rig(cv::FileStorage& fs, const hal::StereoRig& rig);

// The figures `rovctl calibrate` records beside the rig; NaN / 0 / empty where the file has none.
struct CalibrationFigures {
  double rms_reprojection_px = std::numeric_limits<double>::quiet_NaN();
  double epipolar_rms_px = std::numeric_limits<double>::quiet_NaN();
  int views_used = 0;
  std::string calibrated_utc;
};
CalibrationFigures load_calibration_figures(const std::string& file);

}  // namespace rovctl::estimator
