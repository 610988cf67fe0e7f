// Hardware faults the mock HAL injects at run time (camera gone, bus timeout, NaN readings), so
// the application's failsafes can be exercised. Times are simulation time since the trial start.
#pragma once

#include <chrono>

#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

struct FaultInjection {
  double camera_lost_at_s = -1.0;           // grab() reports device_lost from then on (< 0: never)
  double camera_timeout_probability = 0.0;  // each grab() times out with this probability
  double bus_timeout_at_s = -1.0;    // thruster bus writes/reads time out from then on (< 0: never)
  bool bus_open_fails = false;       // ThrusterBus::open() fails
  double sensor_nan_at_s = -1.0;     // depth and attitude read as NaN (flagged valid) from then on
  double sensor_lost_at_s = -1.0;    // Sensors::read() returns false from then on
  double charger_fails_at_s = -1.0;  // the station's charger delivers no current from then on

  // One thruster (index into vehicle.thrusters) failing at a sim time (< 0: never). Dead: no
  // thrust, rpm 0 and its ESC's fault flag set. Weak (a fouled propeller, a worn motor): thrust
  // scaled by thruster_weak_fraction, no flag, rpm low for the command. Stuck (a jammed ESC):
  // holds the thrust it had and follows no further command.
  int thruster_dead_index = 0;
  double thruster_dead_at_s = -1.0;
  int thruster_weak_index = 0;
  double thruster_weak_at_s = -1.0;
  double thruster_weak_fraction = 0.3;
  int thruster_stuck_index = 0;
  double thruster_stuck_at_s = -1.0;
  // Faults of the images and readings the failsafe must catch, each from `*_at_s` for `*_for_s`
  // (< 0: for good): a burst of grab timeouts; the same images delivered again and again (a hung
  // driver, stamps still advancing); frames delivered stale_ms late; the right image stamped
  // stamp_skew_ms before the left; the right camera black (dead sensor, lens covered).
  double camera_drop_at_s = -1.0;
  double camera_drop_for_s = 1.0;
  double frozen_frames_at_s = -1.0;
  double frozen_frames_for_s = 1.0;
  double stale_frames_at_s = -1.0;
  double stale_frames_for_s = 1.0;
  double stale_ms = 500.0;
  double stamp_skew_at_s = -1.0;
  double stamp_skew_for_s = 1.0;
  double stamp_skew_ms = 500.0;
  double camera_black_at_s = -1.0;
  double camera_black_for_s = -1.0;
  // The marker out of every picture (the camera sees open water): a search that never ends.
  double marker_hidden_at_s = -1.0;
  // Depth reads implausibly (sensor_implausible_depth_m, flagged valid) from then on.
  double sensor_implausible_at_s = -1.0;
  double sensor_implausible_depth_m = -1000.0;
  // The attitude reads tilt_rad of extra roll for tilt_for_s (a knock the vehicle rights).
  double tilt_at_s = -1.0;
  double tilt_for_s = 1.0;
  double tilt_rad = 0.8;
  // Each grab takes cpu_stall_ms of the tick's time (virtual time only): the tick overruns.
  double cpu_stall_at_s = -1.0;
  double cpu_stall_for_s = 1.0;
  double cpu_stall_ms = 50.0;
  // The thruster bus's peer answers each request bus_latency_ms late for bus_slow_for_s (in
  // virtual time: the sim stays deterministic); from disarm_ignored_at_s it does not acknowledge
  // a disarm (the ESCs stay armed).
  double bus_slow_at_s = -1.0;
  double bus_slow_for_s = 1.0;
  double bus_latency_ms = 100.0;
  double disarm_ignored_at_s = -1.0;

  // The recharging mission's faults, timed by the seat rather than the clock (a trial docks after
  // 15-40 s): each comes once the probe has been seated that long (< 0: never).
  // A knock out of the socket (a diver's fin, a snagged line): knock_force_n along the docking
  // axis, outwards, for knock_duration_s; again each time the probe has re-seated that long, up to
  // knock_count knocks.
  double knock_after_seated_s = -1.0;
  double knock_force_n = 40.0;
  double knock_duration_s = 0.5;
  int knock_count = 1;
  // A cross-current across the docking axis (towards the station's +x) that rises to surge_mps
  // over surge_ramp_s and stays: more than the seated hold resists (from about 0.22 m/s it turns
  // the vehicle about its probe past mission.recharge.overload_yaw_rad, at about 0.28 m/s out of
  // the seat), less than the vehicle can fight free in the water (about 0.35 m/s).
  double surge_after_seated_s = -1.0;
  double surge_mps = 0.26;
  double surge_ramp_s = 5.0;
  // The stereo camera is lost (a failsafe while charging).
  double camera_lost_after_seated_s = -1.0;

  // Whether a fault scheduled at `at_s` (negative: never) is active at `now`.
  static bool active(double at_s, std::chrono::nanoseconds now) {
    return at_s >= 0.0 && std::chrono::duration<double>(now).count() >= at_s;
  }
  // Whether a fault from `at_s` lasting `for_s` (negative: for good) is active at `now`.
  static bool active(double at_s, double for_s, std::chrono::nanoseconds now) {
    return active(at_s, now) &&
           (for_s < 0.0 || std::chrono::duration<double>(now).count() < at_s + for_s);
  }
};

void describe(ParamVisitor& v, FaultInjection& f);

}  // namespace rovctl::hal::mock
