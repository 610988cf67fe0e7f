// `rovctl check`: pre-flight. One line per check (config, calibration, camera, thruster bus and,
// on ArduSub, its failsafe parameters); exit 0 when all pass, 2 when any fails. Nothing is armed.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "drivers/mavlink/ardusub_failsafe_params.hpp"
#include "drivers/mavlink/ardusub_gcs_id.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "drivers/v4l2/v4l2_stereo_camera.hpp"
#include "estimator/stereo_calibration.hpp"

namespace rovctl::app {
namespace {

struct Checker {
  int failures = 0;
  void line(bool ok, const std::string& what, const std::string& detail) {
    std::cout << (ok ? "PASS  " : "FAIL  ") << what << ": " << detail << "\n";
    // A failure goes to stderr too, as every other command reports its errors.
    if (!ok) std::cerr << "rovctl check: " << what << ": " << detail << "\n";
    if (!ok) ++failures;
  }
  // PASS, WARN or FAIL by a figure against two limits (lower is better).
  void graded(double value, double pass_max, double warn_max, const std::string& what,
              const std::string& detail) {
    if (value > pass_max && value <= warn_max) {
      std::cout << "WARN  " << what << ": " << detail << "\n";
      return;
    }
    line(value <= pass_max, what, detail);
  }
};

std::string figure(double v, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

// What `rovctl calibrate` recorded in the file, and the baseline against the one measured on the
// rig (validation.expected_baseline_m): a calibration can load and still be a poor one.
void check_calibration_figures(Checker& check, const AppConfig& config, const hal::StereoRig& rig) {
  const estimator::CalibrationFigures f =
      estimator::load_calibration_figures(config.calibration_file);
  if (std::isnan(f.rms_reprojection_px)) {
    std::cout << "WARN  calibration figures: none in " << config.calibration_file
              << " (not written by rovctl calibrate): reprojection and epipolar error unknown\n";
  } else {
    check.graded(f.rms_reprojection_px, 0.5, 1.0, "calibration RMS reprojection",
                 figure(f.rms_reprojection_px, 3) + " px over " + std::to_string(f.views_used) +
                     " views, " + f.calibrated_utc + " (PASS <= 0.5, WARN <= 1 px)");
  }
  if (!std::isnan(f.epipolar_rms_px)) {
    check.graded(f.epipolar_rms_px, 0.5, 1.0, "calibration epipolar error",
                 figure(f.epipolar_rms_px, 3) +
                     " px RMS between rectified rows (PASS <= 0.5, WARN <= 1 px)");
  }
  const double expected_m = config.validation.expected_baseline_m;
  if (expected_m > 0.0) {
    const double off_pct = 100.0 * std::abs(rig.baseline_m() / expected_m - 1.0);
    check.graded(off_pct, 2.0, 5.0, "calibration baseline",
                 figure(rig.baseline_m() * 1000.0, 1) + " mm, " + figure(off_pct, 1) +
                     " % from validation.expected_baseline_m " + figure(expected_m * 1000.0, 1) +
                     " mm (PASS <= 2 %, WARN <= 5 %)");
  }
}

// The V4L2 cameras' controls as open() set them: set against read back, WARN for a control the
// camera lacks, FAIL for a value it cannot honour. True when one was refused.
bool check_camera_controls(Checker& check, const AppConfig& config,
                           const hal::StereoCamera& camera) {
  const auto* v4l2 = dynamic_cast<const drivers::V4l2StereoCamera*>(&camera);
  if (v4l2 == nullptr) return false;
  bool refused = false;
  for (const drivers::ControlReportLine& l : v4l2->controls_report()) {
    if (l.level == drivers::ControlLevel::fail) {
      // The key the camera cannot honour, with its file and line.
      const std::size_t at = l.text.find("camera.v4l2.");
      const std::string where =
          at == std::string::npos
              ? std::string()
              : config_location(config, l.text.substr(at, l.text.find(' ', at) - at)) + ": ";
      check.line(false, "camera", where + l.text);
      refused = true;
    } else {
      std::cout << drivers::to_string(l.level) << "  camera " << l.text << "\n";
    }
  }
  return refused;
}

// ArduSub's own failsafes are what stops the vehicle when rovctl dies: each one read back, with
// whether its value is safe for rovctl (drivers/mavlink/ardusub_failsafe_params).
void check_ardusub_failsafes(Checker& check, drivers::ArdusubThrusterBus& bus,
                             const drivers::ArdusubParams& params) {
  std::array<std::optional<float>, 3> values;
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = bus.read_parameter(drivers::kArdusubFailsafeParams[i]);
  }
  for (const drivers::ArdusubFailsafeVerdict& v :
       drivers::judge_ardusub_failsafes(params, values)) {
    check.line(v.safe, "ArduSub " + v.name, v.reason);
  }
  // A GCS id ArduSub does not obey means every command is ignored without a word: read it under
  // its 4.7 name when the older one is not answered.
  std::array<std::optional<float>, 2> gcs_id;
  gcs_id[0] = bus.read_parameter(drivers::kArdusubGcsIdParams[0]);
  if (!gcs_id[0]) gcs_id[1] = bus.read_parameter(drivers::kArdusubGcsIdParams[1]);
  const drivers::ArdusubFailsafeVerdict v =
      drivers::judge_ardusub_gcs_id(params.gcs_system_id, gcs_id);
  check.line(v.safe, "ArduSub " + v.name, v.reason);
}

std::string one_decimal(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", v);
  return text;
}

// The link as the tick will use it: the round trip of a parameter read, what arrives over 1.2 s
// (a 1 Hz HEARTBEAT always falls in it) against what open() asked for, and the mode ArduSub is
// in now (rovctl sets its flight_mode before it arms).
void check_ardusub_link(Checker& check, drivers::ArdusubThrusterBus& bus, const AppConfig& config) {
  if (const auto rtt = bus.last_round_trip()) {
    check.line(true, "ArduSub round trip",
               std::to_string(rtt->count()) + " ms (PARAM_REQUEST_READ to PARAM_VALUE)");
  }
  const drivers::ArdusubThrusterBus::ArrivalRates r =
      bus.measure_arrivals(std::chrono::milliseconds(1200));
  check.line(r.heartbeat_hz > 0.0, "ArduSub HEARTBEAT",
             one_decimal(r.heartbeat_hz) + " Hz over 1.2 s");
  if (config.sensors.backend == "ardusub") {
    const double asked = 1000.0 / config.sensors.ardusub.stream_interval_ms;
    const auto stream = [&](const char* name, double hz) {
      // A fifth below the asked rate leaves the stream's staleness limits no slack.
      check.line(hz >= 0.8 * asked, std::string("ArduSub ") + name,
                 one_decimal(hz) + " Hz over 1.2 s, asked " + one_decimal(asked) +
                     " Hz (sensors.ardusub.stream_interval_ms)");
    };
    stream("ATTITUDE_QUATERNION", r.attitude_hz);
    stream("SCALED_PRESSURE2", r.pressure_hz);
    stream("SYS_STATUS", r.sys_status_hz);
  }
  // What would refuse the arm, asked without arming (MAV_CMD_RUN_PREARM_CHECKS).
  if (const std::optional<std::string> failure = bus.run_prearm_checks()) {
    check.line(failure->empty(), "ArduSub pre-arm checks",
               failure->empty() ? "no failure reported" : *failure);
  } else {
    check.line(true, "ArduSub pre-arm checks",
               "not answered (MAV_CMD_RUN_PREARM_CHECKS): a refusal shows when rovctl arms");
  }
  const drivers::ArdusubParams& p = config.thruster_bus.ardusub;
  const auto mode = static_cast<std::uint32_t>(drivers::ardusub_custom_mode(p.flight_mode));
  check.line(true, "ArduSub mode",
             "custom mode " + std::to_string(bus.vehicle_mode()) +
                 (bus.vehicle_mode() == mode ? " (" + p.flight_mode + ")"
                                             : "; rovctl sets " + p.flight_mode + " (" +
                                                   std::to_string(mode) + ") before it arms"));
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
  // What the validation adjusted (a contact switch no backend reports -> vision contact): the
  // same config `run` flies, said here before the flight.
  for (const std::string& w : config.warnings) std::cout << "WARN  " << w << "\n";
  std::cout << "PASS  contact: "
            << (config.mission.contact_switch && config.mission.contact_from_vision
                    ? "contact switch or vision"
                : config.mission.contact_switch ? "contact switch"
                                                : "vision contact")
            << " ends DOCK\n";
  hal::StereoRig rig;
  try {
    // The one calibration validation run, sim and every other command go through.
    rig = load_rig(config);
    check.line(true, "calibration",
               config.calibration_file + " (" + std::to_string(rig.left.width_px) + "x" +
                   std::to_string(rig.left.height_px) + ", baseline " +
                   std::to_string(rig.baseline_m() * 1000.0).substr(0, 5) + " mm)");
  } catch (const std::exception& e) {
    check.line(false, "calibration", e.what());
    return kExitUsage;
  }
  check_calibration_figures(check, config, rig);

  VehicleBackends hw = make_vehicle_backends(config, rig);
  std::string error;
  const bool opened = hw.camera->open(error);
  const bool refused = check_camera_controls(check, config, *hw.camera);
  if (opened) {
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
  } else if (!refused) {  // a refused control is its own FAIL line above
    check.line(false, "camera", error);
  }
  if (hw.bus->open(error)) {
    hal::ThrusterTelemetry telemetry;
    const hal::BusStatus status = hw.bus->read(telemetry);
    check.line(status != hal::BusStatus::fault, "thruster bus",
               hw.bus->name() + ": " +
                   (status == hal::BusStatus::fault ? "not answering" : "answering") + ", " +
                   std::to_string(config.vehicle.thrusters.thrusters.size()) + " thrusters");
    if (auto* ardusub = dynamic_cast<drivers::ArdusubThrusterBus*>(hw.bus)) {
      check_ardusub_failsafes(check, *ardusub, config.thruster_bus.ardusub);
      check_ardusub_link(check, *ardusub, config);
    }
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
