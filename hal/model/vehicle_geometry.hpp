// Where things are on the vehicle: the stereo rig's mount, the docking probe, the thrusters.
// Shared by the simulation (to render and to detect contact) and control (to aim the probe).
#pragma once

#include <Eigen/Geometry>

#include "hal/model/thruster_layout.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal {

struct VehicleGeometry {
  // Left camera in the body frame (body: x forward, y starboard, z down). The camera looks
  // forward: z_cl = x_body, x_cl = y_body, y_cl = z_body, then tilted by these angles.
  Eigen::Vector3d left_camera_position_body_m{0.22, -0.089, -0.05};
  double camera_tilt_down_deg = 0.0;  // positive pitches the optical axis down
  // Tip of the docking probe in the body frame; it mates along the body x axis.
  Eigen::Vector3d probe_tip_body_m{0.55, 0.0, 0.05};
  ThrusterLayout thrusters = ThrusterLayout::bluerov2_heavy();

  Eigen::Isometry3d T_body_cl() const;
};

void describe(ParamVisitor& v, VehicleGeometry& geometry);

}  // namespace rovctl::hal
