// Parameter declarations of the thruster bus selection.
#include "drivers/thruster_bus_params.hpp"

namespace rovctl::drivers {

void describe(hal::ParamVisitor& v, BusTimingParams& p) {
  v.param("watchdog_ms", p.watchdog_ms,
          {"ms", 20, 5000,
           "heartbeat gap after which the thruster controller stops (deploy/modbus-register-map.md"
           " register 16; on ArduSub its FS_PILOT_TIMEOUT); a longer gap reports the bus fault, "
           "which trips the failsafe"});
  v.param("degraded_ms", p.degraded_ms,
          {"ms", 1, 5000,
           "heartbeat gap (time since the last acknowledged write) beyond which the bus reports "
           "degraded; below watchdog_ms. A gap this machine made itself (the tick or the bus's I/O "
           "thread held off the CPU) is not held against the bus until watchdog_ms"});
  v.param("command_deadline_ms", p.command_deadline_ms,
          {"ms", 1, 1000,
           "age beyond which a command still waiting for the bus is dropped instead of sent"});
  v.param("close_timeout_ms", p.close_timeout_ms,
          {"ms", 10, 10000,
           "wait for the final neutral and disarm to be acknowledged on shutdown; `rovctl run` "
           "exits 1 when they were not"});
}

void describe(hal::ParamVisitor& v, ThrusterBusParams& p) {
  v.param("backend", p.backend,
          "mock: simulated vehicle; modbus: thruster controller on Modbus RTU/TCP; dronecan: "
          "ESCs on CAN (uavcan.equipment.esc.RawCommand); ardusub: ArduSub over MAVLink "
          "(MANUAL_CONTROL)",
          {"mock", "modbus", "dronecan", "ardusub"});
  v.section(
      "timing",
      "heartbeat and command deadlines of the thruster controller (modbus, dronecan, ardusub)",
      [&p](hal::ParamVisitor& s) { describe(s, p.timing); });
  v.section("modbus", "Modbus thruster controller (backend modbus)",
            [&p](hal::ParamVisitor& s) { describe(s, p.modbus); });
  v.section("dronecan", "DroneCAN ESCs over SocketCAN (backend dronecan)",
            [&p](hal::ParamVisitor& s) { describe(s, p.dronecan); });
  v.section("ardusub", "ArduSub autopilot over MAVLink (backend ardusub)",
            [&p](hal::ParamVisitor& s) { describe(s, p.ardusub); });
}

}  // namespace rovctl::drivers
