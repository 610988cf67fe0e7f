// Parameter declarations of the DroneCAN thruster bus.
#include "drivers/socketcan/dronecan_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, DronecanParams& p) {
  v.param("interface", p.interface, "SocketCAN interface of the ESC bus (e.g. can0)");
  v.param("node_id", p.node_id,
          {"-", 1, 127, "rovctl's DroneCAN node ID (must differ from every ESC's)"});
  v.param("priority", p.priority,
          {"-", 0, 31, "DroneCAN transfer priority of the ESC commands (0 = highest)"});
  v.param("status_timeout_ms", p.status_timeout_ms,
          {"ms", 10, 10000, "an ESC whose esc.Status is older than this is reported stale"});
  v.param("max_consecutive_failures", p.max_consecutive_failures,
          {"-", 1, 100, "failed ticks in a row after which the bus reports a fault (failsafe)"});
}

}  // namespace rovctl::drivers
