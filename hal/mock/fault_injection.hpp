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

  // Whether a fault scheduled at `at_s` (negative: never) is active at `now`.
  static bool active(double at_s, std::chrono::nanoseconds now) {
    return at_s >= 0.0 && std::chrono::duration<double>(now).count() >= at_s;
  }
};

void describe(ParamVisitor& v, FaultInjection& f);

}  // namespace rovctl::hal::mock
