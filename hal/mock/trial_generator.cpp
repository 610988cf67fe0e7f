// Draws trial starts by rejection: position on a sphere segment in front of the station, then a
// heading that puts the marker fully in at least one view (or in neither, when asked).
#include "hal/mock/trial_generator.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "hal/model/pose.hpp"

namespace rovctl::hal::mock {

namespace {

// SplitMix64: decorrelates the trial index and seed into independent streams.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

void check_range(double lo, double hi, const char* lo_key, const char* hi_key) {
  if (lo > hi) {
    throw std::invalid_argument(std::string("sim.trials.") + lo_key + " (" + std::to_string(lo) +
                                ") is greater than sim.trials." + hi_key + " (" +
                                std::to_string(hi) + ")");
  }
}

}  // namespace

TrialGenerator::TrialGenerator(const SimParams& params, const VehicleGeometry& vehicle,
                               const StereoRig& rig, const MarkerModel& marker)
    : r_(params.trials),
      T_world_marker_(station_T_world_marker(params.station)),
      T_body_cl_(vehicle.T_body_cl()),
      rig_(rig),
      marker_(marker) {
  check_range(r_.distance_min_m, r_.distance_max_m, "distance_min_m", "distance_max_m");
  check_range(r_.noise_sigma_min, r_.noise_sigma_max, "noise_sigma_min", "noise_sigma_max");
}

void TrialGenerator::spheres_in_view(const Eigen::Isometry3d& T_world_body, int& left,
                                     int& right) const {
  const Eigen::Isometry3d T_cl_marker = (T_world_body * T_body_cl_).inverse() * T_world_marker_;
  const Eigen::Isometry3d T_cr_marker = rig_.T_cr_cl * T_cl_marker;
  auto inside = [this](const CameraModel& cam, const Eigen::Vector3d& p) {
    Eigen::Vector2d uv;
    if (p.z() < 0.05 || !cam.project(p, uv)) return false;
    const double m = r_.visibility_margin_px;
    return uv.x() >= m && uv.y() >= m && uv.x() <= cam.width_px - 1 - m &&
           uv.y() <= cam.height_px - 1 - m;
  };
  left = right = 0;
  for (const MarkerSphere& s : marker_.spheres) {
    left += inside(rig_.left, T_cl_marker * s.centre_marker_m) ? 1 : 0;
    right += inside(rig_.right, T_cr_marker * s.centre_marker_m) ? 1 : 0;
  }
}

TrialConditions TrialGenerator::make(int index, std::uint64_t seed) const {
  TrialConditions t;
  t.index = index;
  t.seed = seed;
  std::mt19937_64 rng(mix(seed ^ mix(static_cast<std::uint64_t>(index))));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  t.world_seed = rng();
  t.camera_seed = rng();
  t.sensor_seed = rng();

  const bool want_visible = unit(rng) >= r_.out_of_view_fraction;
  t.distance_m = uniform(r_.distance_min_m, r_.distance_max_m);
  t.bearing_deg = uniform(-r_.bearing_max_deg, r_.bearing_max_deg);
  t.elevation_deg = uniform(-r_.elevation_max_deg, r_.elevation_max_deg);
  const double b = t.bearing_deg * kRadPerDeg;
  const double e = t.elevation_deg * kRadPerDeg;
  // Camera position in the marker frame: in front of it (-z), to starboard (+x) for a positive
  // bearing, above (-y) for a positive elevation.
  const Eigen::Vector3d cam_marker =
      t.distance_m *
      Eigen::Vector3d(std::cos(e) * std::sin(b), -std::sin(e), -std::cos(e) * std::cos(b));
  const Eigen::Vector3d cam_world = T_world_marker_ * cam_marker;
  const Eigen::Vector3d sight = T_world_marker_.translation() - cam_world;
  const double sight_heading = std::atan2(sight.y(), sight.x());

  // Out-of-view starts turn the vehicle further away than in-view ones may.
  const double h_max = want_visible
                           ? r_.heading_offset_max_deg
                           : std::min(180.0, std::max(90.0, 2.0 * r_.heading_offset_max_deg));
  const double rp = r_.roll_pitch_max_deg * kRadPerDeg;
  const double roll = uniform(-rp, rp);
  const double pitch = uniform(-rp, rp);
  auto pose_for = [&](double heading_offset_deg) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(sight_heading + heading_offset_deg * kRadPerDeg,
                                                 Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    // Place the body so that the left camera sits at the drawn point.
    T.translation() = cam_world - R * T_body_cl_.translation();
    return T;
  };

  int left = 0, right = 0;
  const int n = static_cast<int>(marker_.spheres.size());
  bool found = false;
  Eigen::Isometry3d T_world_body = pose_for(0.0);
  for (int attempt = 0; attempt < 500 && !found; ++attempt) {
    const double h = uniform(-h_max, h_max);
    const Eigen::Isometry3d T = pose_for(h);
    spheres_in_view(T, left, right);
    found = want_visible ? (left == n || right == n) : (left == 0 && right == 0);
    if (found) {
      T_world_body = T;
      t.heading_offset_deg = h;
    }
  }
  if (!found) {
    // Fall back to facing the marker; the log says the draw was not what was asked.
    t.as_requested = false;
    t.heading_offset_deg = 0.0;
    T_world_body = pose_for(0.0);
  }
  spheres_in_view(T_world_body, left, right);
  t.marker_in_left_view = left == n;
  t.marker_in_right_view = right == n;
  t.initial.position_world_m = T_world_body.translation();
  t.initial.q_world_body = Eigen::Quaterniond(T_world_body.linear());
  t.initial.nu_body.setZero();

  const double speed = uniform(0.0, r_.current_max_mps);
  const double direction = uniform(-M_PI, M_PI);
  t.current_mean_world_mps = {speed * std::cos(direction), speed * std::sin(direction), 0.0};
  t.image_noise_sigma = uniform(r_.noise_sigma_min, r_.noise_sigma_max);
  return t;
}

SimParams params_for_trial(const SimParams& params, const TrialConditions& trial) {
  SimParams p = params;
  p.current.mean_world_mps = trial.current_mean_world_mps;
  p.camera.render.noise_sigma = trial.image_noise_sigma;
  return p;
}

}  // namespace rovctl::hal::mock
