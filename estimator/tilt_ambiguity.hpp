// The pose three spheres seen from afar cannot tell from another: their triangle tilted the other
// way about the line of sight. The estimator refits from it to learn whether the images can.
#pragma once

#include <Eigen/Geometry>

#include "hal/model/marker_model.hpp"

namespace rovctl::estimator {

// T_cl_marker with the spheres' triangle turned about its centroid so that its normal is mirrored
// about the line of sight from the left camera: the same image in orthographic projection, and
// the nearest other minimum of any fit on the spheres' images under perspective. T itself when
// the triangle faces the camera squarely or the marker has fewer than three spheres.
Eigen::Isometry3d mirrored_tilt(const Eigen::Isometry3d& T_cl_marker,
                                const hal::MarkerModel& marker);

}  // namespace rovctl::estimator
