// Reads the stereo rig from OpenCV's stereo calibration YAML (cv::FileStorage after
// cv::stereoCalibrate: K1, D1, K2, D2, R, T and the image size) and writes it back.
#pragma once

#include <string>

#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// Throws std::invalid_argument naming the file and the missing or malformed key.
hal::StereoRig load_stereo_calibration(const std::string& file);
void save_stereo_calibration(const std::string& file, const hal::StereoRig& rig);

}  // namespace rovctl::estimator
