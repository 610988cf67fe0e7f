// The bar's motion: to and fro at constant speed, so every sphere is covered once per sweep.
#include "hal/mock/passing_bar.hpp"

#include <cmath>

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, PassingBar& p) {
  v.param("in_front_of_marker_m", p.in_front_of_marker_m,
          {"m", 0.0, 5.0, "distance of the bar's axis in front of the marker plane"});
  v.param("radius_m", p.radius_m, {"m", 0.0, 0.5, "bar radius (0: no bar)"});
  v.param("half_length_m", p.half_length_m, {"m", 0.0, 10.0, "half the bar's length"});
  v.param("tilt_deg", p.tilt_deg,
          {"deg", -90.0, 90.0, "tilt of the bar from the marker's vertical, in its plane"});
  v.param("sweep_min_m", p.sweep_min_m,
          {"m", -5.0, 5.0, "left end of the sweep, marker x (where it is at time 0)"});
  v.param("sweep_max_m", p.sweep_max_m, {"m", -5.0, 5.0, "right end of the sweep, marker x"});
  v.param("speed_mps", p.speed_mps, {"m/s", 0.0, 5.0, "sweep speed along the marker's x"});
  v.param("albedo_rgb", p.albedo_rgb, {"-", 0.0, 1.0, "bar surface colour, linear RGB"});
}

double bar_x_m(const PassingBar& p, double time_s) {
  const double span = std::abs(p.sweep_max_m - p.sweep_min_m);
  if (span <= 0.0) return p.sweep_min_m;
  double s = std::fmod(std::abs(p.speed_mps * time_s), 2.0 * span);
  if (s > span) s = 2.0 * span - s;
  return p.sweep_min_m + (p.sweep_max_m >= p.sweep_min_m ? s : -s);
}

Rod bar_in_camera(const PassingBar& p, const Eigen::Isometry3d& T_cam_marker, double time_s) {
  const double tilt = p.tilt_deg * M_PI / 180.0;
  const Eigen::Vector3d axis(std::sin(tilt), std::cos(tilt), 0.0);
  const Eigen::Vector3d centre(bar_x_m(p, time_s), 0.0, -p.in_front_of_marker_m);
  return rod_in_camera(T_cam_marker, centre, axis, p.radius_m, p.half_length_m);
}

}  // namespace rovctl::hal::mock
