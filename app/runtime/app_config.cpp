// Top-level config sections; each section's parameters are declared beside their own struct.
#include "app/runtime/app_config.hpp"

#include <filesystem>

#include "app/runtime/config_loader.hpp"
#include "app/runtime/errors.hpp"

namespace rovctl::app {

void describe(hal::ParamVisitor& v, AppConfig& c) {
  v.path("calibration", c.calibration_file,
         "OpenCV stereo calibration YAML (K1, D1, K2, D2, R, T, image size)", true);
  v.section("marker", "the docking marker: three coloured spheres",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.marker); });
  v.section("vehicle", "vehicle geometry: camera mount, docking probe, thrusters",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.vehicle); });
  v.section("estimator", "stereo pose estimator: RM-GA, fitness samples, search volume, mode",
            [&c](hal::ParamVisitor& s) { estimator::describe(s, c.estimator); });
  v.section("station", "docking station: charging socket relative to the marker",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.station); });
  v.section("camera", "stereo camera: mock (simulated), two V4L2 cameras, or a recorded dive",
            [&c](hal::ParamVisitor& s) { drivers::describe(s, c.camera); });
  v.section("thruster_bus",
            "thruster bus: mock, Modbus thruster controller, DroneCAN ESCs or ArduSub (MAVLink)",
            [&c](hal::ParamVisitor& s) { drivers::describe(s, c.thruster_bus); });
  v.section("sensors", "navigation sensors: the simulated world's, or ArduSub's over MAVLink",
            [&c](hal::ParamVisitor& s) { drivers::describe(s, c.sensors); });
  v.section("control", "visual servo, thruster allocation and failsafes",
            [&c](hal::ParamVisitor& s) { control::describe(s, c.control); });
  v.section("mission", "docking mission: thresholds, timeouts and retries",
            [&c](hal::ParamVisitor& s) { control::describe(s, c.mission); });
  v.section("scheduler", "the cyclic executive: period, real-time priority, stage budgets",
            [&c](hal::ParamVisitor& s) { describe(s, c.scheduler); });
  v.section("telemetry", "per-tick telemetry ring and its CSV writer",
            [&c](hal::ParamVisitor& s) { describe(s, c.telemetry); });
  v.section("operator_view", "live operator view in a browser: cameras, estimate, ABORT/START",
            [&c](hal::ParamVisitor& s) { describe(s, c.operator_view); });
  v.section("sim", "simulated world and mock HAL: dynamics, current, station, cameras, trials",
            [&c](hal::ParamVisitor& s) { hal::mock::describe(s, c.sim); });
  v.section("validation",
            "plausibility limits of the calibration, thruster layout and marker, checked before "
            "any device is opened",
            [&c](hal::ParamVisitor& s) { describe(s, c.validation); });
}

AppConfig load_app_config(const std::string& file) {
  AppConfig config;
  load_yaml_file(
      file, [&config](hal::ParamVisitor& v) { describe(v, config); }, &config.key_lines);
  config.config_file = file;
  // Cross-field checks the per-key ranges cannot express, before any command touches hardware.
  try {
    config.estimator.validate();
  } catch (const std::invalid_argument& e) {
    throw ConfigError(file + ": " + e.what());
  }
  validate_app_config(config);
  return config;
}

std::string default_config_path() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/rovctl/config/sim.yaml";
    if (fs::is_regular_file(installed)) return installed.string();
  }
  const fs::path source = fs::path(ROVCTL_SOURCE_DIR) / "deploy/config/sim.yaml";
  if (fs::is_regular_file(source)) return source.string();
  throw ConfigError("no --config given and the shipped config was not found (looked in " +
                    source.string() + ")");
}

}  // namespace rovctl::app
