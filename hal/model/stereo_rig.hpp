// The stereo rig: two cameras and the pose of the left camera in the right one, exactly as
// cv::stereoCalibrate reports it (x_cr = R * x_cl + T). Not assumed rectified.
#pragma once

#include <Eigen/Geometry>

#include "hal/model/camera_model.hpp"

namespace rovctl::hal {

struct StereoRig {
  CameraModel left;
  CameraModel right;
  Eigen::Isometry3d T_cr_cl = Eigen::Isometry3d::Identity();

  double baseline_m() const { return T_cr_cl.translation().norm(); }
};

// A rig of two identical cameras side by side, `baseline_m` apart, toed in by `toe_in_rad` each.
StereoRig make_parallel_rig(const CameraModel& camera, double baseline_m, double toe_in_rad = 0.0);

}  // namespace rovctl::hal
