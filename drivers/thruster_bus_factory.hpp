// Builds the configured real thruster bus; the mock backend is the application's to build.
#pragma once

#include <cstddef>
#include <memory>

#include "drivers/thruster_bus_params.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::drivers {

// nullptr for backend "mock". The bus is not opened: call open() and report its error.
std::unique_ptr<hal::ThrusterBus> make_thruster_bus(const ThrusterBusParams& params,
                                                    std::size_t thruster_count);

}  // namespace rovctl::drivers
