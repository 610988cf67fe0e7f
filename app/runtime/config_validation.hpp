// The one validation of a loaded configuration that `check`, `run`, `sim` and every other command
// go through before any device is opened (load_app_config and load_rig call it): the thruster
// layout can push the axes the servo uses, the marker is three distinct colours at distinct
// places, the calibration describes a real stereo rig, and a contact switch is only relied on
// where a backend reports one. The plausibility limits are declared parameters (`validation.*`).
#pragma once

#include <string>
#include <vector>

#include "hal/model/stereo_rig.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

struct AppConfig;

// What a calibration, a thruster layout and a marker must satisfy to be flown. Each limit's unit,
// range and meaning are declared by describe() below.
struct ValidationLimits {
  // Calibration: the horizontal and vertical fields of view a docking camera can have.
  double fov_min_deg = 10.0;
  double fov_max_deg = 170.0;
  // |fx / fy - 1|: square pixels give 0; calibrations of real cameras stay within a few %.
  double max_aspect_deviation = 0.2;
  // OpenCV's distortion coefficients: a lens calibrated with the 5-coefficient model stays well
  // inside these; beyond them the model folds over inside the image.
  double max_abs_k1 = 2.0;
  double max_abs_k2 = 10.0;
  double max_abs_k3 = 50.0;
  double max_abs_tangential = 0.1;  // |p1|, |p2|
  // The rig: baseline |T| and the angle between the two optical frames (R).
  double baseline_min_m = 0.03;
  double baseline_max_m = 1.0;
  double max_rig_rotation_deg = 30.0;
  // The baseline measured on the vehicle (0: not given); `rovctl check` holds the calibration's
  // |T| against it.
  double expected_baseline_m = 0.0;
  // Thrusters: of the effectiveness rows of the servoed axes (x, y, z, yaw; all six with
  // control.servo.six_dof), each scaled to unit norm, the smallest singular value over the
  // largest. 0: some combination of those axes cannot be pushed at all.
  double thruster_min_singular_ratio = 0.05;
  // Marker: the least gap between two spheres' surfaces, and the least distance of each centre
  // from the line through the other two (collinear spheres leave a rotation unobservable).
  double marker_min_gap_m = 0.01;
  double marker_min_height_m = 0.03;
};

void describe(hal::ParamVisitor& v, ValidationLimits& limits);

// "file:line: key" for a key of the config, the line where the file gives it (or its nearest
// enclosing key that the file gives), or "file: key" when the file gives neither.
std::string config_location(const AppConfig& config, const std::string& key);

// The config-only checks, run by load_app_config after the per-key ones: thruster layout, marker,
// contact source. Throws ConfigError "file:line: key: what". Where the vehicle's backends report
// no contact switch but the mission relies on one, the mission is switched to vision contact and a
// warning added to config.warnings (what `rovctl check` prints).
void validate_app_config(AppConfig& config);

// The calibration's plausibility, run by load_rig on every rig it loads. Throws ConfigError
// "calibration-file:line: key: what".
void validate_stereo_rig(const hal::StereoRig& rig, const std::string& calibration_file,
                         const ValidationLimits& limits);

// True when the backends the config names report the dock contact (hal::Sensors): today only the
// mock HAL does, so any config with a mock camera or bus.
bool backends_report_contact(const AppConfig& config);

}  // namespace rovctl::app
