// The rim of a sphere as a camera sees it: the circle where the viewing cone from the camera's
// centre touches the sphere. Its projection is the sphere's silhouette (an ellipse, distorted by
// the lens), shared by the renderer's bounding boxes and the refiner's silhouette centroids.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace rovctl::hal {

struct SphereRim {
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  // in the camera frame
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX();       // orthonormal, across the viewing axis
  Eigen::Vector3d e2 = Eigen::Vector3d::UnitY();
  double radius_m = 0.0;

  // The rim point at angle phi (rad) around the viewing axis.
  Eigen::Vector3d point(double phi) const { return point(std::cos(phi), std::sin(phi)); }
  // The same, from the angle's cosine and sine: callers that walk fixed angles keep a table.
  Eigen::Vector3d point(double cos_phi, double sin_phi) const {
    return centre_m + radius_m * (cos_phi * e1 + sin_phi * e2);
  }
};

// The rim of a sphere of radius r centred at c (camera frame). False when the camera is inside or
// almost touching the sphere, or the sphere is not wholly in front of it.
bool sphere_rim(const Eigen::Vector3d& c, double r, SphereRim& rim);

}  // namespace rovctl::hal
