// The backends `rovctl run`, `check` and `thrusters` fly on, as the config names them: real
// drivers, the mock HAL, or a mix (e.g. replayed images with a real Modbus bus). Where any part
// is simulated, the simulated world runs in real time beside it.
#pragma once

#include <memory>
#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/mock_ardusub_endpoint.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/sensors.hpp"
#include "hal/interfaces/stereo_camera.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/mock_ardusub.hpp"
#include "hal/mock/simulated_hal.hpp"
#include "hal/mock/trial_generator.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct VehicleBackends {
  std::unique_ptr<hal::mock::SimulatedHal> sim;  // when any backend is mock
  // A trial with thruster_bus.backend ardusub: the mock ArduSub on the simulated vehicle and its
  // MAVLink endpoint, which the real driver (real_bus) talks to over loopback UDP through
  // sim_bus. Declared before real_bus: the driver's last disarm still finds its peer.
  std::unique_ptr<hal::mock::MockArdusub> mock_ardusub;
  std::unique_ptr<MockArdusubEndpoint> ardusub_peer;
  std::unique_ptr<hal::Clock> real_clock;  // when none is
  std::unique_ptr<hal::StereoCamera> real_camera;
  std::unique_ptr<hal::Sensors> real_sensors;  // outlives real_bus, which may feed it
  std::unique_ptr<hal::ThrusterBus> real_bus;
  std::unique_ptr<hal::ThrusterBus> sim_bus;  // SteppedArdusubBus over real_bus
  hal::Clock* clock = nullptr;
  hal::StereoCamera* camera = nullptr;
  hal::ThrusterBus* bus = nullptr;
  hal::Sensors* sensors = nullptr;
};

// Builds (does not open) the backends. Throws ConfigError on an unknown combination.
VehicleBackends make_vehicle_backends(const AppConfig& config, const hal::StereoRig& rig);

// The mock HAL, set up for one docking trial (virtual time unless `realtime`). With
// thruster_bus.backend ardusub the thrusters are flown through the ArduSub driver and the mock
// ArduSub over loopback UDP (and sensors.backend ardusub reads ArduSub's streams).
VehicleBackends make_trial_backends(const AppConfig& config, const hal::StereoRig& rig,
                                    const hal::mock::TrialConditions& trial, bool realtime);

// Loads the calibration named by the config and checks its plausibility (validate_stereo_rig);
// ConfigError naming the file, line and key on failure.
hal::StereoRig load_rig(const AppConfig& config);

}  // namespace rovctl::app
