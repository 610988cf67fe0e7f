// Placing a rod in the camera frame and ordering it among the scene's other objects.
#include "hal/mock/rod.hpp"

#include <algorithm>

namespace rovctl::hal::mock {

Rod rod_in_camera(const Eigen::Isometry3d& T_cam_marker, const Eigen::Vector3d& centre_marker_m,
                  const Eigen::Vector3d& axis_marker, double radius_m, double half_length_m) {
  Rod r;
  r.centre_m = (T_cam_marker * centre_marker_m).cast<float>();
  r.axis = (T_cam_marker.linear() * axis_marker.normalized()).cast<float>();
  r.radius_m = static_cast<float>(radius_m);
  r.half_length_m = static_cast<float>(half_length_m);
  return r;
}

double rod_depth_m(const Rod& rod) {
  const Eigen::Vector3d c = rod.centre_m.cast<double>();
  const Eigen::Vector3d a = rod.axis.cast<double>();
  const double u = std::clamp(-c.dot(a), -static_cast<double>(rod.half_length_m),
                              static_cast<double>(rod.half_length_m));
  return (c + u * a).norm();
}

}  // namespace rovctl::hal::mock
