// The checks a loaded config and its calibration go through before any device is opened.
#include "app/runtime/config_validation.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "control/control_allocation_pseudo_inverse.hpp"
#include "drivers/mavlink/ardusub_rc_override_map.hpp"
#include "drivers/mavlink/mavlink_link.hpp"
#include "estimator/stereo_calibration.hpp"
#include "hal/primitives/number_format.hpp"

namespace rovctl::app {
namespace {

// The parent of a dotted key path: "a.b[2].c" -> "a.b[2]" -> "a.b" -> "a" -> "".
std::string parent_of(const std::string& key) {
  const std::size_t cut = key.find_last_of(".[");
  return cut == std::string::npos ? std::string() : key.substr(0, cut);
}

constexpr const char* kAxisNames[6] = {"x (surge)", "y (sway)", "z (heave)",
                                       "roll",      "pitch",    "yaw"};

void check_thrusters(const AppConfig& config) {
  const std::string where = config_location(config, "vehicle.thrusters.thrusters");
  // The allocator's own checks (zero direction, channel off the bus or used twice, weights naming
  // no thruster) are config errors too: they must not first surface when the vehicle is built.
  try {
    const control::ControlAllocator allocator(config.vehicle.thrusters, config.control.allocation);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(where + ": " + e.what());
  }
  std::vector<int> axes = {0, 1, 2, 5};  // what the servo drives by default
  if (config.control.servo.six_dof) axes = {0, 1, 2, 3, 4, 5};
  const Eigen::MatrixXd B = config.vehicle.thrusters.configuration_matrix();
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(axes.size()), B.cols());
  for (std::size_t r = 0; r < axes.size(); ++r) {
    const Eigen::RowVectorXd row = B.row(axes[r]);
    // Forces (N per N) and moments (N m per N) differ in unit: each row is scaled to unit norm
    // so that the ratio below measures independence of the axes, not the lever arms' length.
    if (row.norm() < 1e-9) {
      throw ConfigError(where + ": no thruster pushes along the servo's " +
                        std::string(kAxisNames[axes[r]]) + " axis: the layout cannot control it");
    }
    rows.row(static_cast<Eigen::Index>(r)) = row / row.norm();
  }
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(rows).singularValues();
  const double ratio = sv.size() == static_cast<Eigen::Index>(axes.size()) && sv[0] > 0.0
                           ? sv[sv.size() - 1] / sv[0]
                           : 0.0;
  if (ratio < config.validation.thruster_min_singular_ratio) {
    std::string names;
    for (const int a : axes) names += (names.empty() ? "" : ", ") + std::string(kAxisNames[a]);
    throw ConfigError(where + ": the thrusters cannot push the servo's axes (" + names +
                      ") independently: singular value ratio " + hal::format_number(ratio) +
                      " is below validation.thruster_min_singular_ratio " +
                      hal::format_number(config.validation.thruster_min_singular_ratio));
  }
}

void check_marker(const AppConfig& config) {
  const auto& spheres = config.marker.spheres;
  const ValidationLimits& lim = config.validation;
  auto key = [](std::size_t i, const char* field) {
    return "marker.spheres[" + std::to_string(i) + "]." + field;
  };
  if (spheres.size() != 3) {
    throw ConfigError(config_location(config, "marker.spheres") + ": expected 3 spheres (red, " +
                      "green and blue), got " + std::to_string(spheres.size()) +
                      ": fewer leave the marker's pose ambiguous");
  }
  for (std::size_t j = 1; j < spheres.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (spheres[i].colour == spheres[j].colour) {
        throw ConfigError(config_location(config, key(j, "name")) + ": '" + spheres[j].name +
                          "' is also sphere " + std::to_string(i) +
                          "'s colour: the marker needs one red, one green and one blue sphere");
      }
      const double gap = (spheres[i].centre_marker_m - spheres[j].centre_marker_m).norm() -
                         spheres[i].radius_m - spheres[j].radius_m;
      if (gap < lim.marker_min_gap_m) {
        throw ConfigError(config_location(config, key(j, "centre_m")) + ": the " + spheres[j].name +
                          " and " + spheres[i].name + " spheres are " + hal::format_number(gap) +
                          " m apart surface to surface, below " + "validation.marker_min_gap_m " +
                          hal::format_number(lim.marker_min_gap_m) + " m");
      }
    }
  }
  // The sphere nearest the line through the other two names the problem.
  std::size_t worst = 0;
  double worst_height = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = spheres[(k + 1) % 3].centre_marker_m;
    const Eigen::Vector3d b = spheres[(k + 2) % 3].centre_marker_m;
    const Eigen::Vector3d p = spheres[k].centre_marker_m;
    const double height = (b - a).cross(p - a).norm() / (b - a).norm();
    if (k == 0 || height < worst_height) {
      worst = k;
      worst_height = height;
    }
  }
  if (worst_height < lim.marker_min_height_m) {
    throw ConfigError(config_location(config, key(worst, "centre_m")) + ": the " +
                      spheres[worst].name + " sphere is " + hal::format_number(worst_height) +
                      " m from the line through the other two, below " +
                      "validation.marker_min_height_m " +
                      hal::format_number(lim.marker_min_height_m) +
                      " m: a rotation about that line could not be seen");
  }
}

// The camera controls' keys that only mean something together; the camera's own ranges are
// checked when it is opened (drivers/v4l2/camera_controls), where `check` reports them.
void check_camera_controls(const AppConfig& config) {
  const drivers::V4l2CameraParams& v = config.camera.v4l2;
  const double frame_period_us = 1e6 / v.fps;
  if (!v.auto_exposure && v.exposure_time_us > frame_period_us) {
    throw ConfigError(config_location(config, "camera.v4l2.exposure_time_us") + ": " +
                      std::to_string(v.exposure_time_us) +
                      " us does not fit in the frame period at camera.v4l2.fps " +
                      std::to_string(v.fps) + " (" +
                      std::to_string(static_cast<int>(frame_period_us)) + " us)");
  }
  if (v.white_balance == "auto" && v.white_balance_temperature_k != 0) {
    throw ConfigError(config_location(config, "camera.v4l2.white_balance_temperature_k") +
                      ": needs camera.v4l2.white_balance lock (auto white balance ignores it)");
  }
}

void check_contact(AppConfig& config) {
  control::MissionParams& m = config.mission;
  if (m.contact_switch && !backends_report_contact(config)) {
    // ArduSub and PX4 users expect the vehicle to fly on what it has, told so at pre-flight: the
    // mission ends DOCK on vision contact, and `rovctl check` prints this.
    m.contact_switch = false;
    m.contact_from_vision = true;
    config.warnings.push_back(
        config_location(config, "mission.contact_switch") +
        ": no backend reports a dock contact (camera.backend " + config.camera.backend +
        ", thruster_bus.backend " + config.thruster_bus.backend +
        "; only the mock HAL has sensors): the mission uses vision contact "
        "(mission.contact_from_vision); say mission.contact_switch: false to silence this");
  }
  if (!m.contact_switch && !m.contact_from_vision) {
    throw ConfigError(config_location(config, "mission.contact_from_vision") +
                      ": neither mission.contact_switch nor contact_from_vision: DOCK could "
                      "never end");
  }
}

// "calibration-file:line: key" for a top-level key of the calibration file.
std::string calibration_location(const std::string& file, const std::string& key) {
  const int line = estimator::calibration_key_line(file, key);
  return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + key;
}

void check_camera(const hal::CameraModel& c, const std::string& file, const char* k_key,
                  const char* d_key, const ValidationLimits& lim) {
  auto fail = [&file](const char* key, const std::string& what) {
    throw ConfigError(calibration_location(file, key) + ": " + what);
  };
  if (!(c.cx_px >= 0 && c.cx_px <= c.width_px && c.cy_px >= 0 && c.cy_px <= c.height_px)) {
    fail(k_key, "principal point (" + hal::format_number(c.cx_px) + ", " +
                    hal::format_number(c.cy_px) + ") px lies outside the " +
                    std::to_string(c.width_px) + "x" + std::to_string(c.height_px) + " image");
  }
  const double fov_h = 2.0 * std::atan(0.5 * c.width_px / c.fx_px) * 180.0 / M_PI;
  const double fov_v = 2.0 * std::atan(0.5 * c.height_px / c.fy_px) * 180.0 / M_PI;
  const struct {
    const char* name;
    double deg;
  } fields_of_view[] = {{"horizontal", fov_h}, {"vertical", fov_v}};
  for (const auto& fov : fields_of_view) {
    if (!(fov.deg >= lim.fov_min_deg && fov.deg <= lim.fov_max_deg)) {
      fail(k_key, std::string(fov.name) + " field of view " + hal::format_number(fov.deg) +
                      " deg is outside validation.fov_min_deg .. fov_max_deg (" +
                      hal::format_number(lim.fov_min_deg) + " .. " +
                      hal::format_number(lim.fov_max_deg) +
                      " deg): check fx, fy against the image size");
    }
  }
  if (!(std::abs(c.fx_px / c.fy_px - 1.0) <= lim.max_aspect_deviation)) {
    fail(k_key, "fx / fy = " + hal::format_number(c.fx_px / c.fy_px) +
                    " differs from 1 by more than validation.max_aspect_deviation " +
                    hal::format_number(lim.max_aspect_deviation));
  }
  const struct {
    const char* name;
    double value;
    double limit;
    const char* limit_key;
  } coefficients[] = {{"k1", c.k1, lim.max_abs_k1, "max_abs_k1"},
                      {"k2", c.k2, lim.max_abs_k2, "max_abs_k2"},
                      {"k3", c.k3, lim.max_abs_k3, "max_abs_k3"},
                      {"p1", c.p1, lim.max_abs_tangential, "max_abs_tangential"},
                      {"p2", c.p2, lim.max_abs_tangential, "max_abs_tangential"}};
  for (const auto& k : coefficients) {
    if (!(std::abs(k.value) <= k.limit)) {
      fail(d_key, std::string(k.name) + " = " + hal::format_number(k.value) +
                      " is beyond validation." + k.limit_key + " (|" + k.name +
                      "| <= " + hal::format_number(k.limit) + ")");
    }
  }
}

}  // namespace

void describe(hal::ParamVisitor& v, ValidationLimits& l) {
  v.param("fov_min_deg", l.fov_min_deg,
          {"deg", 1.0, 179.0, "calibration: least horizontal and vertical field of view"});
  v.param("fov_max_deg", l.fov_max_deg,
          {"deg", 1.0, 179.0, "calibration: largest horizontal and vertical field of view"});
  v.param("max_aspect_deviation", l.max_aspect_deviation,
          {"-", 0.0, 1.0, "calibration: largest |fx / fy - 1| (0: square pixels)"});
  v.param("max_abs_k1", l.max_abs_k1,
          {"-", 0.0, 100.0, "calibration: largest |k1| (OpenCV radial distortion)"});
  v.param("max_abs_k2", l.max_abs_k2, {"-", 0.0, 1000.0, "calibration: largest |k2|"});
  v.param("max_abs_k3", l.max_abs_k3, {"-", 0.0, 10000.0, "calibration: largest |k3|"});
  v.param("max_abs_tangential", l.max_abs_tangential,
          {"-", 0.0, 10.0, "calibration: largest |p1| and |p2| (tangential distortion)"});
  v.param("baseline_min_m", l.baseline_min_m,
          {"m", 0.001, 5.0, "calibration: shortest stereo baseline |T|"});
  v.param("baseline_max_m", l.baseline_max_m,
          {"m", 0.001, 5.0, "calibration: longest stereo baseline |T| (T in metres)"});
  v.param("max_rig_rotation_deg", l.max_rig_rotation_deg,
          {"deg", 0.0, 180.0, "calibration: largest angle between the two cameras (R)"});
  v.param("expected_baseline_m", l.expected_baseline_m,
          {"m", 0.0, 5.0,
           "calibration: the baseline measured on the rig, for `rovctl check` (0: not given; "
           "PASS within 2 %, WARN within 5 %, FAIL beyond)"});
  v.param("thruster_min_singular_ratio", l.thruster_min_singular_ratio,
          {"-", 0.0, 1.0,
           "thrusters: least ratio of smallest to largest singular value of the effectiveness "
           "rows of the servoed axes (x, y, z, yaw; six with six_dof), each scaled to unit norm"});
  v.param("marker_min_gap_m", l.marker_min_gap_m,
          {"m", 0.0, 1.0, "marker: least gap between two spheres' surfaces"});
  v.param("marker_min_height_m", l.marker_min_height_m,
          {"m", 0.0, 1.0,
           "marker: least distance of each sphere's centre from the line through the other two"});
}

std::string config_location(const AppConfig& config, const std::string& key) {
  for (std::string k = key; !k.empty(); k = parent_of(k)) {
    const auto it = config.key_lines.find(k);
    if (it != config.key_lines.end()) {
      return config.config_file + ":" + std::to_string(it->second) + ": " + key;
    }
  }
  return config.config_file + ": " + key;
}

bool backends_report_contact(const AppConfig& config) {
  return config.camera.backend == "mock" || config.thruster_bus.backend == "mock";
}

void validate_app_config(AppConfig& config) {
  if (!(config.validation.fov_min_deg < config.validation.fov_max_deg)) {
    throw ConfigError(config_location(config, "validation.fov_min_deg") +
                      ": must be below validation.fov_max_deg");
  }
  if (!(config.validation.baseline_min_m < config.validation.baseline_max_m)) {
    throw ConfigError(config_location(config, "validation.baseline_min_m") +
                      ": must be below validation.baseline_max_m");
  }
  const drivers::BusTimingParams& bus = config.thruster_bus.timing;
  if (!(bus.degraded_ms < bus.watchdog_ms)) {
    throw ConfigError(config_location(config, "thruster_bus.timing.degraded_ms") +
                      ": must be below thruster_bus.timing.watchdog_ms (a slow bus is reported "
                      "before the controller stops on it)");
  }
  if (config.sensors.backend == "ardusub" && config.thruster_bus.backend != "ardusub") {
    throw ConfigError(config_location(config, "sensors.backend") +
                      ": ardusub needs thruster_bus.backend ardusub (its link carries them)");
  }
  if (config.thruster_bus.backend == "ardusub") {
    const drivers::ArdusubParams& a = config.thruster_bus.ardusub;
    drivers::mavlink::LinkEndpoint endpoint;
    std::string error;
    // The parser's message starts with the key it is given: here the file:line: key.
    if (!drivers::mavlink::parse_link_endpoint(
            a.link, config_location(config, "thruster_bus.ardusub.link"), endpoint, error)) {
      throw ConfigError(error);
    }
    if (!(a.ack_timeout_ms < bus.close_timeout_ms)) {
      throw ConfigError(config_location(config, "thruster_bus.ardusub.ack_timeout_ms") +
                        ": must be below thruster_bus.timing.close_timeout_ms (the I/O thread "
                        "answers the final disarm within it)");
    }
    // The channel map and PWM range are checked where they are used; here with file:line.
    try {
      const drivers::ArdusubRcOverrideMap map(config.vehicle.thrusters, a.rc_override);
    } catch (const std::invalid_argument& e) {
      const std::string key = "thruster_bus.ardusub.rc_override";
      const std::string where = config_location(config, key);
      throw ConfigError(where.substr(0, where.size() - key.size()) + e.what());
    }
  }
  check_thrusters(config);
  check_marker(config);
  check_camera_controls(config);
  check_contact(config);
  if (config.operator_view.enabled()) {
    ListenAddress address;
    std::string error;
    if (!parse_listen_address(config.operator_view.listen, address, error)) {
      throw ConfigError(config_location(config, "operator_view.listen") + ": " + error);
    }
  }
}

void validate_stereo_rig(const hal::StereoRig& rig, const std::string& file,
                         const ValidationLimits& lim) {
  check_camera(rig.left, file, "K1", "D1", lim);
  check_camera(rig.right, file, "K2", "D2", lim);
  const double baseline = rig.baseline_m();
  if (!(baseline >= lim.baseline_min_m && baseline <= lim.baseline_max_m)) {
    throw ConfigError(calibration_location(file, "T") + ": baseline " +
                      hal::format_number(baseline) +
                      " m is outside validation.baseline_min_m .. baseline_max_m (" +
                      hal::format_number(lim.baseline_min_m) + " .. " +
                      hal::format_number(lim.baseline_max_m) + " m; T is in metres)");
  }
  const double angle_deg = Eigen::AngleAxisd(rig.T_cr_cl.linear()).angle() * 180.0 / M_PI;
  if (!(angle_deg <= lim.max_rig_rotation_deg)) {
    throw ConfigError(calibration_location(file, "R") + ": the cameras are turned " +
                      hal::format_number(angle_deg) + " deg from each other, beyond " +
                      "validation.max_rig_rotation_deg " +
                      hal::format_number(lim.max_rig_rotation_deg) +
                      " deg: they would not see the marker together");
  }
}

}  // namespace rovctl::app
