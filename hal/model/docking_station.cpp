// Docking-station geometry and the docked relative pose it implies.
#include "hal/model/docking_station.hpp"

namespace rovctl::hal {

void describe(ParamVisitor& v, DockingStation& s) {
  v.param("socket_m", s.socket_marker_m,
          {"m", -2.0, 2.0, "charging socket mouth in the marker frame (docking axis = marker +z)"});
  v.param("capture_depth_m", s.capture_depth_m,
          {"m", 0.0, 0.2,
           "probe depth past the socket mouth at the socket's bottom: contact, and where the "
           "seated probe rests"});
}

Eigen::Isometry3d docked_T_cl_marker(const Eigen::Isometry3d& T_body_cl,
                                     const Eigen::Vector3d& probe_tip_body_m,
                                     const DockingStation& station) {
  // Aligned: marker axes = camera-looking-along-body-x axes, i.e. R_body_marker = R_body_cl with
  // no tilt. Marker z = body x, marker x = body y, marker y = body z.
  Eigen::Matrix3d R_body_marker;
  R_body_marker.col(0) = Eigen::Vector3d::UnitY();
  R_body_marker.col(1) = Eigen::Vector3d::UnitZ();
  R_body_marker.col(2) = Eigen::Vector3d::UnitX();
  Eigen::Isometry3d T_body_marker = Eigen::Isometry3d::Identity();
  T_body_marker.linear() = R_body_marker;
  // Socket mouth coincides with the probe tip: p_body_socket = R * socket + t = probe_tip.
  T_body_marker.translation() = probe_tip_body_m - R_body_marker * station.socket_marker_m;
  return T_body_cl.inverse() * T_body_marker;
}

}  // namespace rovctl::hal
