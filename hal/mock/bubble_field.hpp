// The bubbles scenario's content: air bubbles rising past the marker and floating marine snow,
// laid out once from a seed and moved as pure functions of time, so a frame is (seed, t) alone.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "hal/model/camera_model.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::hal::mock {

constexpr int kMaxBubbles = 128;
constexpr int kMaxParticles = 512;

// Bubbles from a leaking fitting, a diver, a vent. Volumes in the marker frame (x right, y down =
// world down, z into the station): by default a plume rising between the vehicle and the marker.
// Bubbles of 2-5 mm radius rise at 0.18-0.30 m/s and zig-zag (R. Clift, J. R. Grace and M. E.
// Weber, Bubbles, Drops, and Particles, Academic Press 1978: terminal velocity of air bubbles in
// water ~0.2-0.3 m/s over that size range); marine snow sinks at millimetres per second and drifts.
struct BubbleParams {
  int bubble_count = 80;
  double bubble_radius_min_m = 0.002;
  double bubble_radius_max_m = 0.005;
  double rise_speed_min_mps = 0.18;
  double rise_speed_max_mps = 0.30;
  double wobble_m = 0.006;  // amplitude of the zig-zag across the rise
  double wobble_hz = 2.0;
  Eigen::Vector3d bubble_volume_min_marker_m{-0.2, -0.5, -0.8};
  Eigen::Vector3d bubble_volume_max_marker_m{0.2, 0.5, -0.05};
  double rim_opacity = 0.7;        // the bright rim: light refracted and reflected at the wall
  double interior_opacity = 0.15;  // the translucent body
  int particle_count = 400;
  double particle_radius_min_m = 0.0005;
  double particle_radius_max_m = 0.0015;
  double particle_drift_mps = 0.01;  // random drift speed, at most, per axis
  double particle_sink_mps = 0.003;
  double particle_opacity = 0.6;
  Eigen::Vector3d particle_volume_min_marker_m{-0.8, -0.6, -1.8};
  Eigen::Vector3d particle_volume_max_marker_m{0.8, 0.6, 0.1};
};

void describe(ParamVisitor& v, BubbleParams& p);

struct Speck {
  Eigen::Vector3d centre_marker_m;
  double radius_m;
};

class BubbleField {
 public:
  // Throws std::invalid_argument naming the sim.scenarios.bubbles key when a range is inverted.
  BubbleField(const BubbleParams& params, std::uint64_t seed);

  int bubble_count() const { return bubble_count_; }
  int particle_count() const { return particle_count_; }
  // Positions at `time_s` (any real time; negative is before the start): bubbles wrap from the
  // top of their volume back to its bottom, particles wrap within theirs.
  Speck bubble(int i, double time_s) const;
  Speck particle(int i, double time_s) const;

  // Blend one bubble or particle at camera-frame position `centre_cam_m` into out_bgr.
  void draw_bubble(const CameraModel& cam, const Eigen::Vector3d& centre_cam_m, double radius_m,
                   cv::Mat& out_bgr) const;
  void draw_particle(const CameraModel& cam, const Eigen::Vector3d& centre_cam_m, double radius_m,
                     cv::Mat& out_bgr) const;

 private:
  struct Seed {
    Eigen::Vector3d start;  // position at time 0
    Eigen::Vector3d velocity_mps;
    double radius_m;
    double phase_rad;
  };

  BubbleParams p_;
  int bubble_count_ = 0;
  int particle_count_ = 0;
  std::array<Seed, kMaxBubbles> bubbles_{};
  std::array<Seed, kMaxParticles> particles_{};
};

}  // namespace rovctl::hal::mock
