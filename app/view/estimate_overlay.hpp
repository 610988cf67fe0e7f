// The estimate drawn on the cameras' images: each sphere's silhouette where the estimated pose
// puts it, through the calibrated (distorted) camera, so the operator sees at a glance whether
// what the vehicle believes sits on what it sees.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "hal/model/camera_model.hpp"
#include "hal/model/marker_model.hpp"

namespace rovctl::app {

// Draws the marker's spheres at T_cam_marker on `image_bgr` (in place): solid outlines when
// `ok` (the estimate is trusted), dashed when it is only a partial view. Spheres behind the
// camera are skipped. Returns how many silhouettes were drawn.
int draw_estimate_overlay(cv::Mat& image_bgr, const hal::CameraModel& camera,
                          const hal::MarkerModel& marker, const Eigen::Isometry3d& T_cam_marker,
                          bool ok);

}  // namespace rovctl::app
