// Backend selection for the vehicle commands.
#include "app/vehicle_backends.hpp"

#include "app/errors.hpp"
#include "drivers/camera_factory.hpp"
#include "drivers/monotonic_clock.hpp"
#include "drivers/thruster_bus_factory.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {

hal::StereoRig load_rig(const AppConfig& config) {
  try {
    return estimator::load_stereo_calibration(config.calibration_file);
  } catch (const std::exception& e) {
    throw ConfigError(e.what());  // names the calibration file and the key
  }
}

VehicleBackends make_vehicle_backends(const AppConfig& config, const hal::StereoRig& rig) {
  VehicleBackends b;
  const bool mock_camera = config.camera.backend == "mock";
  const bool mock_bus = config.thruster_bus.backend == "mock";
  if (mock_camera || mock_bus) {
    // Hardware in the loop: the simulated world starts as trial 0 and runs on the wall clock.
    const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);
    const hal::mock::TrialConditions trial = generator.make(0, 1);
    hal::mock::SimParams sim = hal::mock::params_for_trial(config.sim, trial);
    sim.realtime = true;
    b.sim = std::make_unique<hal::mock::SimulatedHal>(sim, config.vehicle, config.station, rig,
                                                      config.marker, trial);
    b.clock = &b.sim->clock();
    b.sensors = &b.sim->sensors();
  } else {
    b.real_clock = std::make_unique<drivers::MonotonicClock>();
    b.clock = b.real_clock.get();
  }
  if (mock_camera) {
    b.camera = &b.sim->camera();
  } else {
    b.real_camera = drivers::make_stereo_camera(config.camera, *b.clock);
    b.camera = b.real_camera.get();
  }
  if (mock_bus) {
    b.bus = &b.sim->bus();
  } else {
    b.real_bus =
        drivers::make_thruster_bus(config.thruster_bus, config.vehicle.thrusters.thrusters.size());
    b.bus = b.real_bus.get();
  }
  if (b.camera == nullptr || b.bus == nullptr) {
    throw ConfigError(config.config_file + ": camera.backend '" + config.camera.backend +
                      "' / thruster_bus.backend '" + config.thruster_bus.backend +
                      "': no such backend");
  }
  return b;
}

}  // namespace rovctl::app
