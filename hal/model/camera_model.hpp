// A pinhole camera with OpenCV's distortion model (k1, k2, p1, p2, k3): what one camera is.
// project() is inline because the fitness function calls it millions of times a second.
#pragma once

#include <Eigen/Core>
#include <opencv2/core/types.hpp>

namespace rovctl::hal {

struct CameraModel {
  double fx_px = 600.0;
  double fy_px = 600.0;
  double cx_px = 320.0;
  double cy_px = 240.0;
  double k1 = 0.0, k2 = 0.0, p1 = 0.0, p2 = 0.0, k3 = 0.0;
  int width_px = 640;
  int height_px = 480;

  // Projects a point in this camera's frame (OpenCV: x right, y down, z forward) to distorted
  // pixel coordinates. Returns false behind the camera.
  bool project(const Eigen::Vector3d& p_cam_m, Eigen::Vector2d& uv_px) const {
    if (p_cam_m.z() <= 1e-6) return false;
    distort(p_cam_m.x() / p_cam_m.z(), p_cam_m.y() / p_cam_m.z(), uv_px.x(), uv_px.y());
    return true;
  }

  // Normalised image coordinates (x/z, y/z) to distorted pixel coordinates: the one forward
  // distortion of the project (the fitness calls it without the division); unproject() inverts it.
  void distort(double x, double y, double& u_px, double& v_px) const {
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x);
    const double yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y;
    u_px = fx_px * xd + cx_px;
    v_px = fy_px * yd + cy_px;
  }

  // The unit-z ray (x, y, 1) in the camera frame through a distorted pixel (iterative inverse).
  Eigen::Vector3d unproject(const Eigen::Vector2d& uv_px) const;

  bool has_distortion() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0 || k3 != 0; }
  cv::Size image_size() const { return {width_px, height_px}; }
};

}  // namespace rovctl::hal
