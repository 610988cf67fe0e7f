// Shared helpers for the simulation tests: neutral-buoyancy parameters and a thruster command
// that produces a requested body wrench (pseudo-inverse of the configuration matrix).
#pragma once

#include <Eigen/Dense>
#include <algorithm>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::hal::mock::test {

// No net buoyancy, no restoring moment and no current: only what a test applies moves the vehicle.
inline SimParams still_water_params() {
  SimParams p;
  p.dynamics.buoyancy_n = p.dynamics.weight_n;
  p.current.random_sigma_mps.setZero();
  p.current.mean_world_mps.setZero();
  p.thrusters.deadband = 0.0;
  return p;
}

// Commands (fractions) giving `wrench` with the layout, for a thruster model without deadband
// and a linear curve.
inline ThrusterCommand command_for_wrench(const ThrusterLayout& layout,
                                          const Eigen::Matrix<double, 6, 1>& wrench) {
  const Eigen::MatrixXd B = layout.configuration_matrix();
  const Eigen::VectorXd thrust = B.completeOrthogonalDecomposition().solve(wrench);
  ThrusterCommand c;
  c.count = layout.thrusters.size();
  for (std::size_t i = 0; i < c.count; ++i) {
    const Thruster& t = layout.thrusters[i];
    const double f = thrust(static_cast<Eigen::Index>(i));
    c.thrust_fraction[static_cast<std::size_t>(t.channel)] =
        std::clamp(f >= 0 ? f / t.max_forward_n : f / t.max_reverse_n, -1.0, 1.0);
  }
  return c;
}

}  // namespace rovctl::hal::mock::test
