// MockStereoCamera: the StereoCamera of the simulation. Each grab renders both views of the
// marker as the world stood `latency` ago (from the world's pose history), with image noise, in
// the world's imaging scenario (sim.scenario) at that time; the images are all the estimator
// gets. Fault injection: camera lost from a time, dropped frames, a burst of timeouts, frozen,
// stale or skewed frames, a black right image, the marker out of view, a CPU stall. The exposure
// smears the marker as it moves: a manual exposure (camera.v4l2.exposure_time_us) in every
// scenario, and in the exposure scenario the auto exposure too, on a vibrating mount.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>

#include "hal/interfaces/stereo_camera.hpp"
#include "hal/mock/fault_injection.hpp"
#include "hal/mock/scene_renderer.hpp"
#include "hal/mock/sim_clock.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/simulated_world.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::hal::mock {

class MockStereoCamera final : public StereoCamera {
 public:
  // `rig` and `marker` are the true cameras and marker (usually those of the calibration and
  // config); params.render.noise_sigma is the image noise (see params_for_trial()). The scenario
  // is the world's (world.params().scenario); its random layout follows from noise_seed. Throws
  // std::invalid_argument for an unknown scenario.
  MockStereoCamera(const SimulatedWorld& world, const StereoRig& rig, const MarkerModel& marker,
                   const CameraSimParams& params, const FaultInjection& faults,
                   std::uint64_t noise_seed);

  bool open(std::string& error) override;
  // Renders the pair seen at world time - latency, stamped with that capture time, with the
  // scenario's moving parts as they stood then. No heap allocation once `frame`'s images have
  // the camera size.
  GrabStatus grab(StereoFrame& frame) override;
  void close() override { open_ = false; }
  std::string name() const override { return "mock stereo camera"; }

  // How long a frame is exposed (0: sharp, the instant of its stamp), and whether the frame says
  // so (a manual exposure: the driver reads it back; an auto one it does not know).
  std::chrono::nanoseconds exposure() const { return exposure_; }
  bool exposure_known() const { return exposure_known_; }

  // The true marker pose behind the last frame delivered (mid-exposure) (for evaluation and logs
  // only: it must not reach the estimator or the controller).
  const Eigen::Isometry3d& last_T_cl_marker_truth() const { return last_truth_; }
  std::chrono::nanoseconds latency() const { return latency_; }
  FaultInjection& faults() { return faults_; }
  // The clock a CPU stall (faults.cpu_stall_*) advances while the grab "works"; none: no stalls.
  void stall_clock(SimClock* clock) { stall_clock_ = clock; }

 private:
  // The most sub-frames one exposure is rendered from: one per pixel of smear up to here.
  static constexpr int kMaxSubframes = 24;

  // The left camera's view of the marker at `t`, turned by the mount's vibration.
  Eigen::Isometry3d T_cl_marker_at(std::chrono::nanoseconds t) const;
  // Fills poses_ over the exposure centred on `capture`; returns how many.
  int exposure_poses(std::chrono::nanoseconds capture);

  const SimulatedWorld& world_;
  StereoRig rig_;
  SceneRenderer left_;
  SceneRenderer right_;
  std::chrono::nanoseconds latency_;
  FaultInjection faults_;
  std::uint64_t noise_seed_;
  std::mt19937_64 drop_rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  bool open_ = false;
  SimClock* stall_clock_ = nullptr;
  std::uint64_t sequence_ = 0;
  Eigen::Isometry3d last_truth_ = Eigen::Isometry3d::Identity();
  std::chrono::nanoseconds exposure_{0};
  bool exposure_known_ = false;
  bool vibrating_ = false;
  ExposureDrift vibration_;
  std::array<Eigen::Isometry3d, kMaxSubframes> poses_left_;
  std::array<Eigen::Isometry3d, kMaxSubframes> poses_right_;
  ExposureScratch scratch_left_;
  ExposureScratch scratch_right_;
};

}  // namespace rovctl::hal::mock
