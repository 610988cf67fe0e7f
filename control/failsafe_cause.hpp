// Why the failsafe tripped: one value per monitored fault, with its name in the logs and its key
// in the policy table (control.failsafe.policy.<key>).
#pragma once

#include <cstddef>
#include <string_view>

namespace rovctl::control {

enum class FailsafeCause {
  none,
  camera_lost,          // the camera device lost (or its stream ended)
  bus_fault,            // the thruster bus timed out or is dead
  estimate_not_finite,  // NaN/inf in the pose estimate or its fitness
  wrench_not_finite,    // NaN/inf in the commanded wrench
  mission_failed,       // the mission gave up (retries exhausted)
  mission_time,         // the mission ran longer than allowed (CHARGING not counted)
  vision_lost,          // consecutive grab timeouts beyond the allowance
  vision_stale,         // the newest frame older than allowed
  vision_frozen,        // identical images tick after tick (a hung driver)
  stereo_skew,          // left and right captured too far apart
  camera_dead,          // one or both images constant (black, covered, a dead sensor)
  bus_slow,             // bus writes degraded for too many ticks
  sensor_lost,          // the navigation sensors stopped answering
  sensor_nan,           // a sensor reading flagged valid but not finite
  sensor_implausible,   // a reading outside what the vehicle can physically report
  attitude_limit,       // roll or pitch beyond the limit
  search_time,          // SEARCH ran out of time (mission.search_timeout_s)
  cpu_overrun,          // consecutive ticks that overran their period
  thruster_fault,       // failed thrusters left x, y, z or yaw uncontrollable
  leak,                 // water inside the hull (the sensors' leak detector)
  battery_low,          // state of charge below control.failsafe.min_soc_fraction
  disarm_unacked,       // the bus did not acknowledge the failsafe's disarm
};
inline constexpr std::size_t kFailsafeCauseCount =
    static_cast<std::size_t>(FailsafeCause::disarm_unacked) + 1;

// For the logs: "camera lost".
const char* to_string(FailsafeCause c);
// For configs and the command line: "camera_lost".
const char* cause_key(FailsafeCause c);
// The cause with that key; false when none has it.
bool cause_from_key(std::string_view key, FailsafeCause& cause);

}  // namespace rovctl::control
