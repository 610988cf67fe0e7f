// The marker's pose carried across frames: each sound estimate fused into a track that the
// vehicle's attitude and the track's own velocity predict, and coasted, with a growing bound,
// through frames the estimator declines (a hidden sphere, passing bubbles, a smear).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstdint>

namespace rovctl::control {

// Declared rates and limits of the track (the `control.tracker` config section).
struct PoseTrackerParams {
  // The mission acts on the tracked pose; false: on each frame's estimate alone.
  bool enabled = true;
  // The tracked pose is ok at most this long after the last fused estimate.
  double max_coast_s = 1.5;
  // How fast the vehicle's velocity can change: the coast's position bound grows by half this
  // times the coast's time squared (the velocity estimate holds only as long as the velocity).
  // The rendered approaches' sway and easing reach 0.34 m/s^2.
  double accel_mps2 = 0.35;
  // The fastest the vehicle moves: the velocity's bound before the track has a history, and the
  // reach of a new track's second estimate.
  double speed_mps = 1.0;
  // The attitude sensor's error growth between two frames: the coast's rotation bound grows at
  // this rate (the station does not turn, so the camera's own turn carries the marker's).
  double attitude_drift_dps = 0.1;
  // The attitude the track is carried by: the body rates between reads, pulled toward the
  // attitude sensor's with this time constant (AttitudeFilter). 0: the sensor's as read.
  double attitude_filter_s = 2.0;
  // The fastest the vehicle turns: the rotation bound's growth without a valid attitude.
  double turn_rate_dps = 60.0;
  // The fused bound never goes below these, however many estimates agree.
  double floor_mm = 2.0;
  double floor_deg = 0.3;
  // Nor below this share of the newest estimate's own bound: consecutive estimates share their
  // errors (the same water, the same fit's lean: a turbid approach's rotation was 2-3 deg off for
  // ten frames in a row), so agreeing frames are not independent draws that average out.
  double fused_bound_share = 1.0;
  // A partial view's sphere centres (those whose rims show in both views) lie within this of the
  // truth: two or more that agree with each other under the track's rotation fix its translation
  // while a sphere is hidden. 0: partial views are not used.
  double partial_point_mm = 3.0;
  // Sound estimates that disagree with the prediction by more than both bounds explain, over
  // about this long, are a motion of the camera the attitude does not carry (a camera shaking on
  // its mount): its size widens the prediction's bounds, so the track takes such estimates as
  // they come and coasts no surer than the camera holds still. 0: off.
  double unexplained_window_s = 1.0;
  // The velocity is the slope of the fused positions over this much of the track's history: a
  // longer window averages the estimates' noise but lags an accelerating vehicle by half of it.
  double velocity_window_s = 0.2;
};

// One frame's estimate as the tracker takes it. `sound`: it passed its own frame's tests (the
// estimator's ok, before or without the frame-to-frame confirmation: the tracker confirms it
// against its own prediction); bounds are 99 % bounds of the estimate's error.
struct PoseMeasurement {
  bool sound = false;
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  double bound_m = 0.0;
  double bound_deg = 0.0;
  // Not sound but recognised: the marker points (sphere centres) the estimate is supported by in
  // both views, 0..kMaxPoints of them; the tracker places them with T_cl_marker and its own
  // rotation to update the translation.
  static constexpr int kMaxPoints = 3;
  int points = 0;
  std::array<Eigen::Vector3d, kMaxPoints> points_marker_m{};
};

enum class TrackSource : std::uint8_t {
  none = 0,      // no track
  fused = 1,     // this frame's estimate agreed with the track and was fused into it
  coasting = 2,  // predicted from the last fused estimate
  aided = 3,     // a partial view's spheres fused into the translation, the rotation predicted
  nudged = 4,    // a partial view moved the translation; the bound grows as the coast's
};
const char* to_string(TrackSource source);

struct TrackedPose {
  bool ok = false;  // coasting within max_coast_s and both bounds within the estimator's ok limits
  TrackSource source = TrackSource::none;
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  double bound_m = 0.0, bound_deg = 0.0;
  std::chrono::nanoseconds age{0};  // since the last fused sound estimate
  bool rejected = false;            // this frame's sound estimate disagreed with the track
};

// A single estimate can be sure and wrong (a rim fitted to a fading sphere); two in a row the same
// way are not expected. So a track starts from two sound estimates that agree, takes a later one
// only when it agrees with the prediction within both bounds (an innovation gate), and moves to a
// disagreeing one only when the next sound estimate confirms that instead. Fusion weighs the
// prediction and the estimate by their inverse variances (bounds as 3 sigma), so the bound
// tightens as agreeing frames come in, down to the floor. The state is kept in world axes centred
// on the left camera: the marker's position there changes only with the vehicle's translation, its
// rotation not at all. Holds a fixed history; allocates nothing.
class PoseTracker {
 public:
  static constexpr int kHistory = 32;

  // ok_bound_m / ok_bound_deg: the estimator's ok limits, which the tracked pose keeps too.
  PoseTracker(const PoseTrackerParams& params, const Eigen::Isometry3d& T_body_cl,
              double ok_bound_m, double ok_bound_deg);

  // One frame captured at `capture` with the vehicle at q_world_body (attitude_valid false: the
  // attitude is not known, the rotation coasts unchanged at turn_rate_dps). A measurement that is
  // not sound only coasts the track.
  const TrackedPose& update(std::chrono::nanoseconds capture,
                            const Eigen::Quaterniond& q_world_body, bool attitude_valid,
                            const PoseMeasurement& measurement);

  // The track's pose predicted to `capture` without changing it (no estimate at that time).
  TrackedPose predict(std::chrono::nanoseconds capture, const Eigen::Quaterniond& q_world_body,
                      bool attitude_valid) const;

  void reset();
  const TrackedPose& last() const { return out_; }

 private:
  // A pose in world axes centred on the camera: p_w = R_world_cl t_cl_marker.
  struct WorldPose {
    Eigen::Vector3d p_w = Eigen::Vector3d::Zero();
    Eigen::Matrix3d R_world_marker = Eigen::Matrix3d::Identity();
    double bound_m = 0.0, bound_deg = 0.0;
    std::chrono::nanoseconds at{0};
  };
  struct Sample {
    std::chrono::nanoseconds at{0};
    Eigen::Vector3d p_w = Eigen::Vector3d::Zero();
  };

  Eigen::Matrix3d R_world_cl(const Eigen::Quaterniond& q_world_body, bool attitude_valid) const;
  WorldPose to_world(const PoseMeasurement& m, const Eigen::Matrix3d& R_world_cl,
                     std::chrono::nanoseconds at) const;
  // The track predicted to `at` (bounds grown); with the attitude unknown, about the last one.
  // With `unexplained` false, without the camera's unexplained motion (what it is judged by).
  WorldPose predicted(std::chrono::nanoseconds at, bool attitude_valid,
                      bool unexplained = true) const;
  // A sound estimate's disagreement with the prediction, beyond what their bounds explain, into
  // the camera's unexplained motion.
  void observe_innovation(const WorldPose& prediction, const WorldPose& m);
  bool agree(const WorldPose& a, const WorldPose& b) const;
  void start(const WorldPose& first, const WorldPose& second);
  // The prediction with m's position fused in by inverse variance, its bound never below the
  // floor nor fused_bound_share of m's.
  WorldPose fused_translation(const WorldPose& prediction, const WorldPose& m) const;
  void fuse(const WorldPose& prediction, const WorldPose& m);
  // A partial view: the translation its points give with the predicted rotation, fused (aided)
  // when two or more agree with each other and with the prediction, moving the track without
  // vouching for it (nudged) when only the prediction agrees, else coasting.
  TrackSource aid(const WorldPose& prediction, const PoseMeasurement& m,
                  const Eigen::Matrix3d& R_world_cl, std::chrono::nanoseconds capture);
  void remember(const WorldPose& pose);
  void estimate_velocity();
  TrackedPose output(const WorldPose& pose, const Eigen::Matrix3d& R_world_cl, TrackSource source,
                     std::chrono::nanoseconds capture) const;

  PoseTrackerParams params_;
  Eigen::Matrix3d R_body_cl_;
  double ok_bound_m_, ok_bound_deg_;
  bool have_track_ = false;
  WorldPose track_;                       // the last fused pose
  std::chrono::nanoseconds sound_at_{0};  // the last sound estimate fused
  Eigen::Vector3d velocity_w_ = Eigen::Vector3d::Zero();
  // Mean squares (m^2, deg^2) of the sound estimates' innovations beyond their gates: the
  // camera's motion the attitude does not carry.
  double unexplained_m2_ = 0.0, unexplained_deg2_ = 0.0;
  double beyond_gate_ = 0.0;  // the share of sound estimates beyond their gates
  bool have_innovation_ = false;
  std::chrono::nanoseconds innovation_at_{0};
  double velocity_bound_mps_ = 0.0;
  bool have_candidate_ = false;
  WorldPose candidate_;  // a sound estimate the track did not take, waiting for a second
  std::array<Sample, kHistory> history_{};
  int history_size_ = 0, history_next_ = 0;
  Eigen::Matrix3d last_R_world_cl_ = Eigen::Matrix3d::Identity();
  bool have_attitude_ = false;
  TrackedPose out_;
};

}  // namespace rovctl::control
