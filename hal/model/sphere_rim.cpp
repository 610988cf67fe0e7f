// The tangent circle of the cone from the origin to a sphere.
#include "hal/model/sphere_rim.hpp"

#include <Eigen/Geometry>

namespace rovctl::hal {

bool sphere_rim(const Eigen::Vector3d& c, double r, SphereRim& rim) {
  const double d = c.norm();
  if (d <= r * 1.05 || c.z() <= r) return false;
  const Eigen::Vector3d axis = c / d;
  rim.e1 = axis.unitOrthogonal();
  rim.e2 = axis.cross(rim.e1);
  rim.centre_m = c * (1.0 - r * r / (d * d));
  rim.radius_m = r * std::sqrt(d * d - r * r) / d;
  return true;
}

}  // namespace rovctl::hal
