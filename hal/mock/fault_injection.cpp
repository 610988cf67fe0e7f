// Fault-injection parameter declarations.
#include "hal/mock/fault_injection.hpp"

namespace rovctl::hal::mock {

void describe(ParamVisitor& v, FaultInjection& f) {
  v.param("camera_lost_at_s", f.camera_lost_at_s,
          {"s", -1.0, 1e6, "the stereo camera disappears at this sim time (-1: never)"});
  v.param("camera_timeout_probability", f.camera_timeout_probability,
          {"-", 0.0, 1.0, "probability that a grab times out (dropped frame)"});
  v.param("bus_timeout_at_s", f.bus_timeout_at_s,
          {"s", -1.0, 1e6, "the thruster bus times out from this sim time (-1: never)"});
  v.param("bus_open_fails", f.bus_open_fails, "the thruster bus fails to open");
  v.param(
      "sensor_nan_at_s", f.sensor_nan_at_s,
      {"s", -1.0, 1e6, "depth and attitude read NaN (still flagged valid) from then (-1: never)"});
  v.param("sensor_lost_at_s", f.sensor_lost_at_s,
          {"s", -1.0, 1e6, "the navigation sensors stop answering at this sim time (-1: never)"});
  v.param(
      "charger_fails_at_s", f.charger_fails_at_s,
      {"s", -1.0, 1e6, "the station's charger delivers no current from this sim time (-1: never)"});
  v.param("thruster_dead_index", f.thruster_dead_index,
          {"-", 0, 7, "the thruster (index in vehicle.thrusters) that dies at thruster_dead_at_s"});
  v.param("thruster_dead_at_s", f.thruster_dead_at_s,
          {"s", -1.0, 1e6, "that thruster gives no thrust, rpm 0, ESC fault flag set (-1: never)"});
  v.param("thruster_weak_index", f.thruster_weak_index,
          {"-", 0, 7, "the thruster that turns weak at thruster_weak_at_s"});
  v.param("thruster_weak_at_s", f.thruster_weak_at_s,
          {"s", -1.0, 1e6, "that thruster's thrust is scaled down, no fault flag (-1: never)"});
  v.param("thruster_weak_fraction", f.thruster_weak_fraction,
          {"-", 0.0, 1.0, "the weak thruster's thrust as a fraction of what it should give"});
  v.param("thruster_stuck_index", f.thruster_stuck_index,
          {"-", 0, 7, "the thruster that sticks at thruster_stuck_at_s"});
  v.param("thruster_stuck_at_s", f.thruster_stuck_at_s,
          {"s", -1.0, 1e6, "that thruster holds its thrust and follows no command (-1: never)"});
  const auto timed = [&v](const char* at_key, double& at_s, const char* for_key, double& for_s,
                          const char* what) {
    v.param(at_key, at_s, {"s", -1.0, 1e6, what});
    v.param(for_key, for_s, {"s", -1.0, 1e6, "how long it lasts (-1: for good)"});
  };
  timed("camera_drop_at_s", f.camera_drop_at_s, "camera_drop_for_s", f.camera_drop_for_s,
        "every grab times out from this sim time (-1: never)");
  timed("frozen_frames_at_s", f.frozen_frames_at_s, "frozen_frames_for_s", f.frozen_frames_for_s,
        "the camera delivers the same images again from this sim time (-1: never)");
  timed("stale_frames_at_s", f.stale_frames_at_s, "stale_frames_for_s", f.stale_frames_for_s,
        "frames arrive stale_ms late from this sim time (-1: never)");
  v.param("stale_ms", f.stale_ms, {"ms", 0.0, 10000.0, "the stale frames' extra age"});
  timed("stamp_skew_at_s", f.stamp_skew_at_s, "stamp_skew_for_s", f.stamp_skew_for_s,
        "the right image is stamped stamp_skew_ms early from this sim time (-1: never)");
  v.param("stamp_skew_ms", f.stamp_skew_ms,
          {"ms", 0.0, 10000.0, "the left/right stamp skew injected"});
  timed("camera_black_at_s", f.camera_black_at_s, "camera_black_for_s", f.camera_black_for_s,
        "the right camera's image is black from this sim time (-1: never)");
  v.param("marker_hidden_at_s", f.marker_hidden_at_s,
          {"s", -1.0, 1e6, "the marker is out of every picture from this sim time (-1: never)"});
  v.param(
      "sensor_implausible_at_s", f.sensor_implausible_at_s,
      {"s", -1.0, 1e6, "depth reads sensor_implausible_depth_m from this sim time (-1: never)"});
  v.param("sensor_implausible_depth_m", f.sensor_implausible_depth_m,
          {"m", -1e6, 1e6, "the implausible depth reading injected"});
  timed("tilt_at_s", f.tilt_at_s, "tilt_for_s", f.tilt_for_s,
        "the attitude reads tilt_rad of extra roll from this sim time (-1: never)");
  v.param("tilt_rad", f.tilt_rad, {"rad", 0.0, 3.14, "the extra roll injected"});
  timed("cpu_stall_at_s", f.cpu_stall_at_s, "cpu_stall_for_s", f.cpu_stall_for_s,
        "each grab stalls the tick cpu_stall_ms from this sim time (virtual time; -1: never)");
  v.param("cpu_stall_ms", f.cpu_stall_ms, {"ms", 0.0, 10000.0, "the stall per tick"});
  timed("bus_slow_at_s", f.bus_slow_at_s, "bus_slow_for_s", f.bus_slow_for_s,
        "the thruster bus answers bus_latency_ms late from this sim time (-1: never)");
  v.param("bus_latency_ms", f.bus_latency_ms,
          {"ms", 0.0, 10000.0, "the slow bus's answer time per request"});
  v.param(
      "disarm_ignored_at_s", f.disarm_ignored_at_s,
      {"s", -1.0, 1e6, "the thruster bus acknowledges no disarm from this sim time (-1: never)"});
  v.param("knock_after_seated_s", f.knock_after_seated_s,
          {"s", -1.0, 1e6, "a knock out of the socket once seated this long (-1: never)"});
  v.param("knock_force_n", f.knock_force_n,
          {"N", 0.0, 1000.0, "the knock's force along the docking axis, outwards"});
  v.param("knock_duration_s", f.knock_duration_s, {"s", 0.0, 60.0, "how long the knock pushes"});
  v.param("knock_count", f.knock_count,
          {"-", 0, 100, "knocks, each once the probe has (re-)seated knock_after_seated_s"});
  v.param("surge_after_seated_s", f.surge_after_seated_s,
          {"s", -1.0, 1e6, "a cross-current rises once seated this long (-1: never)"});
  v.param("surge_mps", f.surge_mps,
          {"m/s", 0.0, 2.0, "the cross-current's speed (across the docking axis, to station +x)"});
  v.param("surge_ramp_s", f.surge_ramp_s, {"s", 0.0, 600.0, "the cross-current's rise time"});
  v.param("camera_lost_after_seated_s", f.camera_lost_after_seated_s,
          {"s", -1.0, 1e6, "the stereo camera disappears once seated this long (-1: never)"});
}

}  // namespace rovctl::hal::mock
