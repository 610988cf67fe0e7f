// Levenberg-damped Gauss-Newton over a left-multiplied rotation vector and a translation, with a
// forward-difference Jacobian (12 residuals x 6 parameters, fixed-size, allocation-free).
#include "estimator/pose_refiner.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "hal/model/pose.hpp"
#include "hal/model/sphere_rim.hpp"
#include "hal/model/unit_circle.hpp"

namespace rovctl::estimator {

PoseRefiner::PoseRefiner(const hal::StereoRig& rig, const hal::MarkerModel& marker)
    : rig_(rig), marker_(marker) {}

bool PoseRefiner::silhouette_centroid(const hal::CameraModel& camera, const Eigen::Vector3d& c,
                                      double r, Eigen::Vector2d& uv_px) {
  hal::SphereRim rim;
  if (!hal::sphere_rim(c, r, rim)) return false;
  constexpr int kRim = 32;
  static const hal::UnitCircle<kRim> around;
  Eigen::Vector2d first, prev, p;
  double area2 = 0.0, cx = 0.0, cy = 0.0;
  for (int k = 0; k <= kRim; ++k) {
    if (k < kRim) {
      if (!camera.project(rim.point(around[k].x(), around[k].y()), p)) return false;
      if (k == 0) first = p;
    } else {
      p = first;
    }
    if (k > 0) {  // shoelace over the polygon of projected rim points
      const double cross = prev.x() * p.y() - p.x() * prev.y();
      area2 += cross;
      cx += (prev.x() + p.x()) * cross;
      cy += (prev.y() + p.y()) * cross;
    }
    prev = p;
  }
  if (std::abs(area2) < 1e-9) return false;
  uv_px = Eigen::Vector2d(cx, cy) / (3.0 * area2);
  return true;
}

bool PoseRefiner::residuals(const BlobSet& blobs, const Eigen::Isometry3d& T, Residuals& r) const {
  r.setZero();
  const int n = static_cast<int>(std::min<std::size_t>(marker_.spheres.size(), 3));
  for (int view = 0; view < 2; ++view) {
    const hal::CameraModel& cam = view == 0 ? rig_.left : rig_.right;
    for (int i = 0; i < n; ++i) {
      const hal::MarkerSphere& s = marker_.spheres[i];
      const Blob& b = blobs[view][static_cast<int>(s.colour)];
      if (!b.valid || b.touches_border) continue;
      Eigen::Vector3d c = T * s.centre_marker_m;
      if (view == 1) c = rig_.T_cr_cl * c;
      Eigen::Vector2d uv;
      if (!silhouette_centroid(cam, c, s.radius_m, uv)) return false;
      r(view * 6 + i * 2) = uv.x() - b.u_px;
      r(view * 6 + i * 2 + 1) = uv.y() - b.v_px;
    }
  }
  return r.allFinite();
}

bool PoseRefiner::refine(const BlobSet& blobs, Eigen::Isometry3d& T_cl_marker, double max_rms_px,
                         RefineReport* report) const {
  int used = 0;
  const int n = static_cast<int>(std::min<std::size_t>(marker_.spheres.size(), 3));
  for (int view = 0; view < 2; ++view) {
    for (int i = 0; i < n; ++i) {
      const Blob& b = blobs[view][static_cast<int>(marker_.spheres[i].colour)];
      if (b.valid && !b.touches_border) ++used;
    }
  }
  if (used < 4) return false;
  Eigen::Isometry3d T = T_cl_marker;
  Residuals r0;
  if (!residuals(blobs, T, r0)) return false;
  Eigen::Matrix<double, kMaxResiduals, 6> J;
  auto jacobian = [&]() {
    constexpr double h = 1e-6;
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
      d(k) = h;
      Residuals rk;
      if (!residuals(blobs, hal::perturbed(T, d), rk)) return false;
      J.col(k) = (rk - r0) / h;
    }
    return true;
  };
  double lambda = 1e-3;
  // A rejected step (lambda raised) leaves T where it was, and with it J, so J is taken again
  // only where T moved: a third of the iterations on the seed-3 validation set are rejections.
  bool j_at_T = false;
  for (int iter = 0; iter < 15; ++iter) {
    if (!j_at_T && !jacobian()) return false;
    j_at_T = true;
    Eigen::Matrix<double, 6, 6> A = J.transpose() * J;
    const Eigen::Matrix<double, 6, 1> g = J.transpose() * r0;
    A.diagonal() *= 1.0 + lambda;
    A.diagonal().array() += 1e-12;
    const Eigen::Matrix<double, 6, 1> step = -A.ldlt().solve(g);
    if (!step.allFinite()) return false;
    const Eigen::Isometry3d candidate = hal::perturbed(T, step);
    Residuals r1;
    if (residuals(blobs, candidate, r1) && r1.squaredNorm() < r0.squaredNorm()) {
      T = candidate;
      r0 = r1;
      j_at_T = false;
      lambda = std::max(1e-6, lambda * 0.3);
      if (step.norm() < 1e-8) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e6) break;
    }
  }
  const double rms = std::sqrt(r0.squaredNorm() / used);  // per (u, v) pair
  if (report != nullptr) {
    report->centroids = used;
    report->rms_px = rms;
    // Per coordinate: rms / sqrt(2); never below the centroids' own noise (a quarter pixel).
    const double sigma_px = std::max(rms / std::sqrt(2.0), kCentroidNoisePx);
    report->sigma_px = sigma_px;
    // rms / sqrt(2) is the mean square over all 2 n coordinates, as if the fit had taken nothing
    // from them: with four centroids that is half the variance.
    report->sigma_free_px =
        std::max(std::sqrt(r0.squaredNorm() / (2.0 * used - 6.0)), kCentroidNoisePx);
    if (j_at_T || jacobian()) {
      const Eigen::Matrix<double, 6, 6> A = J.transpose() * J;
      report->covariance =
          sigma_px * sigma_px * A.ldlt().solve(Eigen::Matrix<double, 6, 6>::Identity());
    }
  }
  if (!(rms <= max_rms_px)) return false;
  T_cl_marker = T;
  return true;
}

}  // namespace rovctl::estimator
