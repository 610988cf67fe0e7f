// MockStereoCamera: the StereoCamera of the simulation. Each grab renders both views of the
// marker as the world stood `latency` ago (from the world's pose history), with image noise, in
// the world's imaging scenario (sim.scenario) at that time; the images are all the estimator
// gets. Fault injection: camera lost from a time, dropped frames, a burst of timeouts, frozen,
// stale or skewed frames, a black right image, the marker out of view, a CPU stall.
#pragma once

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

  // The true marker pose behind the last frame delivered (for evaluation and logs only: it must
  // not reach the estimator or the controller).
  const Eigen::Isometry3d& last_T_cl_marker_truth() const { return last_truth_; }
  std::chrono::nanoseconds latency() const { return latency_; }
  FaultInjection& faults() { return faults_; }
  // The clock a CPU stall (faults.cpu_stall_*) advances while the grab "works"; none: no stalls.
  void stall_clock(SimClock* clock) { stall_clock_ = clock; }

 private:
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
};

}  // namespace rovctl::hal::mock
