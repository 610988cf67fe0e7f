// Backend selection for the vehicle commands.
#include "app/runtime/vehicle_backends.hpp"

#include "app/runtime/config_validation.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/stepped_ardusub_bus.hpp"
#include "drivers/camera_factory.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "drivers/monotonic_clock.hpp"
#include "drivers/thruster_bus_factory.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {

hal::StereoRig load_rig(const AppConfig& config) {
  hal::StereoRig rig;
  try {
    rig = estimator::load_stereo_calibration(config.calibration_file);
  } catch (const std::exception& e) {
    throw ConfigError(e.what());  // names the calibration file, line and key
  }
  // The same plausibility for every command: `run` must not arm on what `check` rejects.
  validate_stereo_rig(rig, config.calibration_file, config.validation);
  return rig;
}

namespace {

std::unique_ptr<hal::mock::SimulatedHal> make_sim(const AppConfig& config,
                                                  const hal::StereoRig& rig,
                                                  const hal::mock::TrialConditions& trial,
                                                  bool realtime) {
  hal::mock::SimParams sim = hal::mock::params_for_trial(config.sim, trial);
  sim.realtime = realtime;
  const drivers::V4l2CameraParams& cam = config.camera.v4l2;
  sim.camera.exposure_ms = cam.auto_exposure ? 0.0 : cam.exposure_time_us / 1000.0;
  return std::make_unique<hal::mock::SimulatedHal>(sim, config.vehicle, config.station, rig,
                                                   config.marker, trial);
}

// Hardware in the loop without a vehicle: rovctl's ArduSub driver against the mock ArduSub, on
// ports the kernel picks so that parallel trials never collide.
void fly_through_mock_ardusub(const AppConfig& config, VehicleBackends& b) {
  const drivers::ArdusubParams& bus_params = config.thruster_bus.ardusub;
  b.mock_ardusub = std::make_unique<hal::mock::MockArdusub>(b.sim->world(), config.sim.ardusub);
  b.ardusub_peer = std::make_unique<MockArdusubEndpoint>(
      *b.mock_ardusub, *b.clock, bus_params.gcs_system_id, bus_params.vehicle_system_id);
  std::string error;
  if (!b.ardusub_peer->open(error)) throw std::runtime_error("mock ArduSub: " + error);
  drivers::ArdusubParams params = bus_params;
  params.link = "udpout:127.0.0.1:" + std::to_string(b.ardusub_peer->port());
  auto bus = std::make_unique<drivers::ArdusubThrusterBus>(params, config.vehicle.thrusters);
  drivers::ArdusubSensors* sensors = nullptr;
  if (config.sensors.backend == "ardusub") {
    auto s = std::make_unique<drivers::ArdusubSensors>(config.sensors.ardusub, *b.clock);
    sensors = s.get();
    bus->attach(*s);
    b.sensors = sensors;
    b.real_sensors = std::move(s);
  }
  bus->set_wait_hook([peer = b.ardusub_peer.get()] { peer->service(); });
  b.sim_bus = std::make_unique<SteppedArdusubBus>(*bus, *b.ardusub_peer, sensors);
  b.real_bus = std::move(bus);
  b.bus = b.sim_bus.get();
}

}  // namespace

VehicleBackends make_trial_backends(const AppConfig& config, const hal::StereoRig& rig,
                                    const hal::mock::TrialConditions& trial, bool realtime) {
  VehicleBackends b;
  b.sim = make_sim(config, rig, trial, realtime);
  b.clock = &b.sim->clock();
  b.sensors = &b.sim->sensors();
  b.camera = &b.sim->camera();
  b.bus = &b.sim->bus();
  if (config.thruster_bus.backend == "ardusub") fly_through_mock_ardusub(config, b);
  return b;
}

VehicleBackends make_vehicle_backends(const AppConfig& config, const hal::StereoRig& rig) {
  VehicleBackends b;
  const bool mock_camera = config.camera.backend == "mock";
  const bool mock_bus = config.thruster_bus.backend == "mock";
  if (mock_camera || mock_bus) {
    // Hardware in the loop: the simulated world starts as trial 0 and runs on the wall clock.
    const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);
    b.sim = make_sim(config, rig, generator.make(0, 1), true);
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
    b.real_bus = drivers::make_thruster_bus(config.thruster_bus, config.vehicle.thrusters);
    b.bus = b.real_bus.get();
  }
  if (config.sensors.backend == "ardusub") {
    // The bus owns the MAVLink socket, so its I/O thread feeds the sensors too.
    auto* ardusub = dynamic_cast<drivers::ArdusubThrusterBus*>(b.real_bus.get());
    if (ardusub == nullptr) {
      throw ConfigError(config.config_file +
                        ": sensors.backend ardusub needs thruster_bus.backend ardusub");
    }
    auto sensors = std::make_unique<drivers::ArdusubSensors>(config.sensors.ardusub, *b.clock);
    ardusub->attach(*sensors);
    b.sensors = sensors.get();
    b.real_sensors = std::move(sensors);
  }
  if (b.camera == nullptr || b.bus == nullptr) {
    throw ConfigError(config.config_file + ": camera.backend '" + config.camera.backend +
                      "' / thruster_bus.backend '" + config.thruster_bus.backend +
                      "': no such backend");
  }
  return b;
}

}  // namespace rovctl::app
