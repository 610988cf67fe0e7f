// The docking station: the marker on it and the charging socket the probe must enter.
// The docking axis is the marker's +z (into the station).
#pragma once

#include <Eigen/Geometry>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal {

struct DockingStation {
  // The socket mouth in the marker frame; the probe enters it along marker +z.
  Eigen::Vector3d socket_marker_m{0.0, 0.12, 0.0};
  // The socket's bottom: contact is made, and the seated probe rests, this deep past the mouth.
  double capture_depth_m = 0.02;
};

void describe(ParamVisitor& v, DockingStation& station);

// The marker pose in the left camera at contact: probe tip at the socket mouth, vehicle aligned
// with the docking axis (marker z along body x). Control aims for it; the simulation checks it.
Eigen::Isometry3d docked_T_cl_marker(const Eigen::Isometry3d& T_body_cl,
                                     const Eigen::Vector3d& probe_tip_body_m,
                                     const DockingStation& station);

}  // namespace rovctl::hal
