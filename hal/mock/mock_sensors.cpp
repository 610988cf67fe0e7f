// Noisy depth, attitude and rates from the world's truth; NaN and loss by fault injection.
#include "hal/mock/mock_sensors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rovctl::hal::mock {

MockSensors::MockSensors(const SimulatedWorld& world, const SensorSimParams& params,
                         const FaultInjection& faults, std::uint64_t seed)
    : world_(world),
      params_(params),
      faults_(faults),
      rng_(seed),
      charger_rng_(seed ^ 0x9e3779b97f4a7c15ULL) {}

bool MockSensors::read(SensorReadings& r) {
  const std::chrono::nanoseconds now = world_.time();
  if (FaultInjection::active(faults_.sensor_lost_at_s, now)) {
    r.depth_valid = false;
    r.attitude_valid = false;
    return false;
  }
  const VehicleState& s = world_.state();
  r.stamp = now;
  // The probe's seat contact: once captured, as long as it stays seated (with the latch closed it
  // cannot leave, so the docking mission sees what it always saw).
  r.dock_contact_valid = true;
  r.dock_contact = world_.docking().docked && world_.docking().seated;
  const ChargeTruth& charge = world_.charge();
  r.battery_valid = true;
  r.soc_fraction = charge.soc_fraction;
  r.battery_voltage_v = charge.battery_voltage_v;
  r.charger_valid = true;
  r.charge_current_a = std::max(
      0.0, charge.charge_current_a + world_.params().recharge.charger.current_sense_noise_a *
                                         charger_normal_(charger_rng_));
  r.depth_valid = true;
  r.attitude_valid = true;
  if (FaultInjection::active(faults_.sensor_nan_at_s, now)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.depth_m = nan;
    r.q_world_body = Eigen::Quaterniond(nan, nan, nan, nan);
    r.omega_body_radps.setConstant(nan);
    return true;
  }
  r.depth_m = s.position_world_m.z() + params_.depth_noise_m * normal_(rng_);
  if (FaultInjection::active(faults_.sensor_implausible_at_s, now)) {
    r.depth_m = faults_.sensor_implausible_depth_m;
  }
  const double sigma = params_.attitude_noise_deg * M_PI / 180.0;
  const Eigen::Vector3d tilt(sigma * normal_(rng_), sigma * normal_(rng_), sigma * normal_(rng_));
  const double angle = tilt.norm();
  const Eigen::Quaterniond noise = angle > 0.0
                                       ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, tilt / angle))
                                       : Eigen::Quaterniond::Identity();
  r.q_world_body = (s.q_world_body * noise).normalized();
  if (FaultInjection::active(faults_.tilt_at_s, faults_.tilt_for_s, now)) {
    r.q_world_body = r.q_world_body * Eigen::Quaterniond(Eigen::AngleAxisd(
                                          faults_.tilt_rad, Eigen::Vector3d::UnitX()));
  }
  r.omega_body_radps =
      s.omega_body_radps() +
      params_.gyro_noise_radps * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  return true;
}

}  // namespace rovctl::hal::mock
