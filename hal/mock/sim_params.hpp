// The `sim` config section: everything the simulated world and the mock HAL are made of —
// dynamics, thrusters, current, where the station stands, cameras, sensors, integration step,
// trial randomisation, fault injection and the imaging scenario the cameras render.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "hal/mock/battery_model.hpp"
#include "hal/mock/charger.hpp"
#include "hal/mock/fault_injection.hpp"
#include "hal/mock/render_scenario.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/mock/thruster_model.hpp"
#include "hal/mock/vehicle_dynamics.hpp"
#include "hal/mock/water_current.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

// Where the docking station stands in the world (NED). The marker frame's +z, the docking axis,
// points horizontally along `docking_heading_deg` (0 = north): the vehicle docks heading that way,
// so with the defaults it starts south of the station and approaches heading north. Marker +x
// then points to the vehicle's starboard and +y down, as the camera's axes do when aligned.
struct StationPlacement {
  Eigen::Vector3d marker_position_world_m{5.0, 0.0, 2.0};
  double docking_heading_deg = 0.0;
};

void describe(ParamVisitor& v, StationPlacement& p);

// The marker's pose in the world implied by the placement.
Eigen::Isometry3d station_T_world_marker(const StationPlacement& p);

// When the probe counts as docked, and how the station pushes back on it.
struct ContactParams {
  // The socket's capture funnel: the probe tip must be within this of the socket axis.
  double lateral_tolerance_m = 0.03;
  // And the body x axis within this of the docking axis.
  double angle_tolerance_deg = 10.0;
  // Hold the vehicle once docked (the latch closes), ending the motion.
  bool latch_on_dock = true;
  // Penalty contact between the probe tip and the station face / socket bottom.
  double stiffness_npm = 3000.0;
  double damping_nspm = 150.0;
  // The socket's wall: past the mouth the socket narrows from the funnel (lateral_tolerance_m) to
  // a bore of bore_radius_m at the capture depth, and a probe that slides sideways meets it
  // (within wall_band_m beyond the funnel) instead of the station face. Off in the docking
  // trials, whose latch holds the probe; the recharge trials, which hold it themselves, turn it
  // on: a point contact with a 3 cm play would let the push buckle the vehicle about the probe.
  bool socket_wall = false;
  double bore_radius_m = 0.005;
  double wall_band_m = 0.01;
  // The station face is a square this far to each side of the socket: beyond it there is nothing
  // to touch (an unbounded face counted a vehicle that had drifted 5 m aside while searching as
  // touching the station).
  double face_half_size_m = 0.5;
};

void describe(ParamVisitor& v, ContactParams& p);

struct CameraSimParams {
  // Exposure to delivery: the frame grab() returns shows the world this long ago.
  double latency_ms = 40.0;
  RenderOptions render;  // render.noise_sigma is replaced by each trial's image noise
  // Not a key of its own: camera.v4l2's manual exposure time (auto_exposure false), so that one
  // setting exposes the rig's cameras and the simulated ones; 0: the cameras' auto exposure.
  double exposure_ms = 0.0;
};

void describe(ParamVisitor& v, CameraSimParams& p);

struct SensorSimParams {
  double depth_noise_m = 0.005;     // pressure sensor (Bar30 resolution ~2 mm)
  double attitude_noise_deg = 0.5;  // AHRS attitude noise, per axis
  double gyro_noise_radps = 0.005;  // rate noise, per axis
};

void describe(ParamVisitor& v, SensorSimParams& p);

// Randomised initial conditions for the docking trials (issue: 0.6-1.5 m from the station, the
// marker in view of at least one camera or not at all, current up to 0.1 m/s, image noise).
struct TrialRandomisation {
  double distance_min_m = 0.6;  // left camera to marker centre, at the start
  double distance_max_m = 1.5;
  double bearing_max_deg = 20.0;         // camera position off the docking axis, horizontally
  double elevation_max_deg = 10.0;       // and vertically
  double heading_offset_max_deg = 40.0;  // vehicle heading off the bearing to the marker
  double roll_pitch_max_deg = 3.0;
  double out_of_view_fraction = 0.0;   // share of trials that start with the marker in no view
  double visibility_margin_px = 10.0;  // a sphere counts as in view this far inside the border
  double current_max_mps = 0.1;        // horizontal current speed, uniform in [0, max]
  double noise_sigma_min = 1.0;        // image noise, grey levels, uniform in [min, max]
  double noise_sigma_max = 5.0;
};

void describe(ParamVisitor& v, TrialRandomisation& p);

// The recharging mission's world: the battery, the station's charger, how much faster the charge
// runs than the physics while seated, and the sea `rovctl sim --mission recharge` docks into.
struct RechargeSimParams {
  BatteryParams battery;
  ChargerParams charger;
  // While the probe is seated the battery (and the energy books) run this many times faster than
  // the physics: a charge of an hour takes under a minute of ticks, the hold still at tick rate.
  double seated_time_scale = 100.0;
  double initial_soc_min = 0.3;  // each trial's starting SoC, uniform in [min, max]
  double initial_soc_max = 0.5;
  // The sea of the recharge trials (replacing trials.current_max_mps and the current's tide and
  // gusts); the latch stays open, the vehicle holds itself seated.
  double current_max_mps = 0.15;
  double tide_turn_degps = 1.0;
  double gust_peak_mps = 0.05;
  double gust_duration_s = 4.0;
  double gust_interval_s = 15.0;
};

void describe(ParamVisitor& v, RechargeSimParams& p);

// The mock ArduSub (the vehicle side of `rovctl sim` with thruster_bus.backend ardusub).
struct MockArdusubParams {
  double pilot_gain = 0.5;                // ArduSub's JS_GAIN_DEFAULT: scales every pilot axis
  double level_kp_nm_per_rad = 6.0;       // stabilise: roll/pitch moment per radian off level
  double level_kd_nms_per_rad = 2.0;      // and per rad/s of roll/pitch rate
  double pilot_timeout_ms = 3000.0;       // FS_PILOT_TIMEOUT: no pilot input this long: disarm
  double rc_override_time_ms = 3000.0;    // RC_OVERRIDE_TIME: an RC override holds this long
  double heartbeat_period_ms = 1000.0;    // ArduSub's HEARTBEAT (1 Hz)
  double surface_pressure_hpa = 1013.25;  // the pressure sensor's reading at depth 0
  double water_density_kg_m3 = 1025.0;
};

void describe(ParamVisitor& v, MockArdusubParams& p);

struct SimParams {
  double integration_step_ms = 2.0;  // physics step, finer than the control tick
  bool realtime = false;             // pace the simulation by the wall clock (hardware in the loop)
  VehicleDynamicsParams dynamics;
  ThrusterModelParams thrusters;
  WaterCurrentParams current;
  StationPlacement station;
  ContactParams contact;
  CameraSimParams camera;
  SensorSimParams sensors;
  TrialRandomisation trials;
  FaultInjection faults;
  // The imaging conditions the simulated cameras render (one of scenario_names()), and every
  // scenario's parameters.
  std::string scenario = "clear";
  ScenarioParams scenarios;
  RechargeSimParams recharge;
  MockArdusubParams ardusub;
};

void describe(ParamVisitor& v, SimParams& p);

// The recharge trials' sea and station: the current, its tide and gusts from sim.recharge, and no
// latch (the mission holds the probe seated itself).
void apply_recharge_sea(SimParams& p);

}  // namespace rovctl::hal::mock
