// Sensors: the vehicle's navigation sensors where it has them (depth, attitude, rates).
#pragma once

#include <Eigen/Geometry>
#include <chrono>

namespace rovctl::hal {

struct SensorReadings {
  std::chrono::nanoseconds stamp{0};
  bool depth_valid = false;
  double depth_m = 0.0;
  bool attitude_valid = false;
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();  // world = NED
  Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();
  // Charging contact with the docking station (e.g. the charger's current sense).
  bool dock_contact_valid = false;
  bool dock_contact = false;
};

class Sensors {
 public:
  virtual ~Sensors() = default;
  // The latest readings; false when none are available (fields keep their valid flags).
  virtual bool read(SensorReadings& readings) = 0;
};

}  // namespace rovctl::hal
