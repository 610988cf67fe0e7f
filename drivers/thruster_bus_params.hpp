// Which thruster bus the vehicle uses, and its settings (config section `thruster_bus`).
#pragma once

#include <string>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/modbus/modbus_params.hpp"
#include "drivers/socketcan/dronecan_params.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

// The controller's timing, whichever backend: the loop hands commands to an I/O thread that
// measures the heartbeat period (time between acknowledged writes) against these.
struct BusTimingParams {
  int watchdog_ms = 200;         // the controller stops its thrusters after this heartbeat gap
  int degraded_ms = 100;         // a heartbeat gap beyond this reports the bus degraded
  int command_deadline_ms = 66;  // a command older than this is dropped, never sent late
  int close_timeout_ms = 500;    // the wait for the final neutral + disarm to be acknowledged
};

struct ThrusterBusParams {
  std::string backend = "mock";  // mock | modbus | dronecan | ardusub
  BusTimingParams timing;
  ModbusParams modbus;
  DronecanParams dronecan;
  ArdusubParams ardusub;
};

void describe(hal::ParamVisitor& v, BusTimingParams& p);
void describe(hal::ParamVisitor& v, ThrusterBusParams& p);

}  // namespace rovctl::drivers
