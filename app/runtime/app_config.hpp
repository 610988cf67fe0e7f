// The application's whole configuration: one plain struct per section, each declared (key, unit,
// range, meaning) by the describe() beside its own struct, validated at start-up.
#pragma once

#include <string>
#include <vector>

#include "app/runtime/config_loader.hpp"
#include "app/runtime/config_validation.hpp"
#include "app/runtime/cyclic_scheduler.hpp"
#include "app/runtime/operator_view_params.hpp"
#include "app/runtime/telemetry.hpp"
#include "control/control_params.hpp"
#include "drivers/camera_params.hpp"
#include "drivers/sensors_params.hpp"
#include "drivers/thruster_bus_params.hpp"
#include "estimator/estimator_params.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/vehicle_geometry.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

struct AppConfig {
  std::string config_file;       // where it was loaded from (empty: built-in defaults)
  std::string calibration_file;  // OpenCV stereo calibration YAML (K1, D1, K2, D2, R, T, size)
  hal::MarkerModel marker = hal::MarkerModel::standard();
  hal::VehicleGeometry vehicle;
  hal::DockingStation station;
  drivers::CameraParams camera;
  drivers::ThrusterBusParams thruster_bus;
  drivers::SensorsParams sensors;
  estimator::EstimatorParams estimator;
  control::ControlParams control;
  control::MissionParams mission;
  SchedulerParams scheduler;
  TelemetryParams telemetry;
  OperatorViewParams operator_view;
  hal::mock::SimParams sim;
  ValidationLimits validation;
  KeyLines key_lines;                 // the line of every key the file gives
  std::vector<std::string> warnings;  // what validation adjusted ("file:line: key: ...")
};

void describe(hal::ParamVisitor& v, AppConfig& config);

// Loads and validates (validate_app_config: layout, marker, contact source); throws ConfigError
// naming file, line and key.
AppConfig load_app_config(const std::string& file);

// The config shipped with rovctl (deploy/config/sim.yaml), installed or in the source tree.
std::string default_config_path();

}  // namespace rovctl::app
