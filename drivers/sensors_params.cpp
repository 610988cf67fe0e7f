// Parameter declarations of the sensors selection.
#include "drivers/sensors_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, SensorsParams& p) {
  v.param("backend", p.backend,
          "mock: the simulated world's sensors when any backend is simulated, none otherwise; "
          "ardusub: ArduSub's attitude, depth, battery and leak over the ardusub thruster bus's "
          "MAVLink link (needs thruster_bus.backend ardusub)",
          {"mock", "ardusub"});
  v.section("ardusub", "ArduSub's telemetry streams (backend ardusub)",
            [&p](hal::ParamVisitor& s) { describe(s, p.ardusub); });
}

}  // namespace rovctl::drivers
