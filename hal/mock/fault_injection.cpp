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
}

}  // namespace rovctl::hal::mock
