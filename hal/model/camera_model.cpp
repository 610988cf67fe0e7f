// Inverse of the distortion model, by fixed-point iteration (as cv::undistortPoints does).
#include "hal/model/camera_model.hpp"

namespace rovctl::hal {

Eigen::Vector3d CameraModel::unproject(const Eigen::Vector2d& uv_px) const {
  const double xd = (uv_px.x() - cx_px) / fx_px;
  const double yd = (uv_px.y() - cy_px) / fy_px;
  double x = xd, y = yd;
  for (int i = 0; i < 20; ++i) {
    const double r2 = x * x + y * y;
    const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double dx = 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x);
    const double dy = p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y;
    x = (xd - dx) / radial;
    y = (yd - dy) / radial;
  }
  return {x, y, 1.0};
}

}  // namespace rovctl::hal
