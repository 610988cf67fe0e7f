// Run-time failsafes: each monitored fault (FailsafeCause) puts the vehicle in the safe state its
// policy names (control.failsafe.policy): transient causes recover by themselves once gone for
// recover_ticks (the loop resumes the mission from SEARCH), hardware causes latch until reset()
// (an operator's START). Every trip, recovery and latch is queued as an event; no allocation.
// Seated in the station (charging, re-seating, undocking) a dead stop would leave the vehicle
// hanging on its probe in the current; where the thrusters still obey (not a bus fault, not a
// NaN wrench) it first backs out of the socket open loop for backout_s, then goes safe.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

#include "control/control_params.hpp"
#include "control/failsafe_cause.hpp"
#include "control/mission.hpp"
#include "control/thruster_effectiveness.hpp"
#include "hal/interfaces/sensors.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::control {

// back_out: push out of the socket along the docking axis, open loop (the failing input is not
// trusted), for FailsafeParams::backout_s; then the policy's neutral or disarm.
enum class SafeAction { none, neutral, disarm, back_out };
const char* to_string(SafeAction a);

struct FailsafeInput {
  std::chrono::nanoseconds now{0};
  std::uint64_t tick = 0;  // for the log
  hal::GrabStatus grab = hal::GrabStatus::ok;
  hal::BusStatus bus = hal::BusStatus::ok;  // status of the last write (or arm)
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();  // this tick's estimate
  double fitness = 0.0;
  Wrench wrench_body = Wrench::Zero();  // this tick's commanded wrench
  MissionState mission = MissionState::search;
  bool search_timed_out = false;  // the mission failed because SEARCH ran out of time
  bool at_station = false;        // the probe in or at the socket (Mission::at_station())
  // The images of this tick's grab (when ok), from the frame monitor.
  int identical_frames = 0;                 // ticks in a row whose images equal the previous ones
  bool image_dead = false;                  // one or both images constant
  std::chrono::nanoseconds frame_age{0};    // now - capture stamp
  std::chrono::nanoseconds stereo_skew{0};  // |left stamp - right stamp|
  // The sensors: whether they are fitted, whether this tick's read answered, and what it read.
  bool sensors_fitted = false;
  bool sensors_answered = false;
  const hal::SensorReadings* readings = nullptr;
  bool overrun = false;  // releases were skipped right before this tick
  // The thrusters still allocated cannot control x, y, z and yaw (ThrusterHealth, allocator).
  bool thrusters_uncontrollable = false;
  // A disarm the failsafe sent was not acknowledged by the bus (the ESCs may still be armed).
  bool disarm_unacked = false;
};

enum class FailsafeEventKind { trip, safe, recovered, latched };
const char* to_string(FailsafeEventKind k);

struct FailsafeEvent {
  std::chrono::nanoseconds time{0};
  std::uint64_t tick = 0;
  FailsafeEventKind kind = FailsafeEventKind::trip;
  FailsafeCause cause = FailsafeCause::none;
  SafeAction action = SafeAction::none;
};

class Failsafe {
 public:
  static constexpr std::size_t kEventCapacity = 16;

  // Throws std::invalid_argument on an unknown action or recovery (the config loader checks them
  // first).
  explicit Failsafe(const FailsafeParams& params);

  // One tick's checks; returns the action to take now (none while healthy). The first cause
  // found trips; a latching cause found during a recoverable trip takes over. Check the wrench
  // before the thrusters are written. No allocation.
  SafeAction update(const FailsafeInput& in);

  bool tripped() const { return cause_ != FailsafeCause::none; }
  FailsafeCause cause() const { return cause_; }
  SafeAction action() const {
    return !tripped() ? SafeAction::none : backing_out_ ? SafeAction::back_out : action_;
  }
  bool backing_out() const { return tripped() && backing_out_; }
  // Tripped and waiting for the cause to clear (an "auto" cause that has not latched).
  bool awaiting_recovery() const { return tripped() && !latched_; }
  // True once after the tick on which a recoverable trip cleared (the loop resumes the mission).
  bool take_recovered() {
    const bool r = recovered_;
    recovered_ = false;
    return r;
  }
  // Clears the trip and the counters; the mission clock restarts at `now`.
  void reset(std::chrono::nanoseconds now);

  bool pop_event(FailsafeEvent& event);

 private:
  FailsafeCause check(const FailsafeInput& in);
  void trip(FailsafeCause c, const FailsafeInput& in);
  void push_event(const FailsafeInput& in, FailsafeEventKind kind, SafeAction action);

  FailsafeParams p_;
  std::array<SafeAction, kFailsafeCauseCount> actions_{};
  std::array<bool, kFailsafeCauseCount> recovers_{};
  SafeAction action_ = SafeAction::disarm;
  FailsafeCause cause_ = FailsafeCause::none;
  bool latched_ = false;
  bool recovered_ = false;
  std::chrono::nanoseconds tripped_at_{0};
  int healthy_ticks_ = 0;
  bool started_ = false;
  std::chrono::nanoseconds last_now_{0};
  double mission_s_ = 0.0;  // CHARGING not counted
  bool backing_out_ = false;
  std::chrono::nanoseconds back_out_since_{0};
  int camera_timeouts_ = 0;
  int bus_degraded_ = 0;
  int sensors_silent_ = 0;
  int overruns_ = 0;
  std::array<FailsafeEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
};

}  // namespace rovctl::control
