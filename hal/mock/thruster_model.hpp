// The thrusters as the simulated vehicle feels them: deadband, saturation, asymmetric forward and
// reverse thrust, first-order lag, the ESCs' own failsafe when commands stop arriving, and the
// injected failures of one thruster (dead, weak, stuck).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/fault_injection.hpp"
#include "hal/model/thruster_layout.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

struct ThrusterModelParams {
  // T200 + Basic ESC: the thrust follows the command with roughly 0.1 s of motor spin-up.
  double time_constant_s = 0.10;
  // ESC deadband around neutral (Basic ESC: +-25 us of a +-400 us range = 0.0625).
  double deadband = 0.0625;
  // Thrust ~ (fraction past the deadband)^exponent; 1 is linear (what the allocation assumes).
  double curve_exponent = 1.0;
  // The ESCs go neutral when no command has arrived for this long (bus loss, application hang).
  double command_timeout_s = 0.25;
};

void describe(ParamVisitor& v, ThrusterModelParams& p);

class ThrusterModel {
 public:
  ThrusterModel(const ThrusterLayout& layout, const ThrusterModelParams& params);

  // New commands (fractions in [-1, 1], by bus channel) received at `time_s`. Non-finite
  // commands are taken as neutral, as an ESC rejects a malformed frame.
  void command(const ThrusterCommand& cmd, double time_s);
  // All thrusters neutral at once (disarm).
  void neutral(double time_s);

  // Advances the thrust of each thruster by `dt_s` towards its (possibly timed-out) command.
  void step(double time_s, double dt_s);

  // Steady-state thrust [N] for a command fraction on thruster i: deadband, saturation and the
  // forward/reverse asymmetry.
  double static_thrust_n(std::size_t i, double fraction) const;

  // The thrusters' current wrench on the body: [force; moment about the body origin].
  Eigen::Matrix<double, 6, 1> wrench_body() const;

  std::size_t count() const { return count_; }
  double thrust_n(std::size_t i) const { return thrust_n_[i]; }
  double commanded_fraction(std::size_t i) const { return command_[i]; }
  bool timed_out(double time_s) const { return time_s - last_command_s_ > p_.command_timeout_s; }
  int channel(std::size_t i) const { return channel_[i]; }
  void reset();

  // The thruster failures of `faults` (thruster_dead/weak/stuck_*), timed by step()'s clock.
  // Throws std::invalid_argument for a scheduled failure naming no thruster of the layout.
  void set_faults(const FaultInjection& faults);
  // Thruster i's ESC reports a fault (the dead thruster, once dead).
  bool fault_flagged(std::size_t i, double time_s) const;

 private:
  bool failing(int index, double at_s, std::size_t i, double time_s) const {
    return at_s >= 0.0 && time_s >= at_s && static_cast<std::size_t>(index) == i;
  }

  ThrusterModelParams p_;
  std::size_t count_ = 0;
  Eigen::Matrix<double, 6, kMaxThrusters> config_ = Eigen::Matrix<double, 6, kMaxThrusters>::Zero();
  std::array<double, kMaxThrusters> max_forward_n_{};
  std::array<double, kMaxThrusters> max_reverse_n_{};
  std::array<int, kMaxThrusters> channel_{};
  std::array<double, kMaxThrusters> command_{};   // by thruster index
  std::array<double, kMaxThrusters> thrust_n_{};  // actual thrust now, by thruster index
  double last_command_s_ = -1e9;
  FaultInjection faults_;
};

}  // namespace rovctl::hal::mock
