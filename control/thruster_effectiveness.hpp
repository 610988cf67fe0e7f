// The thrusters' effectiveness: the body wrench each newton of thrust produces, and the
// asymmetric forward/reverse limits that map newtons to command fractions. Built once from the
// vehicle's hal::ThrusterLayout; the allocation solves against it.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::control {

using Wrench = Eigen::Matrix<double, 6, 1>;  // body frame [Fx Fy Fz Mx My Mz], N and N m
// Per-thruster vectors, sized to the layout, never larger than the bus: no heap.
using ThrustVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, hal::kMaxThrusters, 1>;
using EffectivenessMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, hal::kMaxThrusters>;

class ThrusterEffectiveness {
 public:
  // Throws std::invalid_argument (naming the thruster) for more than hal::kMaxThrusters
  // thrusters, a zero direction, a channel off the bus or used twice, a deadband outside [0, 1).
  // deadband: the command fraction below which the ESC gives no thrust; beyond it thrust grows
  // linearly to the maximum at 1 (what the simulated T200 + Basic ESC do).
  explicit ThrusterEffectiveness(const hal::ThrusterLayout& layout, double deadband = 0.0);

  // 6 x n: column i is the wrench [N; N m] per newton of thruster i's thrust.
  const EffectivenessMatrix& matrix() const { return matrix_; }
  std::size_t count() const { return count_; }
  double max_forward_n(std::size_t i) const { return max_forward_n_[i]; }
  double max_reverse_n(std::size_t i) const { return max_reverse_n_[i]; }
  int channel(std::size_t i) const { return channel_[i]; }
  // Largest thrust magnitude thruster i can give in the sign of `thrust_n`.
  double limit_n(std::size_t i, double thrust_n) const {
    return thrust_n >= 0.0 ? max_forward_n_[i] : max_reverse_n_[i];
  }
  // Command fraction for a thrust (forward and reverse scale differently, the deadband
  // skipped), not clipped.
  double command_for_thrust(std::size_t i, double thrust_n) const {
    if (thrust_n == 0.0) return 0.0;
    const double magnitude =
        deadband_ + (1.0 - deadband_) * std::abs(thrust_n) / limit_n(i, thrust_n);
    return thrust_n > 0.0 ? magnitude : -magnitude;
  }
  double thrust_for_command(std::size_t i, double command) const {
    const double past = std::max(0.0, std::abs(command) - deadband_) / (1.0 - deadband_);
    return command >= 0.0 ? past * max_forward_n_[i] : -past * max_reverse_n_[i];
  }
  double deadband() const { return deadband_; }
  // The wrench a set of commands (indexed by bus channel) produces: the forward model.
  Wrench wrench_for_command(const hal::ThrusterCommand& command) const;

 private:
  std::size_t count_ = 0;
  double deadband_ = 0.0;
  EffectivenessMatrix matrix_;
  std::array<double, hal::kMaxThrusters> max_forward_n_{};
  std::array<double, hal::kMaxThrusters> max_reverse_n_{};
  std::array<int, hal::kMaxThrusters> channel_{};
};

}  // namespace rovctl::control
