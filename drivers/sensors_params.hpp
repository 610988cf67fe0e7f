// Where the vehicle's navigation sensors come from (config section `sensors`).
#pragma once

#include <string>

#include "drivers/mavlink/ardusub_params.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

struct SensorsParams {
  std::string backend = "mock";  // mock: the simulated world's (none without one) | ardusub
  ArdusubSensorParams ardusub;
};

void describe(hal::ParamVisitor& v, SensorsParams& p);

}  // namespace rovctl::drivers
