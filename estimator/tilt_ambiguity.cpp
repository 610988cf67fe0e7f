// A reflection of the triangle through the plane normal to the line of sight keeps its image
// (orthographic) and, being a plane figure, equals a rotation: about the line where the
// triangle's plane meets that plane, by twice the angle between their normals.
#include "estimator/tilt_ambiguity.hpp"

#include <cmath>

namespace rovctl::estimator {

Eigen::Isometry3d mirrored_tilt(const Eigen::Isometry3d& T_cl_marker,
                                const hal::MarkerModel& marker) {
  if (marker.spheres.size() < 3) return T_cl_marker;
  Eigen::Vector3d p[3];
  for (int i = 0; i < 3; ++i) p[i] = T_cl_marker * marker.spheres[i].centre_marker_m;
  const Eigen::Vector3d centroid = (p[0] + p[1] + p[2]) / 3.0;
  const Eigen::Vector3d sight = centroid.normalized();
  Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
  if (normal.norm() < 1e-12 || !sight.allFinite()) return T_cl_marker;
  normal.normalize();
  if (normal.dot(sight) < 0.0) normal = -normal;
  const Eigen::Vector3d axis = normal.cross(sight);
  const double sin_tilt = axis.norm();
  if (sin_tilt < 1e-9) return T_cl_marker;
  const double tilt = std::atan2(sin_tilt, normal.dot(sight));
  // Turning the normal toward the line of sight by twice its tilt mirrors it about that line.
  const Eigen::Matrix3d R(Eigen::AngleAxisd(2.0 * tilt, axis / sin_tilt));
  Eigen::Isometry3d out = T_cl_marker;
  out.linear() = R * T_cl_marker.linear();
  out.translation() = R * (T_cl_marker.translation() - centroid) + centroid;
  return out;
}

}  // namespace rovctl::estimator
