// Noisy depth, attitude and rates from the world's truth; NaN and loss by fault injection.
#include "hal/mock/mock_sensors.hpp"

#include <cmath>
#include <limits>

namespace rovctl::hal::mock {

MockSensors::MockSensors(const SimulatedWorld& world, const SensorSimParams& params,
                         const FaultInjection& faults, std::uint64_t seed)
    : world_(world), params_(params), faults_(faults), rng_(seed) {}

bool MockSensors::read(SensorReadings& r) {
  const std::chrono::nanoseconds now = world_.time();
  if (FaultInjection::active(faults_.sensor_lost_at_s, now)) {
    r.depth_valid = false;
    r.attitude_valid = false;
    return false;
  }
  const VehicleState& s = world_.state();
  r.stamp = now;
  // The charger's current sense: live once the probe is captured in the socket.
  r.dock_contact_valid = true;
  r.dock_contact = world_.docking().docked;
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
  const double sigma = params_.attitude_noise_deg * M_PI / 180.0;
  const Eigen::Vector3d tilt(sigma * normal_(rng_), sigma * normal_(rng_), sigma * normal_(rng_));
  const double angle = tilt.norm();
  const Eigen::Quaterniond noise = angle > 0.0
                                       ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, tilt / angle))
                                       : Eigen::Quaterniond::Identity();
  r.q_world_body = (s.q_world_body * noise).normalized();
  r.omega_body_radps =
      s.omega_body_radps() +
      params_.gyro_noise_radps * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  return true;
}

}  // namespace rovctl::hal::mock
