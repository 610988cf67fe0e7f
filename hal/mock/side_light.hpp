// The side_light scenario: one strong directional light from the side instead of the lamp over
// the cameras, so each sphere has a dark side, and a station strut and the spheres cast shadows.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "hal/mock/rod.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// Sunlight through a gap, another vehicle's lamp. In the marker frame (x right, y down, z into
// the station). The defaults light the marker from
// its left, a little from above and from the camera's side: the spheres' right halves are in
// shade, the red sphere shades part of the green one, and the strut, a horizontal pipe off to the
// left running towards the vehicle, casts a band of shadow across the blue sphere.
struct SideLight {
  Eigen::Vector3d to_light_marker{-1.0, -0.15, -0.2};  // towards the light (normalised on use)
  double intensity = 1.3;  // lit-side irradiance, relative to the clear scene's full lamp
  double ambient = 0.05;   // fill light reaching the shaded side, same scale
  bool cast_shadows = true;
  Eigen::Vector3d strut_centre_marker_m{-0.388, -0.118, -0.118};
  Eigen::Vector3d strut_axis_marker{0.0, 0.0, 1.0};
  double strut_radius_m = 0.008;  // 0: no strut
  double strut_half_length_m = 0.3;
  Eigen::Vector3d strut_albedo_rgb{0.25, 0.25, 0.25};
};

void describe(ParamVisitor& v, SideLight& s);

constexpr int kMaxShadowCasters = 8;  // spheres

// The light and its shadow casters in one camera's frame, for one frame.
struct SideLighting {
  Eigen::Vector3f to_light = Eigen::Vector3f::UnitX();  // unit, camera frame
  float intensity = 1.0f;
  float ambient = 0.0f;
  bool cast_shadows = false;
  Rod strut;
  int sphere_count = 0;
  Eigen::Vector3f sphere_centre_m[kMaxShadowCasters];
  float sphere_radius_m[kMaxShadowCasters] = {};

  // Whether the light reaching surface point `p` (camera frame) is blocked by the strut or by a
  // sphere other than `self`.
  bool shadowed(const Eigen::Vector3f& p, int self) const {
    if (!cast_shadows) return false;
    if (strut.radius_m > 0.0f && blocks(strut, p, to_light)) return true;
    for (int j = 0; j < sphere_count; ++j) {
      if (j == self) continue;
      const Eigen::Vector3f v = sphere_centre_m[j] - p;
      const float s = v.dot(to_light);
      if (s > 0.0f && v.squaredNorm() - s * s < sphere_radius_m[j] * sphere_radius_m[j]) {
        return true;
      }
    }
    return false;
  }
};

SideLighting side_lighting(const SideLight& s, const Eigen::Isometry3d& T_cam_marker);

}  // namespace rovctl::hal::mock
