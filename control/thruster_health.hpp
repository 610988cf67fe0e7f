// ThrusterHealth: decides from the ESCs' telemetry (fault flags, rpm against the commanded thrust)
// which thrusters have failed — dead, weak or stuck — with a persistence count per symptom.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "control/control_params.hpp"
#include "control/thruster_effectiveness.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::control {

enum class ThrusterFailure {
  none,
  fault_flag,  // the ESC reports a fault
  dead,        // no rpm for a command that should turn it
  weak,        // too few rpm for the command
  stuck,       // rpm that does not follow the command (reversed, too fast, turning at neutral)
};
const char* to_string(ThrusterFailure f);

class ThrusterHealth {
 public:
  ThrusterHealth(const ThrusterEffectiveness& effectiveness, const ThrusterHealthParams& params);

  // One tick: `telemetry` as read now, `last_command` the commands written on the previous tick
  // (by bus channel), `dt_s` the time since. Returns how many thrusters failed on this call; a
  // failed thruster stays failed (it is judged no more). Invalid telemetry judges nothing. No
  // allocation.
  std::size_t update(const hal::ThrusterTelemetry& telemetry,
                     const hal::ThrusterCommand& last_command, double dt_s);

  bool failed(std::size_t i) const { return failure_[i] != ThrusterFailure::none; }
  ThrusterFailure failure(std::size_t i) const { return failure_[i]; }
  // The rpm the thruster should turn at now, from its filtered command.
  double expected_rpm(std::size_t i) const;

 private:
  // The symptom of thruster i this tick (none when healthy or not judged).
  ThrusterFailure symptom(std::size_t i, double rpm, std::uint16_t flags) const;

  const ThrusterEffectiveness& effectiveness_;
  ThrusterHealthParams p_;
  std::array<double, hal::kMaxThrusters> expected_thrust_n_{};
  std::array<ThrusterFailure, hal::kMaxThrusters> candidate_{};
  std::array<int, hal::kMaxThrusters> count_{};
  std::array<ThrusterFailure, hal::kMaxThrusters> failure_{};
};

}  // namespace rovctl::control
