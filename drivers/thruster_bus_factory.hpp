// Builds the configured real thruster bus; the mock backend is the application's to build.
#pragma once

#include <cstddef>
#include <memory>

#include "drivers/thruster_bus_params.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::drivers {

// nullptr for backend "mock". The bus is not opened: call open() and report its error.
// `layout` is the vehicle's: its thruster count, and for ArduSub the geometry that turns the
// allocator's fractions back into the wrench.
std::unique_ptr<hal::ThrusterBus> make_thruster_bus(const ThrusterBusParams& params,
                                                    const hal::ThrusterLayout& layout);

}  // namespace rovctl::drivers
