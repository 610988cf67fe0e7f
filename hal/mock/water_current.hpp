// The water current in the world frame: a constant part plus a slowly varying random part
// (per axis, a Gauss-Markov process smoothed by a first-order filter, so that it has a finite
// rate of change), optionally turning with the tide and gusting, reproducible from a seed.
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
  // The tide turns the constant part about the vertical at this rate (0: it keeps its direction).
  double tide_turn_degps = 0.0;
  // Gusts along the constant part's direction (a random horizontal one when it is zero): raised-
  // cosine pulses of up to gust_peak_mps, each gust_duration_s long, starting at random with
  // mean gap gust_interval_s. 0: no gusts.
  double gust_peak_mps = 0.0;
  double gust_duration_s = 4.0;
  double gust_interval_s = 20.0;
};

void describe(ParamVisitor& v, WaterCurrentParams& p);

class WaterCurrent {
 public:
  WaterCurrent(const WaterCurrentParams& params, std::uint64_t seed);

  // Advances the random part by `dt_s` (exact discretisation of both first-order stages).
  void step(double dt_s);

  Eigen::Vector3d velocity_world_mps() const { return mean_now_ + gust_ + random_; }
  // Rate of change over the last step, for the added-mass term of the dynamics.
  const Eigen::Vector3d& rate_world_mps2() const { return rate_; }
  const Eigen::Vector3d& mean_world_mps() const { return p_.mean_world_mps; }
  void set_mean_world_mps(const Eigen::Vector3d& mean) {
    p_.mean_world_mps = mean;
    mean_now_ = mean;
  }
  // The gust's part of the velocity now.
  const Eigen::Vector3d& gust_world_mps() const { return gust_; }
  void reset(std::uint64_t seed);

 private:
  WaterCurrentParams p_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  Eigen::Vector3d driver_ = Eigen::Vector3d::Zero();  // the Gauss-Markov process
  Eigen::Vector3d random_ = Eigen::Vector3d::Zero();  // driver_ low-passed: the varying part
  Eigen::Vector3d rate_ = Eigen::Vector3d::Zero();
  // Tide and gusts draw on their own generator, so the random part is the same with or without.
  void step_tide_and_gusts(double dt_s);
  std::mt19937_64 gust_rng_;
  double time_s_ = 0.0;
  double gust_start_s_ = -1.0;  // < 0: no gust under way
  double gust_next_s_ = 0.0;
  double gust_amplitude_mps_ = 0.0;
  Eigen::Vector3d mean_now_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gust_ = Eigen::Vector3d::Zero();
};

}  // namespace rovctl::hal::mock
