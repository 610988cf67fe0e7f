// `rovctl check`: pre-flight. One line per check (config, calibration, camera, thruster bus,
// estimator); exit 0 when all pass, 2 when any fails. Nothing is armed.
#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"

namespace rovctl::app {
namespace {

struct Checker {
  int failures = 0;
  void line(bool ok, const std::string& what, const std::string& detail) {
    std::cout << (ok ? "PASS  " : "FAIL  ") << what << ": " << detail << "\n";
    if (!ok) ++failures;
  }
};

std::string calibration_problem(const hal::CameraModel& c, const char* which) {
  const std::string name = which;
  if (c.cx_px < 0 || c.cx_px > c.width_px || c.cy_px < 0 || c.cy_px > c.height_px) {
    return name + " principal point lies outside the image";
  }
  const double fov_deg = 2.0 * std::atan(0.5 * c.width_px / c.fx_px) * 180.0 / M_PI;
  if (fov_deg < 10.0 || fov_deg > 170.0) {
    return name + " horizontal field of view " + std::to_string(fov_deg) + " deg is implausible";
  }
  if (std::abs(c.fx_px / c.fy_px - 1.0) > 0.2) return name + " fx/fy differ by more than 20 %";
  if (std::abs(c.k1) > 2.0) return name + " k1 is implausibly large";
  return "";
}

}  // namespace

int command_check(const Words& words) {
  const CliArgs args = CliArgs::parse("check", words, {"--config"}, {});
  if (!args.has("--config")) throw UsageError("rovctl check: --config FILE is required");
  Checker check;
  AppConfig config;
  try {
    config = load_app_config(args.get("--config"));
    check.line(true, "config", config.config_file);
  } catch (const std::exception& e) {
    check.line(false, "config", e.what());
    return kExitUsage;
  }
  hal::StereoRig rig;
  try {
    rig = load_rig(config);
    std::string problem = calibration_problem(rig.left, "left");
    if (problem.empty()) problem = calibration_problem(rig.right, "right");
    if (problem.empty() && (rig.baseline_m() < 0.03 || rig.baseline_m() > 1.0)) {
      problem = "baseline " + std::to_string(rig.baseline_m()) + " m is implausible";
    }
    check.line(problem.empty(), "calibration",
               problem.empty()
                   ? config.calibration_file + " (" + std::to_string(rig.left.width_px) + "x" +
                         std::to_string(rig.left.height_px) + ", baseline " +
                         std::to_string(rig.baseline_m() * 1000.0).substr(0, 5) + " mm)"
                   : config.calibration_file + ": " + problem);
  } catch (const std::exception& e) {
    check.line(false, "calibration", e.what());
    return kExitUsage;
  }

  VehicleBackends hw = make_vehicle_backends(config, rig);
  std::string error;
  if (hw.camera->open(error)) {
    hal::StereoFrame frame;
    hal::GrabStatus status = hal::GrabStatus::timeout;
    for (int attempt = 0; attempt < 30 && status != hal::GrabStatus::ok; ++attempt) {
      status = hw.camera->grab(frame);
      if (status == hal::GrabStatus::timeout)
        std::this_thread::sleep_for(std::chrono::milliseconds(33));
    }
    const bool size_ok =
        status == hal::GrabStatus::ok && frame.left_bgr.cols == rig.left.width_px &&
        frame.left_bgr.rows == rig.left.height_px && frame.right_bgr.cols == rig.right.width_px &&
        frame.right_bgr.rows == rig.right.height_px;
    std::string detail = hw.camera->name() + ": ";
    if (status != hal::GrabStatus::ok) {
      detail += std::string("no stereo pair (") + hal::to_string(status) + ")";
    } else if (!size_ok) {
      detail += "images are " + std::to_string(frame.left_bgr.cols) + "x" +
                std::to_string(frame.left_bgr.rows) + ", the calibration expects " +
                std::to_string(rig.left.width_px) + "x" + std::to_string(rig.left.height_px);
    } else {
      detail += "stereo pair " + std::to_string(frame.left_bgr.cols) + "x" +
                std::to_string(frame.left_bgr.rows);
    }
    check.line(size_ok, "camera", detail);
    hw.camera->close();
  } else {
    check.line(false, "camera", error);
  }
  if (hw.bus->open(error)) {
    hal::ThrusterTelemetry telemetry;
    const hal::BusStatus status = hw.bus->read(telemetry);
    check.line(status != hal::BusStatus::fault, "thruster bus",
               hw.bus->name() + ": " +
                   (status == hal::BusStatus::fault ? "not answering" : "answering") + ", " +
                   std::to_string(config.vehicle.thrusters.thrusters.size()) + " thrusters");
    hw.bus->close();
  } else {
    check.line(false, "thruster bus", error);
  }
  // The operator view: reachable only from the vehicle unless the config says otherwise.
  if (config.operator_view.enabled()) {
    ListenAddress address;
    std::string problem;
    parse_listen_address(config.operator_view.listen, address, problem);  // validated at load
    if (address.loopback()) {
      check.line(true, "operator view",
                 "on " + config.operator_view.listen + " (this machine only)");
    } else {
      std::cout << "WARN  operator view: listens on " << config.operator_view.listen
                << ", reachable from the network"
                << (config.operator_view.token.empty()
                        ? " (read-only: no token)"
                        : "; anyone with operator_view.token can ABORT and START")
                << "\n";
    }
  }
  std::cout << (check.failures == 0
                    ? "pre-flight: all checks passed\n"
                    : "pre-flight: " + std::to_string(check.failures) + " check(s) failed\n");
  return check.failures == 0 ? kExitOk : kExitUsage;
}

}  // namespace rovctl::app
