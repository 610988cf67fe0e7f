// The occluders scenario's moving obstacle: a dark bar (a loose cable, a diver's fin) hanging in
// front of the station and sweeping to and fro across the marker, hiding spheres as it passes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/mock/rod.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// In the marker frame (x right, y down, z into the station). At 35 mm/s a 30 mm bar takes about
// two seconds to pass over a 40 mm sphere.
struct PassingBar {
  double in_front_of_marker_m = 0.2;  // the bar's axis is this far in front of the marker plane
  double radius_m = 0.015;
  double half_length_m = 1.5;
  double tilt_deg = 10.0;      // axis off the marker's y (vertical) axis, in the marker plane
  double sweep_min_m = -0.35;  // the bar's x sweeps between these
  double sweep_max_m = 0.35;
  double speed_mps = 0.035;  // along x, back and forth; at sweep_min_m at time 0
  Eigen::Vector3d albedo_rgb{0.03, 0.03, 0.035};  // dark, linear RGB
};

void describe(ParamVisitor& v, PassingBar& p);

// Where the bar's axis crosses the marker's x axis at `time_s` (a triangle wave).
double bar_x_m(const PassingBar& p, double time_s);

// The bar at `time_s`, seen from the camera at T_cam_marker.
Rod bar_in_camera(const PassingBar& p, const Eigen::Isometry3d& T_cam_marker, double time_s);

}  // namespace rovctl::hal::mock
