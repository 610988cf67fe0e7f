// Parameter declarations of the thruster bus selection.
#include "drivers/thruster_bus_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, ThrusterBusParams& p) {
  v.param("backend", p.backend,
          "mock: simulated vehicle; modbus: thruster controller on Modbus RTU/TCP; dronecan: "
          "ESCs on CAN (uavcan.equipment.esc.RawCommand)",
          {"mock", "modbus", "dronecan"});
  v.section("modbus", "Modbus thruster controller (backend modbus)",
            [&p](hal::ParamVisitor& s) { describe(s, p.modbus); });
  v.section("dronecan", "DroneCAN ESCs over SocketCAN (backend dronecan)",
            [&p](hal::ParamVisitor& s) { describe(s, p.dronecan); });
}

}  // namespace rovctl::drivers
