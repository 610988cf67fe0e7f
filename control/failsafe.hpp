// Run-time failsafes: a lost camera, a faulted thruster bus, NaN in the estimate or the wrench,
// or the mission's limits put the vehicle in the safe state (neutral or disarmed). Latching: only
// reset() (a new mission, an operator) clears it. Trips are queued as events; no allocation.
// Seated in the station (charging, re-seating, undocking) a dead stop would leave the vehicle
// hanging on its probe in the current; where the thrusters still obey (not a bus fault, not a
// NaN wrench) it first backs out of the socket open loop for backout_s, then goes safe.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstddef>

#include "control/control_params.hpp"
#include "control/mission.hpp"
#include "control/thruster_effectiveness.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::control {

enum class FailsafeCause {
  none,
  camera_lost,          // device lost, or too many consecutive timeouts
  bus_fault,            // bus fault, or degraded for too long
  estimate_not_finite,  // NaN/inf in the pose estimate or its fitness
  wrench_not_finite,    // NaN/inf in the commanded wrench
  mission_failed,       // the mission gave up (retries exhausted, search timed out)
  mission_time,         // the mission ran longer than allowed
  thruster_fault,       // failed thrusters left x, y, z or yaw uncontrollable
};
const char* to_string(FailsafeCause c);

// back_out: push out of the socket along the docking axis, open loop (the failing input is not
// trusted), for FailsafeParams::backout_s; then the configured neutral or disarm.
enum class SafeAction { none, neutral, disarm, back_out };
const char* to_string(SafeAction a);

struct FailsafeInput {
  std::chrono::nanoseconds now{0};
  hal::GrabStatus grab = hal::GrabStatus::ok;
  hal::BusStatus bus = hal::BusStatus::ok;  // status of the last write (or arm)
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();  // this tick's estimate
  double fitness = 0.0;
  Wrench wrench_body = Wrench::Zero();  // this tick's commanded wrench
  MissionState mission = MissionState::search;
  bool at_station = false;  // the probe in or at the socket (Mission::at_station())
  // The thrusters still allocated cannot control x, y, z and yaw (ThrusterHealth, allocator).
  bool thrusters_uncontrollable = false;
};

struct FailsafeEvent {
  std::chrono::nanoseconds time{0};
  FailsafeCause cause = FailsafeCause::none;
  SafeAction action = SafeAction::none;
};

class Failsafe {
 public:
  static constexpr std::size_t kEventCapacity = 16;

  explicit Failsafe(const FailsafeParams& params);

  // One tick's checks; returns the action to take now (none while healthy). The first cause
  // found latches. Check the wrench before the thrusters are written. No allocation.
  SafeAction update(const FailsafeInput& in);

  bool tripped() const { return cause_ != FailsafeCause::none; }
  FailsafeCause cause() const { return cause_; }
  SafeAction action() const {
    return !tripped() ? SafeAction::none : backing_out_ ? SafeAction::back_out : action_;
  }
  bool backing_out() const { return tripped() && backing_out_; }
  // Clears the latch and the counters; the mission clock restarts at `now`.
  void reset(std::chrono::nanoseconds now);

  bool pop_event(FailsafeEvent& event);

 private:
  FailsafeCause check(const FailsafeInput& in);
  void push_event(const FailsafeEvent& e);

  FailsafeParams p_;
  SafeAction action_;
  FailsafeCause cause_ = FailsafeCause::none;
  bool started_ = false;
  std::chrono::nanoseconds start_{0};
  bool backing_out_ = false;
  std::chrono::nanoseconds back_out_since_{0};
  int camera_timeouts_ = 0;
  int bus_degraded_ = 0;
  std::array<FailsafeEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
};

}  // namespace rovctl::control
