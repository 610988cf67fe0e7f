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
