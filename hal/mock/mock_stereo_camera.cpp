// Rendered stereo frames from the simulated world's past pose, with latency, noise and faults.
#include "hal/mock/mock_stereo_camera.hpp"

#include <cmath>

namespace rovctl::hal::mock {

namespace {
// Both views draw the same scene: one layout seed for the pair, apart from the noise's.
SceneConditions world_scene(const SimulatedWorld& world, std::uint64_t noise_seed) {
  const SimParams& p = world.params();
  return scene_conditions(p.scenario, p.scenarios, noise_seed * 0x9E3779B97F4A7C15ull + 0x5CE4E);
}
}  // namespace

MockStereoCamera::MockStereoCamera(const SimulatedWorld& world, const StereoRig& rig,
                                   const MarkerModel& marker, const CameraSimParams& params,
                                   const FaultInjection& faults, std::uint64_t noise_seed)
    : world_(world),
      rig_(rig),
      left_(rig.left, marker, params.render, world_scene(world, noise_seed)),
      right_(rig.right, marker, params.render, world_scene(world, noise_seed)),
      latency_(std::llround(params.latency_ms * 1e6)),
      faults_(faults),
      noise_seed_(noise_seed),
      drop_rng_(noise_seed ^ 0x5DEECE66Dull) {}

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
  last_truth_ = world_.T_cl_marker_at(capture);
  if (FaultInjection::active(faults_.marker_hidden_at_s, now)) {
    // Far off to the side: every sphere projects outside both images.
    last_truth_.translation() = Eigen::Vector3d(1000.0, 0.0, 5.0);
  }
  // A fresh noise pattern per frame, reproducible from the trial's seed.
  const std::uint64_t seed = noise_seed_ ^ (0x9E3779B97F4A7C15ull * (sequence_ + 1));
  const double capture_s = std::chrono::duration<double>(capture).count();
  render_stereo(left_, right_, rig_, last_truth_, seed, capture_s, frame.left_bgr, frame.right_bgr);
  frame.left_stamp = capture;
  frame.right_stamp = capture;
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
