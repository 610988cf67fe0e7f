// Thruster bus selection by the config's backend name.
#include "drivers/thruster_bus_factory.hpp"

#include "drivers/modbus/modbus_thruster_bus.hpp"
#include "drivers/socketcan/dronecan_thruster_bus.hpp"

namespace rovctl::drivers {

std::unique_ptr<hal::ThrusterBus> make_thruster_bus(const ThrusterBusParams& params,
                                                    std::size_t thruster_count) {
  if (params.backend == "modbus") {
    return std::make_unique<ModbusThrusterBus>(params.modbus, thruster_count);
  }
  if (params.backend == "dronecan") {
    return std::make_unique<DronecanThrusterBus>(params.dronecan, thruster_count);
  }
  return nullptr;
}

}  // namespace rovctl::drivers
