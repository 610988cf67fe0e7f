// Which thruster bus the vehicle uses, and its settings (config section `thruster_bus`).
#pragma once

#include <string>

#include "drivers/modbus/modbus_params.hpp"
#include "drivers/socketcan/dronecan_params.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::drivers {

struct ThrusterBusParams {
  std::string backend = "mock";  // mock | modbus | dronecan
  ModbusParams modbus;
  DronecanParams dronecan;
};

void describe(hal::ParamVisitor& v, ThrusterBusParams& p);

}  // namespace rovctl::drivers
