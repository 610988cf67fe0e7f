// Improvement beyond the paper: Gauss-Newton refinement of a pose on the blobs' centroids. The
// model predicts each centroid exactly (the centroid of the distorted image of the sphere's rim),
// so the result is sub-pixel although a sphere's image centre is not its centre's projection.
#pragma once

#include <Eigen/Geometry>

#include "estimator/blob_seeder.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::estimator {

// How well a refined pose fits: the residual and the pose's covariance for that residual.
struct RefineReport {
  int centroids = 0;    // whole blobs used (of 6)
  double rms_px = 0.0;  // per centroid (u, v)
  // A centroid coordinate's noise: rms_px / sqrt(2), at least kCentroidNoisePx.
  double sigma_px = 0.0;
  // The same as the residual measures it: its sum of squares over the 2 n - 6 coordinates the
  // pose's six parameters leave free, at least kCentroidNoisePx.
  double sigma_free_px = 0.0;
  // Covariance of the pose's error, rotation vector (rad) then translation (m), from the
  // Gauss-Newton normal equations with sigma_px.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

class PoseRefiner {
 public:
  PoseRefiner(const hal::StereoRig& rig, const hal::MarkerModel& marker);

  // Refines T_cl_marker in place. False (pose unchanged) when fewer than four whole blobs are
  // seen or the fit leaves more than max_rms_px of residual.
  bool refine(const BlobSet& blobs, Eigen::Isometry3d& T_cl_marker, double max_rms_px = 1.5,
              RefineReport* report = nullptr) const;

  // Centroid of the sphere's silhouette in distorted pixels; false behind the camera.
  static bool silhouette_centroid(const hal::CameraModel& camera, const Eigen::Vector3d& centre_m,
                                  double radius_m, Eigen::Vector2d& uv_px);

  static constexpr double kCentroidNoisePx = 0.25;  // per coordinate, the least credited

 private:
  static constexpr int kMaxResiduals = 12;  // 2 views x 3 spheres x (u, v)
  using Residuals = Eigen::Matrix<double, kMaxResiduals, 1>;
  bool residuals(const BlobSet& blobs, const Eigen::Isometry3d& T, Residuals& r) const;

  hal::StereoRig rig_;
  hal::MarkerModel marker_;
};

}  // namespace rovctl::estimator
