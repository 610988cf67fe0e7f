// Rendered stereo frames from the simulated world's past pose, with latency, noise and faults.
#include "hal/mock/mock_stereo_camera.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::hal::mock {

namespace {
// Both views draw the same scene: one layout seed for the pair, apart from the noise's. A manual
// exposure holds the brightness that an auto exposure lets drift.
SceneConditions world_scene(const SimulatedWorld& world, const CameraSimParams& camera,
                            std::uint64_t noise_seed) {
  const SimParams& p = world.params();
  SceneConditions scene =
      scene_conditions(p.scenario, p.scenarios, noise_seed * 0x9E3779B97F4A7C15ull + 0x5CE4E);
  if (camera.exposure_ms > 0.0) {
    scene.params.exposure.gain_min = 1.0;
    scene.params.exposure.gain_max = 1.0;
  }
  return scene;
}

std::chrono::nanoseconds from_ms(double ms) {
  return std::chrono::nanoseconds(std::llround(ms * 1e6));
}
}  // namespace

MockStereoCamera::MockStereoCamera(const SimulatedWorld& world, const StereoRig& rig,
                                   const MarkerModel& marker, const CameraSimParams& params,
                                   const FaultInjection& faults, std::uint64_t noise_seed)
    : world_(world),
      rig_(rig),
      left_(rig.left, marker, params.render, world_scene(world, params, noise_seed)),
      right_(rig.right, marker, params.render, world_scene(world, params, noise_seed)),
      latency_(std::llround(params.latency_ms * 1e6)),
      faults_(faults),
      noise_seed_(noise_seed),
      drop_rng_(noise_seed ^ 0x5DEECE66Dull) {
  const bool exposure_scenario = left_.scenario() == Scenario::exposure;
  vibration_ = world.params().scenarios.exposure;
  vibrating_ = exposure_scenario && vibration_.vibration_deg > 0.0;
  if (params.exposure_ms > 0.0) {
    exposure_ = from_ms(params.exposure_ms);
    exposure_known_ = true;
  } else if (exposure_scenario) {
    exposure_ = from_ms(vibration_.auto_exposure_ms);  // the sim knows it; the frame does not
  }
}

Eigen::Isometry3d MockStereoCamera::T_cl_marker_at(std::chrono::nanoseconds t) const {
  Eigen::Isometry3d T = world_.T_cl_marker_at(t);
  if (vibrating_) {
    T.prerotate(vibration_rotation(vibration_, std::chrono::duration<double>(t).count()));
  }
  return T;
}

int MockStereoCamera::exposure_poses(std::chrono::nanoseconds capture) {
  poses_left_[0] = T_cl_marker_at(capture);
  if (exposure_.count() <= 0) return 1;
  // The marker's path across the left image during the exposure, in pixels, sets how many
  // sub-frames draw the smear: about one per pixel, so that it reads as a streak.
  constexpr int kProbe = 8;
  double path_px = 0.0;
  Eigen::Vector2d prev;
  bool have_prev = false;
  for (int k = 0; k <= kProbe; ++k) {
    const auto t = capture - exposure_ / 2 + exposure_ * k / kProbe;
    Eigen::Vector2d uv;
    if (!rig_.left.project(T_cl_marker_at(t).translation(), uv)) continue;
    if (have_prev) path_px += (uv - prev).norm();
    prev = uv;
    have_prev = true;
  }
  const int count = std::clamp(static_cast<int>(std::ceil(path_px)), 1, kMaxSubframes);
  if (count == 1) return 1;
  for (int k = 0; k < count; ++k) {
    const auto t = capture - exposure_ / 2 + exposure_ * (2 * k + 1) / (2 * count);
    poses_left_[static_cast<std::size_t>(k)] = T_cl_marker_at(t);
  }
  return count;
}

bool MockStereoCamera::open(std::string& error) {
  if (FaultInjection::active(faults_.camera_lost_at_s, world_.time())) {
    error = "mock stereo camera: device lost (injected fault sim.faults.camera_lost_at_s)";
    return false;
  }
  open_ = true;
  return true;
}

GrabStatus MockStereoCamera::grab(StereoFrame& frame) {
  const std::chrono::nanoseconds now = world_.time();
  if (!open_ || FaultInjection::active(faults_.camera_lost_at_s, now) ||
      world_.seated_fault_active(faults_.camera_lost_after_seated_s)) {
    return GrabStatus::device_lost;
  }
  if (faults_.camera_timeout_probability > 0.0 &&
      unit_(drop_rng_) < faults_.camera_timeout_probability) {
    return GrabStatus::timeout;
  }
  if (FaultInjection::active(faults_.camera_drop_at_s, faults_.camera_drop_for_s, now)) {
    return GrabStatus::timeout;
  }
  if (stall_clock_ != nullptr &&
      FaultInjection::active(faults_.cpu_stall_at_s, faults_.cpu_stall_for_s, now)) {
    stall_clock_->advance(std::chrono::nanoseconds(std::llround(faults_.cpu_stall_ms * 1e6)));
  }
  if (FaultInjection::active(faults_.frozen_frames_at_s, faults_.frozen_frames_for_s, now) &&
      sequence_ > 0) {
    // A hung driver hands over the last buffer again, newly stamped.
    frame.left_stamp = frame.right_stamp = now - latency_;
    frame.sequence = sequence_++;
    return GrabStatus::ok;
  }
  std::chrono::nanoseconds capture = now - latency_;
  if (FaultInjection::active(faults_.stale_frames_at_s, faults_.stale_frames_for_s, now)) {
    capture -= std::chrono::nanoseconds(std::llround(faults_.stale_ms * 1e6));
  }
  // The exposure is centred on the capture stamp, so a sharp frame is the world at the stamp.
  int count = exposure_poses(capture);
  last_truth_ = T_cl_marker_at(capture);
  if (FaultInjection::active(faults_.marker_hidden_at_s, now)) {
    // Far off to the side: every sphere projects outside both images.
    last_truth_.translation() = Eigen::Vector3d(1000.0, 0.0, 5.0);
    poses_left_[0] = last_truth_;
    count = 1;
  }
  for (int k = 0; k < count; ++k) {
    poses_right_[static_cast<std::size_t>(k)] =
        rig_.T_cr_cl * poses_left_[static_cast<std::size_t>(k)];
  }
  // A fresh noise pattern per frame, reproducible from the trial's seed.
  const std::uint64_t seed = noise_seed_ ^ (0x9E3779B97F4A7C15ull * (sequence_ + 1));
  const double capture_s = std::chrono::duration<double>(capture).count();
  left_.render_exposed(poses_left_.data(), count, seed, capture_s, frame.left_bgr, scratch_left_);
  right_.render_exposed(poses_right_.data(), count, right_noise_seed(seed), capture_s,
                        frame.right_bgr, scratch_right_);
  frame.left_stamp = capture;
  frame.right_stamp = capture;
  frame.exposure = exposure_known_ ? exposure_ : std::chrono::nanoseconds(0);
  if (FaultInjection::active(faults_.stamp_skew_at_s, faults_.stamp_skew_for_s, now)) {
    frame.right_stamp -= std::chrono::nanoseconds(std::llround(faults_.stamp_skew_ms * 1e6));
  }
  if (FaultInjection::active(faults_.camera_black_at_s, faults_.camera_black_for_s, now)) {
    frame.right_bgr.setTo(cv::Scalar::all(0));
  }
  frame.sequence = sequence_++;
  return GrabStatus::ok;
}

}  // namespace rovctl::hal::mock
