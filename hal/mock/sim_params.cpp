// The `sim` config section's declarations: key, unit, range and meaning of every parameter.
#include "hal/mock/sim_params.hpp"

#include <cmath>

namespace rovctl::hal::mock {

Eigen::Isometry3d station_T_world_marker(const StationPlacement& p) {
  // Docking heading 0: marker x east, y down, z (the docking axis) north.
  Eigen::Matrix3d R0;
  R0.col(0) = Eigen::Vector3d::UnitY();
  R0.col(1) = Eigen::Vector3d::UnitZ();
  R0.col(2) = Eigen::Vector3d::UnitX();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(p.docking_heading_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) * R0;
  T.translation() = p.marker_position_world_m;
  return T;
}

void describe(ParamVisitor& v, StationPlacement& p) {
  v.param("marker_position_m", p.marker_position_world_m,
          {"m", -1e4, 1e4, "marker centre in the world (NED: x north, y east, z down)"});
  v.param("docking_heading_deg", p.docking_heading_deg,
          {"deg", -360.0, 360.0,
           "direction of the docking axis (marker +z), 0 = north; the vehicle docks heading so"});
}

void describe(ParamVisitor& v, ContactParams& p) {
  v.param("lateral_tolerance_m", p.lateral_tolerance_m,
          {"m", 0.001, 0.5, "probe tip within this of the socket axis counts as captured"});
  v.param("angle_tolerance_deg", p.angle_tolerance_deg,
          {"deg", 0.1, 90.0, "body x within this of the docking axis counts as aligned"});
  v.param("latch_on_dock", p.latch_on_dock, "hold the vehicle still once docked");
  v.param("stiffness_npm", p.stiffness_npm,
          {"N/m", 10.0, 1e6, "contact stiffness of the station face and the socket bottom"});
  v.param("damping_nspm", p.damping_nspm, {"N s/m", 0.0, 1e5, "contact damping"});
  v.param("socket_wall", p.socket_wall,
          "a probe past the socket mouth meets the socket's wall sideways (not the face)");
  v.param("bore_radius_m", p.bore_radius_m,
          {"m", 0.0, 0.5, "radius of the socket's bore at the capture depth (the funnel narrows)"});
  v.param("wall_band_m", p.wall_band_m,
          {"m", 0.0, 0.1, "how far beyond the funnel tolerance the wall catches the probe"});
  v.param("face_half_size_m", p.face_half_size_m,
          {"m", 0.05, 100.0,
           "the station face: a square this far to each side of the socket (larger than the "
           "plate the marker is on); a probe beside it touches nothing"});
}

void describe(ParamVisitor& v, CameraSimParams& p) {
  v.param("latency_ms", p.latency_ms,
          {"ms", 0.0, 500.0, "capture latency: a frame shows the world this long before grab"});
  v.section("render", "how the simulated cameras draw the marker",
            [&p](ParamVisitor& s) { describe(s, p.render); });
}

void describe(ParamVisitor& v, SensorSimParams& p) {
  v.param("depth_noise_m", p.depth_noise_m, {"m", 0.0, 1.0, "depth sensor noise (std dev)"});
  v.param("attitude_noise_deg", p.attitude_noise_deg,
          {"deg", 0.0, 10.0, "attitude noise per axis (std dev)"});
  v.param("gyro_noise_radps", p.gyro_noise_radps,
          {"rad/s", 0.0, 1.0, "angular rate noise per axis (std dev)"});
}

void describe(ParamVisitor& v, TrialRandomisation& p) {
  v.param("distance_min_m", p.distance_min_m,
          {"m", 0.05, 20.0, "nearest start: left camera to marker centre"});
  v.param("distance_max_m", p.distance_max_m,
          {"m", 0.05, 20.0, "farthest start: left camera to marker centre"});
  v.param("bearing_max_deg", p.bearing_max_deg,
          {"deg", 0.0, 80.0, "start position off the docking axis, horizontally, at most"});
  v.param("elevation_max_deg", p.elevation_max_deg,
          {"deg", 0.0, 60.0, "start position off the docking axis, vertically, at most"});
  v.param("heading_offset_max_deg", p.heading_offset_max_deg,
          {"deg", 0.0, 180.0, "vehicle heading off the line of sight to the marker, at most"});
  v.param("roll_pitch_max_deg", p.roll_pitch_max_deg,
          {"deg", 0.0, 30.0, "initial roll and pitch, at most"});
  v.param("out_of_view_fraction", p.out_of_view_fraction,
          {"-", 0.0, 1.0, "share of trials starting with the marker in neither camera"});
  v.param("visibility_margin_px", p.visibility_margin_px,
          {"px", 0.0, 200.0, "a sphere is in view when this far inside the image border"});
  v.param("current_max_mps", p.current_max_mps,
          {"m/s", 0.0, 1.0, "horizontal current speed, uniform in [0, max], random direction"});
  v.param("noise_sigma_min", p.noise_sigma_min,
          {"grey levels", 0.0, 50.0, "image noise std dev, uniform in [min, max]"});
  v.param("noise_sigma_max", p.noise_sigma_max,
          {"grey levels", 0.0, 50.0, "image noise std dev, upper end"});
}

void describe(ParamVisitor& v, RechargeSimParams& p) {
  v.section("battery", "the vehicle's battery and the thrusters' power draw",
            [&p](ParamVisitor& s) { describe(s, p.battery); });
  v.section("charger", "the docking station's charger",
            [&p](ParamVisitor& s) { describe(s, p.charger); });
  v.param("seated_time_scale", p.seated_time_scale,
          {"-", 1.0, 10000.0, "battery time per physics time while seated (speeds the charge up)"});
  v.param("initial_soc_min", p.initial_soc_min,
          {"-", 0.0, 1.0, "lowest state of charge a trial starts with"});
  v.param("initial_soc_max", p.initial_soc_max,
          {"-", 0.0, 1.0, "highest state of charge a trial starts with"});
  v.param("current_max_mps", p.current_max_mps,
          {"m/s", 0.0, 1.0, "recharge trials: horizontal current speed, uniform in [0, max]"});
  v.param("tide_turn_degps", p.tide_turn_degps,
          {"deg/s", -10.0, 10.0, "recharge trials: rate at which the current turns"});
  v.param("gust_peak_mps", p.gust_peak_mps,
          {"m/s", 0.0, 1.0, "recharge trials: largest gust along the current"});
  v.param("gust_duration_s", p.gust_duration_s, {"s", 0.1, 600.0, "recharge trials: gust length"});
  v.param("gust_interval_s", p.gust_interval_s,
          {"s", 0.1, 3600.0, "recharge trials: mean gap between gusts"});
}

void apply_recharge_sea(SimParams& p) {
  p.trials.current_max_mps = p.recharge.current_max_mps;
  p.current.tide_turn_degps = p.recharge.tide_turn_degps;
  p.current.gust_peak_mps = p.recharge.gust_peak_mps;
  p.current.gust_duration_s = p.recharge.gust_duration_s;
  p.current.gust_interval_s = p.recharge.gust_interval_s;
  p.contact.latch_on_dock = false;
  p.contact.socket_wall = true;
}

void describe(ParamVisitor& v, MockArdusubParams& p) {
  v.param("pilot_gain", p.pilot_gain,
          {"-", 0.1, 1.0, "the mock ArduSub's joystick gain (JS_GAIN_DEFAULT) on every axis"});
  v.param("level_kp_nm_per_rad", p.level_kp_nm_per_rad,
          {"N*m/rad", 0.0, 500.0, "stabilise: roll/pitch moment per radian off level"});
  v.param("level_kd_nms_per_rad", p.level_kd_nms_per_rad,
          {"N*m*s/rad", 0.0, 100.0, "stabilise: roll/pitch moment per rad/s of roll/pitch rate"});
  v.param("pilot_timeout_ms", p.pilot_timeout_ms,
          {"ms", 100.0, 60000.0,
           "FS_PILOT_TIMEOUT: no MANUAL_CONTROL this long while armed: neutral and disarm"});
  v.param("rc_override_time_ms", p.rc_override_time_ms,
          {"ms", 100.0, 60000.0,
           "RC_OVERRIDE_TIME: an RC_CHANNELS_OVERRIDE drives the passthrough outputs this long"});
  v.param("heartbeat_period_ms", p.heartbeat_period_ms,
          {"ms", 10.0, 5000.0, "period of the mock ArduSub's HEARTBEAT (ArduSub: 1000)"});
  v.param("surface_pressure_hpa", p.surface_pressure_hpa,
          {"hPa", 800.0, 1100.0, "absolute pressure the mock reports at depth 0"});
  v.param("water_density_kg_m3", p.water_density_kg_m3,
          {"kg/m^3", 990.0, 1050.0, "water density the mock's pressure grows with"});
}

void describe(ParamVisitor& v, SimParams& p) {
  v.param("integration_step_ms", p.integration_step_ms,
          {"ms", 0.1, 10.0, "physics integration step (RK4), finer than the control tick"});
  v.param("realtime", p.realtime,
          "pace the simulation by the wall clock (hardware in the loop) instead of virtual time");
  v.section("dynamics",
            "6-DOF Fossen model; defaults: BlueROV2 (Wu 2018, Flinders Univ. MSc thesis) with the "
            "Heavy's mass (von Benzon et al., J. Mar. Sci. Eng. 2022, 10(12), 1898)",
            [&p](ParamVisitor& s) { describe(s, p.dynamics); });
  v.section("thrusters", "thruster response: lag, deadband, curve, ESC timeout",
            [&p](ParamVisitor& s) { describe(s, p.thrusters); });
  v.section("current", "water current: constant plus slowly varying random part",
            [&p](ParamVisitor& s) { describe(s, p.current); });
  v.section("station", "where the docking station stands in the world",
            [&p](ParamVisitor& s) { describe(s, p.station); });
  v.section("contact", "docking capture and contact with the station",
            [&p](ParamVisitor& s) { describe(s, p.contact); });
  v.section("camera", "simulated stereo camera: latency and rendering",
            [&p](ParamVisitor& s) { describe(s, p.camera); });
  v.section("sensors", "simulated depth and attitude sensors",
            [&p](ParamVisitor& s) { describe(s, p.sensors); });
  v.section("trials", "randomised initial conditions of the docking trials",
            [&p](ParamVisitor& s) { describe(s, p.trials); });
  v.section("faults", "hardware faults injected at run time",
            [&p](ParamVisitor& s) { describe(s, p.faults); });
  v.param("scenario", p.scenario,
          "imaging conditions of the simulated cameras: clear water (default), turbid water, a "
          "side light with shadows, bubbles and particles, a passing occluder, a noisy "
          "compressing sensor, or a drifting, smearing auto exposure on a vibrating mount",
          scenario_names());
  v.section("scenarios", "parameters of each imaging scenario (used when it is selected)",
            [&p](ParamVisitor& s) { describe(s, p.scenarios); });
  v.section("recharge", "the recharging mission: battery, charger, sped-up charge, its sea",
            [&p](ParamVisitor& s) { describe(s, p.recharge); });
  v.section("ardusub", "the mock ArduSub behind thruster_bus.backend ardusub in rovctl sim",
            [&p](ParamVisitor& s) { describe(s, p.ardusub); });
}

}  // namespace rovctl::hal::mock
