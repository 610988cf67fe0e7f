// The water current in the world frame: a constant part plus a slowly varying random part
// (per axis, a Gauss-Markov process smoothed by a first-order filter, so that it has a finite
// rate of change), reproducible from a seed.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

struct WaterCurrentParams {
  Eigen::Vector3d mean_world_mps = Eigen::Vector3d::Zero();  // NED; trials override it
  // Standard deviation of the random part per axis (stationary), and how slowly it varies.
  Eigen::Vector3d random_sigma_mps{0.01, 0.01, 0.002};
  double correlation_time_s = 10.0;
};

void describe(ParamVisitor& v, WaterCurrentParams& p);

class WaterCurrent {
 public:
  WaterCurrent(const WaterCurrentParams& params, std::uint64_t seed);

  // Advances the random part by `dt_s` (exact discretisation of both first-order stages).
  void step(double dt_s);

  Eigen::Vector3d velocity_world_mps() const { return p_.mean_world_mps + random_; }
  // Rate of change over the last step, for the added-mass term of the dynamics.
  const Eigen::Vector3d& rate_world_mps2() const { return rate_; }
  const Eigen::Vector3d& mean_world_mps() const { return p_.mean_world_mps; }
  void set_mean_world_mps(const Eigen::Vector3d& mean) { p_.mean_world_mps = mean; }
  void reset(std::uint64_t seed);

 private:
  WaterCurrentParams p_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d driver_ = Eigen::Vector3d::Zero();  // the Gauss-Markov process
  Eigen::Vector3d random_ = Eigen::Vector3d::Zero();  // driver_ low-passed: the varying part
  Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();
};

}  // namespace rovctl::hal::mock
