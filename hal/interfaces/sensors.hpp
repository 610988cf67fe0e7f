// Sensors: the vehicle's navigation sensors where it has them (depth, attitude, rates), the dock
// contact, and the battery and charger state the recharging mission watches.
#pragma once

#include <Eigen/Geometry>
#include <chrono>

namespace rovctl::hal {

struct SensorReadings {
  std::chrono::nanoseconds stamp{0};
  // How old each part was when read (0 for a sensor sampled at the read): a part past its
  // source's limit is also marked invalid, so stale is never served as fresh.
  std::chrono::nanoseconds depth_age{0};
  std::chrono::nanoseconds attitude_age{0};
  std::chrono::nanoseconds battery_age{0};
  bool depth_valid = false;
  double depth_m = 0.0;
  bool attitude_valid = false;
  Eigen::Quaterniond q_world_body = Eigen::Quaterniond::Identity();  // world = NED
  Eigen::Vector3d omega_body_radps = Eigen::Vector3d::Zero();
  // Charging contact with the docking station (e.g. the charger's current sense).
  bool dock_contact_valid = false;
  bool dock_contact = false;
  // The battery (from its monitor) and the station's charger (its current sense, over the dock's
  // link). charge_current_a is what the charger pushes into the battery: 0 when it delivers none.
  bool battery_valid = false;
  double soc_fraction = 0.0;  // state of charge, 0..1
  double battery_voltage_v = 0.0;
  bool charger_valid = false;
  double charge_current_a = 0.0;
  // Water inside the hull (e.g. ArduSub's leak detector).
  bool leak_valid = false;
  bool leak = false;
};

class Sensors {
 public:
  virtual ~Sensors() = default;
  // The latest readings; false when none are available (fields keep their valid flags).
  virtual bool read(SensorReadings& readings) = 0;
};

}  // namespace rovctl::hal
