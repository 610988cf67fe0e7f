// Roll and pitch levelling from the IMU: the moments that hold the vehicle level while the
// visual servo steers x, y, z and yaw (ArduSub's stabilise loop, as a PD on attitude and gyro).
#pragma once

#include <Eigen/Core>

#include "control/control_params.hpp"
#include "hal/interfaces/sensors.hpp"

namespace rovctl::control {

class AttitudeStabilizer {
 public:
  explicit AttitudeStabilizer(const AttitudeParams& params) : p_(params) {}

  // Body-x (roll) and body-y (pitch) moments, N m, that level the vehicle. False, with zero
  // moments, when disabled or when the reading has no valid, finite attitude and rates (the
  // caller then keeps the servo's own damping). No allocation.
  bool update(const hal::SensorReadings& readings, Eigen::Vector2d& moment_nm) const;

  // Roll and pitch (rad) of a world(NED)-from-body attitude, Z-Y-X Euler angles.
  static Eigen::Vector2d roll_pitch(const Eigen::Quaterniond& q_world_body);

 private:
  AttitudeParams p_;
};

}  // namespace rovctl::control
