// The backends `rovctl run`, `check` and `thrusters` fly on, as the config names them: real
// drivers, the mock HAL, or a mix (e.g. replayed images with a real Modbus bus). Where any part
// is simulated, the simulated world runs in real time beside it.
#pragma once

#include <memory>
#include <string>

#include "app/app_config.hpp"
#include "hal/clock.hpp"
#include "hal/mock/simulated_hal.hpp"
#include "hal/sensors.hpp"
#include "hal/stereo_camera.hpp"
#include "hal/stereo_rig.hpp"
#include "hal/thruster_bus.hpp"

namespace rovctl::app {

struct VehicleBackends {
  std::unique_ptr<hal::mock::SimulatedHal> sim;  // when any backend is mock
  std::unique_ptr<hal::Clock> real_clock;        // when none is
  std::unique_ptr<hal::StereoCamera> real_camera;
  std::unique_ptr<hal::ThrusterBus> real_bus;
  hal::Clock* clock = nullptr;
  hal::StereoCamera* camera = nullptr;
  hal::ThrusterBus* bus = nullptr;
  hal::Sensors* sensors = nullptr;
};

// Builds (does not open) the backends. Throws ConfigError on an unknown combination.
VehicleBackends make_vehicle_backends(const AppConfig& config, const hal::StereoRig& rig);

// Loads the calibration named by the config; ConfigError naming the file on failure.
hal::StereoRig load_rig(const AppConfig& config);

}  // namespace rovctl::app
