// Top-level config sections; each section's parameters are declared beside their own struct.
#include "app/app_config.hpp"

#include <filesystem>

#include "app/config_loader.hpp"
#include "app/errors.hpp"

namespace rovctl::app {

void describe(hal::ParamVisitor& v, AppConfig& c) {
  v.path("calibration", c.calibration_file,
         "OpenCV stereo calibration YAML (K1, D1, K2, D2, R, T, image size)", true);
  v.section("marker", "the docking marker: three coloured spheres",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.marker); });
  v.section("vehicle", "vehicle geometry: camera mount, docking probe, thrusters",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.vehicle); });
  v.section("station", "docking station: charging socket relative to the marker",
            [&c](hal::ParamVisitor& s) { hal::describe(s, c.station); });
}

AppConfig load_app_config(const std::string& file) {
  AppConfig config;
  load_yaml_file(file, [&config](hal::ParamVisitor& v) { describe(v, config); });
  config.config_file = file;
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
