// Randomised initial conditions of docking trial i for seed s: where the vehicle starts
// (0.6-1.5 m from the station, the marker in view of at least one camera or in neither), the
// current (up to 0.1 m/s) and the image noise. The same (i, s) always gives the same trial.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>

#include "hal/mock/sim_params.hpp"
#include "hal/mock/vehicle_dynamics.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::hal::mock {

struct TrialConditions {
  int index = 0;
  std::uint64_t seed = 0;
  VehicleState initial;  // at rest
  Eigen::Vector3d current_mean_world_mps = Eigen::Vector3d::Zero();
  double image_noise_sigma = 0.0;  // grey levels
  std::uint64_t world_seed = 0;    // the current's random part
  std::uint64_t camera_seed = 0;   // image noise
  std::uint64_t sensor_seed = 0;   // depth/attitude noise
  // What was drawn, for the trial log.
  double distance_m = 0.0;  // left camera to marker centre
  double bearing_deg = 0.0;
  double elevation_deg = 0.0;
  double heading_offset_deg = 0.0;    // off the line of sight to the marker
  bool marker_in_left_view = false;   // all spheres inside the left image
  bool marker_in_right_view = false;  // all spheres inside the right image
  bool as_requested = true;           // false if the visibility asked for could not be drawn
};

class TrialGenerator {
 public:
  // `rig` and `marker` are the simulated (true) cameras and marker, used to decide visibility.
  // Throws std::invalid_argument naming the sim.trials key when a range is inverted.
  TrialGenerator(const SimParams& params, const VehicleGeometry& vehicle, const StereoRig& rig,
                 const MarkerModel& marker);

  TrialConditions make(int index, std::uint64_t seed) const;

  // How many of the marker's spheres lie inside the left and right images at a body pose.
  void spheres_in_view(const Eigen::Isometry3d& T_world_body, int& left, int& right) const;

 private:
  TrialRandomisation r_;
  Eigen::Isometry3d T_world_marker_;
  Eigen::Isometry3d T_body_cl_;
  StereoRig rig_;
  MarkerModel marker_;
};

// Applies a trial's drawn conditions to a copy of the sim parameters (current, image noise).
SimParams params_for_trial(const SimParams& params, const TrialConditions& trial);

}  // namespace rovctl::hal::mock
