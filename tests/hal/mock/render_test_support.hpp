// Shared helpers for the renderer tests: a distorted camera like the shipped rig's, and the marker
// straight ahead of it.
#pragma once

#include <Eigen/Geometry>

#include "hal/model/camera_model.hpp"
#include "hal/model/pose.hpp"

namespace rovctl::hal::mock::test {

inline CameraModel distorted_camera() {
  CameraModel c;
  c.fx_px = 552.0;
  c.fy_px = 549.0;
  c.cx_px = 331.5;
  c.cy_px = 236.0;
  c.k1 = -0.12;
  c.k2 = 0.05;
  return c;
}

inline Eigen::Isometry3d ahead(double z) {
  return make_pose({0.0, 0.0, z}, Eigen::Quaterniond::Identity());
}

}  // namespace rovctl::hal::mock::test
