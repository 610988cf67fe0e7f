// Camera mount pose and the vehicle geometry's parameter declarations.
#include "hal/model/vehicle_geometry.hpp"

#include <cmath>

namespace rovctl::hal {

Eigen::Isometry3d VehicleGeometry::T_body_cl() const {
  Eigen::Matrix3d R_body_cam;  // columns: camera x, y, z axes in body coordinates
  R_body_cam.col(0) = Eigen::Vector3d::UnitY();
  R_body_cam.col(1) = Eigen::Vector3d::UnitZ();
  R_body_cam.col(2) = Eigen::Vector3d::UnitX();
  // Tilt about the camera x axis: positive turns z toward +y_cam (down).
  const Eigen::AngleAxisd tilt(-camera_tilt_down_deg * M_PI / 180.0, Eigen::Vector3d::UnitX());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_body_cam * tilt.toRotationMatrix();
  T.translation() = left_camera_position_body_m;
  return T;
}

void describe(ParamVisitor& v, VehicleGeometry& g) {
  v.param("left_camera_position_m", g.left_camera_position_body_m,
          {"m", -5.0, 5.0, "left camera's optical centre in the body frame"});
  v.param("camera_tilt_down_deg", g.camera_tilt_down_deg,
          {"deg", -90.0, 90.0, "downward tilt of the stereo rig's optical axes"});
  v.param("probe_tip_m", g.probe_tip_body_m,
          {"m", -5.0, 5.0, "docking probe tip in the body frame; it mates along body x"});
  v.section("thrusters", "thruster geometry and strength",
            [&g](ParamVisitor& s) { describe(s, g.thrusters); });
}

}  // namespace rovctl::hal
