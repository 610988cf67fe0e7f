// The marker's pose tracked across frames (see pose_tracker.hpp). No allocation.
#include "control/pose_tracker.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "hal/primitives/duration_seconds.hpp"

namespace rovctl::control {
namespace {

using hal::seconds;

constexpr double kDegPerRad = 180.0 / M_PI;

double angle_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return std::abs(Eigen::AngleAxisd(a.transpose() * b).angle()) * kDegPerRad;
}

}  // namespace

const char* to_string(TrackSource source) {
  switch (source) {
    case TrackSource::fused:
      return "fused";
    case TrackSource::coasting:
      return "coasting";
    case TrackSource::aided:
      return "aided";
    case TrackSource::nudged:
      return "nudged";
    case TrackSource::none:
      break;
  }
  return "none";
}

PoseTracker::PoseTracker(const PoseTrackerParams& params, const Eigen::Isometry3d& T_body_cl,
                         double ok_bound_m, double ok_bound_deg)
    : params_(params),
      R_body_cl_(T_body_cl.linear()),
      ok_bound_m_(ok_bound_m),
      ok_bound_deg_(ok_bound_deg) {}

void PoseTracker::reset() {
  have_track_ = false;
  have_candidate_ = false;
  history_size_ = 0;
  history_next_ = 0;
  velocity_w_.setZero();
  unexplained_m2_ = 0.0;
  unexplained_deg2_ = 0.0;
  beyond_gate_ = 0.0;
  have_innovation_ = false;
  out_ = TrackedPose{};
}

Eigen::Matrix3d PoseTracker::R_world_cl(const Eigen::Quaterniond& q_world_body,
                                        bool attitude_valid) const {
  if (!attitude_valid) return last_R_world_cl_;
  return q_world_body.normalized().toRotationMatrix() * R_body_cl_;
}

PoseTracker::WorldPose PoseTracker::to_world(const PoseMeasurement& m,
                                             const Eigen::Matrix3d& R_world_cl,
                                             std::chrono::nanoseconds at) const {
  WorldPose w;
  w.p_w = R_world_cl * m.T_cl_marker.translation();
  w.R_world_marker = R_world_cl * m.T_cl_marker.linear();
  w.bound_m = m.bound_m;
  w.bound_deg = m.bound_deg;
  w.at = at;
  return w;
}

PoseTracker::WorldPose PoseTracker::predicted(std::chrono::nanoseconds at, bool attitude_valid,
                                              bool unexplained) const {
  WorldPose p = track_;
  const double dt_s = std::max(0.0, seconds(at - track_.at));
  // The camera's turn is the attitude sensor's to carry, within its drift; without it, the
  // marker may have turned in the camera as fast as the vehicle turns.
  const double turn_deg =
      (attitude_valid ? params_.attitude_drift_dps : params_.turn_rate_dps) * dt_s;
  p.p_w += velocity_w_ * dt_s;
  p.bound_m += velocity_bound_mps_ * dt_s + 0.5 * params_.accel_mps2 * dt_s * dt_s +
               p.p_w.norm() * turn_deg / kDegPerRad;
  p.bound_deg += turn_deg;
  // The gates are 99 % bounds: one sound estimate in ten beyond its gate is no longer chance
  // (a lone one beyond it, in far turbid water, is).
  constexpr double kShakeShare = 0.1;
  if (unexplained && beyond_gate_ > kShakeShare) {
    // Three times the excess's root mean square; the camera's own turn swings the marker's
    // position by its lever.
    const double shake_deg = 3.0 * std::sqrt(unexplained_deg2_);
    p.bound_m += 3.0 * std::sqrt(unexplained_m2_) + p.p_w.norm() * shake_deg / kDegPerRad;
    p.bound_deg += shake_deg;
  }
  p.at = at;
  return p;
}

void PoseTracker::observe_innovation(const WorldPose& prediction, const WorldPose& m) {
  if (params_.unexplained_window_s <= 0.0) return;
  // How far the innovation reaches beyond its gate (both bounds); estimates within it explain
  // themselves. One wild estimate counts no more than twice its gate.
  const auto excess = [](double innovation, double bound_a, double bound_b) {
    const double gate = std::hypot(bound_a, bound_b);
    const double x = std::clamp(innovation - gate, 0.0, 2.0 * gate);
    return x * x;
  };
  const double d_m = (m.p_w - prediction.p_w).norm();
  const double d_deg = angle_deg(m.R_world_marker, prediction.R_world_marker);
  const double e_m2 = excess(d_m, prediction.bound_m, m.bound_m);
  const double e_deg2 = excess(d_deg, prediction.bound_deg, m.bound_deg);
  const double dt_s = have_innovation_ ? seconds(m.at - innovation_at_) : 0.0;
  const double a = std::clamp(dt_s / params_.unexplained_window_s, 0.0, 1.0);
  unexplained_m2_ += a * (e_m2 - unexplained_m2_);
  unexplained_deg2_ += a * (e_deg2 - unexplained_deg2_);
  beyond_gate_ += a * ((e_m2 > 0.0 || e_deg2 > 0.0 ? 1.0 : 0.0) - beyond_gate_);
  innovation_at_ = m.at;
  have_innovation_ = true;
}

bool PoseTracker::agree(const WorldPose& a, const WorldPose& b) const {
  // Two independent errors within their 99 % bounds differ by about the root of their squares.
  return (a.p_w - b.p_w).norm() <= std::hypot(a.bound_m, b.bound_m) &&
         angle_deg(a.R_world_marker, b.R_world_marker) <= std::hypot(a.bound_deg, b.bound_deg);
}

PoseTracker::WorldPose PoseTracker::fused_translation(const WorldPose& prediction,
                                                      const WorldPose& m) const {
  // Inverse-variance weights, the bounds taken as the same multiple of each error's sigma.
  const double wp = 1.0 / std::max(1e-12, prediction.bound_m * prediction.bound_m);
  const double wm = 1.0 / std::max(1e-12, m.bound_m * m.bound_m);
  WorldPose fused = prediction;
  fused.p_w = (wp * prediction.p_w + wm * m.p_w) / (wp + wm);
  fused.bound_m = std::max(
      {params_.floor_mm / 1000.0, params_.fused_bound_share * m.bound_m, 1.0 / std::sqrt(wp + wm)});
  return fused;
}

void PoseTracker::fuse(const WorldPose& prediction, const WorldPose& m) {
  const WorldPose translated = fused_translation(prediction, m);
  track_.p_w = translated.p_w;
  track_.bound_m = translated.bound_m;
  const double wp_deg = 1.0 / std::max(1e-12, prediction.bound_deg * prediction.bound_deg);
  const double wm_deg = 1.0 / std::max(1e-12, m.bound_deg * m.bound_deg);
  const Eigen::Quaterniond qp(prediction.R_world_marker);
  const Eigen::Quaterniond qm(m.R_world_marker);
  track_.R_world_marker = qp.slerp(wm_deg / (wp_deg + wm_deg), qm).toRotationMatrix();
  track_.bound_deg = std::max({params_.floor_deg, params_.fused_bound_share * m.bound_deg,
                               1.0 / std::sqrt(wp_deg + wm_deg)});
  track_.at = m.at;
  sound_at_ = m.at;
  remember(track_);
}

void PoseTracker::remember(const WorldPose& pose) {
  history_[history_next_] = Sample{pose.at, pose.p_w};
  history_next_ = (history_next_ + 1) % kHistory;
  history_size_ = std::min(history_size_ + 1, kHistory);
  estimate_velocity();
}

TrackSource PoseTracker::aid(const WorldPose& prediction, const PoseMeasurement& m,
                             const Eigen::Matrix3d& R_world_cl, std::chrono::nanoseconds capture) {
  if (params_.partial_point_mm <= 0.0 || m.points <= 0 || m.points > PoseMeasurement::kMaxPoints ||
      !m.T_cl_marker.matrix().allFinite()) {
    return TrackSource::coasting;
  }
  // The least-squares translation with the rotation fixed: the mean of the points' offsets. Its
  // bound: the points' own, plus the rotation's bound swinging them about the marker's origin.
  const Eigen::Matrix3d R_cl_marker = R_world_cl.transpose() * prediction.R_world_marker;
  const double point_m = params_.partial_point_mm / 1000.0;
  const double swing_rad = prediction.bound_deg / kDegPerRad;
  std::array<Eigen::Vector3d, PoseMeasurement::kMaxPoints> offsets;
  Eigen::Vector3d t = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
  double lever_m = 0.0;
  for (int i = 0; i < m.points; ++i) {
    const Eigen::Vector3d& c = m.points_marker_m[i];
    offsets[i] = m.T_cl_marker * c - R_cl_marker * c;
    t += offsets[i];
    centre += c;
    lever_m = std::max(lever_m, c.norm());
  }
  t /= static_cast<double>(m.points);
  centre /= static_cast<double>(m.points);
  // Two or more spheres placed where the track's rotation puts them relative to each other
  // vouch for their translation: a sphere whose centre an occluder shifted (a bar across it moves
  // it differently in the two views, so its depth is centimetres off) lands off the others.
  bool rigid = m.points >= 2;
  for (int i = 0; i < m.points && rigid; ++i) {
    const double lever_i = (m.points_marker_m[i] - centre).norm();
    rigid = (offsets[i] - t).norm() <= point_m + lever_i * swing_rad;
  }
  WorldPose aided = prediction;
  aided.p_w = R_world_cl * t;
  aided.bound_m = point_m + lever_m * swing_rad;
  const double innovation_m = (aided.p_w - prediction.p_w).norm();
  if (innovation_m > std::hypot(aided.bound_m, prediction.bound_m)) return TrackSource::coasting;
  // An unrefined fit's depth is loose (a pixel of disparity is centimetres at a metre): a partial
  // view that moved the spheres away from the prediction is trusted no closer than it moved them.
  aided.bound_m = std::max(aided.bound_m, innovation_m);
  const WorldPose fused = fused_translation(prediction, aided);
  if (rigid) {
    // Fused into the translation as a sound estimate's would be; the rotation stays the
    // prediction's, its bound growing with the attitude's drift.
    track_ = fused;
    track_.at = capture;
    sound_at_ = capture;
    remember(track_);
    return TrackSource::aided;
  }
  // A single sphere, or spheres that do not agree, move the track but vouch for nothing: the
  // bound grows on as the coast's from the last sound estimate (fused as 3 mm points, a bar's
  // shifted centres walked the track 25 mm off over ten frames while it claimed 4.5). Nor do
  // these positions feed the velocity. The corrected position is carried back to the last fused
  // time, where the coast starts from.
  track_.p_w = fused.p_w - velocity_w_ * std::max(0.0, seconds(capture - track_.at));
  return TrackSource::nudged;
}

void PoseTracker::estimate_velocity() {
  // The least-squares slope of the fused positions within the window before the newest; its
  // bound from the positions' bound over the spread of their times, plus what the velocity can
  // have changed within the window.
  const std::chrono::nanoseconds newest = track_.at;
  double n = 0.0, t_sum = 0.0;
  Eigen::Vector3d p_sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < history_size_; ++i) {
    const Sample& s = history_[i];
    const double age_s = seconds(newest - s.at);
    if (age_s < 0.0 || age_s > params_.velocity_window_s) continue;
    n += 1.0;
    t_sum -= age_s;
    p_sum += s.p_w;
  }
  velocity_w_.setZero();
  velocity_bound_mps_ = params_.speed_mps;
  // Two positions leave no scatter to judge their slope by: on a camera shaking on its mount, a
  // new track's first two (four frames apart) gave a velocity that coasted it 58 mm off within
  // two frames while its bound said 7.
  if (n < 3.0) return;
  const double t_mean = t_sum / n;
  const Eigen::Vector3d p_mean = p_sum / n;
  double sxx = 0.0, span_s = 0.0;
  Eigen::Vector3d sxy = Eigen::Vector3d::Zero();
  for (int i = 0; i < history_size_; ++i) {
    const Sample& s = history_[i];
    const double age_s = seconds(newest - s.at);
    if (age_s < 0.0 || age_s > params_.velocity_window_s) continue;
    const double dt = -age_s - t_mean;
    sxx += dt * dt;
    sxy += dt * (s.p_w - p_mean);
    span_s = std::max(span_s, age_s);
  }
  if (sxx <= 0.0) return;
  velocity_w_ = sxy / sxx;
  // The positions' scatter about the fitted line, where it is wider than their bound says (a
  // motion the attitude does not carry, such as a camera shaking on its mount), widens the
  // velocity's bound by as much: 3 sigma of the slope.
  double residual_sq = 0.0;
  for (int i = 0; i < history_size_; ++i) {
    const Sample& s = history_[i];
    const double age_s = seconds(newest - s.at);
    if (age_s < 0.0 || age_s > params_.velocity_window_s) continue;
    residual_sq += (s.p_w - p_mean - velocity_w_ * (-age_s - t_mean)).squaredNorm();
  }
  const double scatter_m = 3.0 * std::sqrt(residual_sq / (n - 2.0));
  const double bound =
      std::max(track_.bound_m, scatter_m) / std::sqrt(sxx) + 0.5 * params_.accel_mps2 * span_s;
  velocity_bound_mps_ = std::min(params_.speed_mps, bound);
  if (velocity_w_.norm() > params_.speed_mps) velocity_w_ *= params_.speed_mps / velocity_w_.norm();
}

void PoseTracker::start(const WorldPose& first, const WorldPose& second) {
  history_size_ = 0;
  history_next_ = 0;
  velocity_w_.setZero();
  velocity_bound_mps_ = params_.speed_mps;
  track_ = first;
  history_[history_next_++] = Sample{first.at, first.p_w};
  history_size_ = 1;
  have_track_ = true;
  fuse(predicted(second.at, true), second);
}

TrackedPose PoseTracker::output(const WorldPose& pose, const Eigen::Matrix3d& R_world_cl,
                                TrackSource source, std::chrono::nanoseconds capture) const {
  TrackedPose out;
  out.source = source;
  out.T_cl_marker.linear() = R_world_cl.transpose() * pose.R_world_marker;
  out.T_cl_marker.translation() = R_world_cl.transpose() * pose.p_w;
  out.bound_m = pose.bound_m;
  out.bound_deg = pose.bound_deg;
  out.age = capture - sound_at_;
  out.ok = source != TrackSource::none && seconds(out.age) <= params_.max_coast_s &&
           out.bound_m <= ok_bound_m_ && out.bound_deg <= ok_bound_deg_;
  return out;
}

TrackedPose PoseTracker::predict(std::chrono::nanoseconds capture,
                                 const Eigen::Quaterniond& q_world_body,
                                 bool attitude_valid) const {
  if (!have_track_) return TrackedPose{};
  return output(predicted(capture, attitude_valid), R_world_cl(q_world_body, attitude_valid),
                TrackSource::coasting, capture);
}

const TrackedPose& PoseTracker::update(std::chrono::nanoseconds capture,
                                       const Eigen::Quaterniond& q_world_body, bool attitude_valid,
                                       const PoseMeasurement& measurement) {
  const Eigen::Matrix3d R = R_world_cl(q_world_body, attitude_valid);
  if (attitude_valid) last_R_world_cl_ = R;
  // A track not fused for longer than it may coast has nothing left to gate with.
  if (have_track_ && seconds(capture - sound_at_) > params_.max_coast_s) have_track_ = false;
  if (have_candidate_ && seconds(capture - candidate_.at) > params_.max_coast_s) {
    have_candidate_ = false;
  }
  bool rejected = false;
  TrackSource source = have_track_ ? TrackSource::coasting : TrackSource::none;
  const bool sound = measurement.sound && measurement.T_cl_marker.matrix().allFinite() &&
                     std::isfinite(measurement.bound_m) && std::isfinite(measurement.bound_deg);
  if (sound) {
    const WorldPose m = to_world(measurement, R, capture);
    WorldPose candidate = candidate_;
    if (have_candidate_) {
      // The candidate may have moved as far as the vehicle can since (it has no velocity).
      const double dt_s = std::max(0.0, seconds(capture - candidate_.at));
      candidate.bound_m += params_.speed_mps * dt_s;
      candidate.bound_deg += params_.attitude_drift_dps * dt_s;
    }
    if (have_track_) observe_innovation(predicted(capture, attitude_valid, false), m);
    const WorldPose prediction = have_track_ ? predicted(capture, attitude_valid) : WorldPose{};
    if (have_track_ && agree(prediction, m)) {
      fuse(prediction, m);
      have_candidate_ = false;
      source = TrackSource::fused;
    } else if (have_candidate_ && agree(candidate, m)) {
      start(candidate_, m);  // two in a row agree: the new track replaces any old one
      have_candidate_ = false;
      source = TrackSource::fused;
    } else {
      rejected = have_track_;
      candidate_ = m;
      have_candidate_ = true;
    }
  } else if (have_track_) {
    source = aid(predicted(capture, attitude_valid), measurement, R, capture);
  }
  out_ = have_track_ ? output(source == TrackSource::fused || source == TrackSource::aided
                                  ? track_
                                  : predicted(capture, attitude_valid),
                              R, source, capture)
                     : TrackedPose{};
  // A sound estimate that disagrees with the track says one of them is wrong: neither is ok until
  // the next frame confirms one. (A camera on a mount that shook 1.5 deg at 8 Hz, unseen by the
  // attitude sensor, had the coast claim ok 113 mm off while each estimate disagreed with it.)
  out_.rejected = rejected;
  if (rejected) out_.ok = false;
  return out_;
}

}  // namespace rovctl::control
