// The side light's declarations, and its light and strut carried into a camera's frame.
#include "hal/mock/side_light.hpp"

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, SideLight& s) {
  v.param("to_light_marker", s.to_light_marker,
          {"-", -1.0, 1.0, "direction towards the light in the marker frame (normalised)"});
  v.param("intensity", s.intensity,
          {"-", 0.0, 10.0, "irradiance of the lit side, relative to the clear scene's lamp"});
  v.param("ambient", s.ambient, {"-", 0.0, 1.0, "fill light on the shaded side, same scale"});
  v.param("cast_shadows", s.cast_shadows, "the strut and the spheres cast shadows");
  v.param("strut_centre_marker_m", s.strut_centre_marker_m,
          {"m", -10.0, 10.0, "middle of the shadow-casting strut, marker frame"});
  v.param("strut_axis_marker", s.strut_axis_marker,
          {"-", -1.0, 1.0, "direction of the strut's axis, marker frame (normalised)"});
  v.param("strut_radius_m", s.strut_radius_m, {"m", 0.0, 0.5, "strut radius (0: no strut)"});
  v.param("strut_half_length_m", s.strut_half_length_m,
          {"m", 0.0, 10.0, "half the strut's length"});
  v.param("strut_albedo_rgb", s.strut_albedo_rgb,
          {"-", 0.0, 1.0, "strut surface colour, linear RGB"});
}

SideLighting side_lighting(const SideLight& s, const Eigen::Isometry3d& T_cam_marker) {
  SideLighting l;
  const Eigen::Vector3d dir =
      s.to_light_marker.norm() > 0.0 ? s.to_light_marker.normalized() : Eigen::Vector3d::UnitX();
  l.to_light = (T_cam_marker.linear() * dir).cast<float>();
  l.intensity = static_cast<float>(s.intensity);
  l.ambient = static_cast<float>(s.ambient);
  l.cast_shadows = s.cast_shadows;
  const Eigen::Vector3d axis =
      s.strut_axis_marker.norm() > 0.0 ? s.strut_axis_marker : Eigen::Vector3d::UnitZ();
  l.strut = rod_in_camera(T_cam_marker, s.strut_centre_marker_m, axis, s.strut_radius_m,
                          s.strut_half_length_m);
  return l;
}

}  // namespace rovctl::hal::mock
