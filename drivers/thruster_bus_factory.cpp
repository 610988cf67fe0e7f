// Thruster bus selection by the config's backend name.
#include "drivers/thruster_bus_factory.hpp"

#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "drivers/modbus/modbus_thruster_bus.hpp"
#include "drivers/socketcan/dronecan_thruster_bus.hpp"

namespace rovctl::drivers {

std::unique_ptr<hal::ThrusterBus> make_thruster_bus(const ThrusterBusParams& params,
                                                    const hal::ThrusterLayout& layout) {
  const std::size_t thruster_count = layout.thrusters.size();
  if (params.backend == "modbus") {
    return std::make_unique<ModbusThrusterBus>(params.modbus, thruster_count);
  }
  if (params.backend == "dronecan") {
    return std::make_unique<DronecanThrusterBus>(params.dronecan, thruster_count);
  }
  if (params.backend == "ardusub") {
    return std::make_unique<ArdusubThrusterBus>(params.ardusub, layout);
  }
  return nullptr;
}

}  // namespace rovctl::drivers
