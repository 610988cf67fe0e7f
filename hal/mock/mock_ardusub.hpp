// MockArdusub: what ArduSub does with a companion's pilot input on the simulated vehicle — arm
// state and flight mode, MANUAL_CONTROL axes to a body wrench through the pilot gain, a stabilise
// loop holding roll and pitch level, its mixer onto the simulated thrusters, and the pilot-input
// failsafe. How it is talked to (MAVLink) lives above the mock HAL (app/runtime).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstdint>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/simulated_world.hpp"

namespace rovctl::hal::mock {

// MANUAL_CONTROL's axes as ArduSub receives them: x, y, r in -1000..1000, z 0..1000 (500 neutral).
struct PilotAxes {
  int x = 0;
  int y = 0;
  int z = 500;
  int r = 0;
};

// ArduSub's custom_mode numbers (ArduSub/mode.h) the mock knows.
constexpr std::uint32_t kArdusubModeStabilize = 0;
constexpr std::uint32_t kArdusubModeAltHold = 2;
constexpr std::uint32_t kArdusubModeManual = 19;

class MockArdusub {
 public:
  // The world's vehicle layout is ArduSub's frame; it boots in MANUAL, disarmed.
  MockArdusub(SimulatedWorld& world, const MockArdusubParams& params);

  // COMMAND_LONG ARM_DISARM: always accepted (no pre-arm checks in the mock); true when taken.
  bool arm(bool armed, std::chrono::nanoseconds now);
  bool armed() const { return armed_; }
  void set_mode(std::uint32_t custom_mode) { mode_ = custom_mode; }
  std::uint32_t mode() const { return mode_; }

  // MANUAL_CONTROL from the GCS: the newest pilot input, which refreshes the failsafe timer.
  void pilot_input(const PilotAxes& axes, std::chrono::nanoseconds now);
  // RC_CHANNELS_OVERRIDE from the GCS with the thrusters' outputs set to RC passthrough
  // (SERVOn_FUNCTION = RCINn, output n on channel n): each channel's PWM drives its ESC, past the
  // mixer and stabilise, while the override is fresher than RC_OVERRIDE_TIME and whatever the arm
  // state (passthrough outputs are not motor outputs). It refreshes the pilot-input timer.
  void rc_override(const std::array<std::uint16_t, 18>& channels_us, std::chrono::nanoseconds now);
  // One pass of ArduSub's loop at `now`: the pilot failsafe, then the axes through the pilot
  // gain, the stabilise loop's roll/pitch moments on the vehicle's attitude (its AHRS: the
  // world's truth) and the mixer, delivered to the simulated thrusters. No allocation.
  void update(std::chrono::nanoseconds now);

  // Force (N) or torque (N*m) at full stick with pilot gain 1: what ArduSub's mixer gets out of
  // this layout along each pilot axis (surge, sway, heave up, yaw clockwise from above).
  const Eigen::Vector4d& full_stick() const { return full_stick_; }
  // The body wrench [F; M] asked of the mixer in the last update (before the thrusters' limits).
  const Eigen::Matrix<double, 6, 1>& demanded_wrench() const { return demanded_; }
  const ThrusterCommand& last_command() const { return command_; }
  bool pilot_failsafe() const { return pilot_failsafe_; }

  // What ArduSub streams: attitude (body FRD in NED) and rates, absolute pressure (hPa), battery.
  Eigen::Quaterniond q_ned_body() const;
  Eigen::Vector3d omega_body_radps() const;
  double pressure_hpa() const;
  double battery_voltage_v() const;
  int battery_remaining_pct() const;
  const MockArdusubParams& params() const { return params_; }

 private:
  // Thruster fractions for `wrench` through the pseudo-inverse, scaled down together when one
  // saturates (ArduSub's mixer keeps the direction too).
  void mix(const Eigen::Matrix<double, 6, 1>& wrench, ThrusterCommand& out) const;

  SimulatedWorld& world_;
  MockArdusubParams params_;
  std::size_t count_ = 0;
  Eigen::Matrix<double, kMaxThrusters, 6> pinv_ = Eigen::Matrix<double, kMaxThrusters, 6>::Zero();
  std::array<double, kMaxThrusters> max_forward_n_{};
  std::array<double, kMaxThrusters> max_reverse_n_{};
  std::array<std::size_t, kMaxThrusters> channel_{};
  Eigen::Vector4d full_stick_ = Eigen::Vector4d::Zero();
  bool armed_ = false;
  std::uint32_t mode_ = kArdusubModeManual;
  PilotAxes axes_;
  std::array<std::uint16_t, 18> override_us_{};
  bool override_seen_ = false;
  std::chrono::nanoseconds last_override_{0};
  std::chrono::nanoseconds last_input_{0};
  bool pilot_failsafe_ = false;
  Eigen::Matrix<double, 6, 1> demanded_ = Eigen::Matrix<double, 6, 1>::Zero();
  ThrusterCommand command_{};
};

}  // namespace rovctl::hal::mock
