// A straight cylinder in the scene (a cable, a fin's edge, a strut of the station frame): where a
// camera ray meets it and whether it stands between a surface and a light.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace rovctl::hal::mock {

// In the camera frame.
struct Rod {
  Eigen::Vector3f centre_m = Eigen::Vector3f::Zero();  // middle of the axis segment
  Eigen::Vector3f axis = Eigen::Vector3f::UnitY();     // unit
  float radius_m = 0.0f;
  float half_length_m = 0.0f;
};

// A rod given in the marker frame, seen from the camera at T_cam_marker.
Rod rod_in_camera(const Eigen::Isometry3d& T_cam_marker, const Eigen::Vector3d& centre_marker_m,
                  const Eigen::Vector3d& axis_marker, double radius_m, double half_length_m);

// Distance from the camera to the nearest point of the rod's axis: its place in the painter's
// order (far first) among the spheres, bubbles and other rods.
double rod_depth_m(const Rod& rod);

// Where the camera ray t * d (d a unit-z ray (x, y, 1)) first enters the rod's side: ray
// parameter t (the depth) and the outward unit normal. False when it misses, passes beyond the
// ends, or the camera is inside the rod.
inline bool intersect(const Rod& rod, const Eigen::Vector3f& d, float& t, Eigen::Vector3f& normal) {
  const Eigen::Vector3f w = -rod.centre_m;
  const float d_ax = d.dot(rod.axis);
  const float w_ax = w.dot(rod.axis);
  const float a = d.squaredNorm() - d_ax * d_ax;
  const float b = d.dot(w) - d_ax * w_ax;
  const float c = w.squaredNorm() - w_ax * w_ax - rod.radius_m * rod.radius_m;
  const float disc = b * b - a * c;
  if (disc <= 0.0f || a <= 1e-12f || c <= 0.0f) return false;
  t = (-b - std::sqrt(disc)) / a;
  if (t <= 0.0f) return false;
  const float along = t * d_ax + w_ax;
  if (along > rod.half_length_m || along < -rod.half_length_m) return false;
  normal = (t * d + w - along * rod.axis) / rod.radius_m;
  return true;
}

// Whether the rod blocks light reaching `p` from the unit direction `to_light` (a directional
// light: the shadow is the rod's parallel projection).
inline bool blocks(const Rod& rod, const Eigen::Vector3f& p, const Eigen::Vector3f& to_light) {
  const Eigen::Vector3f w0 = p - rod.centre_m;
  const float b = to_light.dot(rod.axis);
  const float d = to_light.dot(w0);
  const float e = rod.axis.dot(w0);
  const float denom = 1.0f - b * b;
  if (denom <= 1e-6f) return (w0 - e * rod.axis).squaredNorm() < rod.radius_m * rod.radius_m;
  const float s = (b * e - d) / denom;  // along the light ray from p
  const float u = (e - b * d) / denom;  // along the rod's axis
  if (s <= 0.0f || u > rod.half_length_m || u < -rod.half_length_m) return false;
  return (w0 + s * to_light - u * rod.axis).squaredNorm() < rod.radius_m * rod.radius_m;
}

}  // namespace rovctl::hal::mock
