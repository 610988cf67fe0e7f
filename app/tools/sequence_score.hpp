// Rendered docking-approach sequences (tests/estimator/water_set/render_sequence.py's recordings
// with per-frame truth) and two arms scored on them frame by frame, as the loop would run them:
// the still estimator with its frame-to-frame confirmation, and the same followed by the pose
// tracker fed the camera's true attitude.
#pragma once

#include <Eigen/Geometry>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "control/pose_tracker.hpp"
#include "estimator/estimator_params.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct SequenceFrame {
  std::uint64_t frame = 0;  // the 30 Hz trajectory's frame index (frames.csv's sequence)
  std::chrono::nanoseconds stamp{0};
  std::string left_png, right_png;  // full paths
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  Eigen::Quaterniond q_world_cam = Eigen::Quaterniond::Identity();
  bool hidden_sphere = false;  // a sphere wholly hidden in both views
  int bubbles_on_sight_lines = 0;
};

struct RenderedSequence {
  std::string name, kind;
  std::vector<SequenceFrame> frames;  // frames.csv's rows, in its order
};

// DIR holding sequences.json (every sequence it lists), or one sequence folder (sequence.json and
// frames.csv). Frames the truth lists but frames.csv does not (a render stopped early) are left
// out. Throws std::invalid_argument naming the file and what is wrong.
std::vector<RenderedSequence> load_sequences(const std::string& dir);

// One arm's frames: ok and right (within kRightTranslationMm and kRightRotationDeg), ok but
// wrong, not ok.
struct ArmCount {
  int frames = 0, right = 0, wrong = 0, not_ok = 0;
  void add(bool ok, bool right_pose);
};

struct SequenceScoreRow {
  std::string label;  // a sequence's name, a kind, "hidden-sphere frames", "bubble frames", "all"
  ArmCount still, tracked;
};

struct FrameScore {
  const RenderedSequence* sequence = nullptr;
  const SequenceFrame* frame = nullptr;
  bool still_ok = false, still_right = false;
  bool tracked_ok = false, tracked_right = false;
  control::TrackSource source = control::TrackSource::none;
  double still_mm = 0.0, still_deg = 0.0;              // the estimate's error
  double still_bound_mm = 0.0, still_bound_deg = 0.0;  // and its bound (NaN: none)
  double tracked_mm = 0.0, tracked_deg = 0.0;          // the tracked pose's error
  double bound_mm = 0.0, bound_deg = 0.0;              // the tracked pose's bound
};

struct SequenceScores {
  std::vector<SequenceScoreRow> by_sequence, by_kind, by_event;  // by_event ends with "all"
  std::vector<FrameScore> frames;
};

// Each sequence from a fresh estimator (seeded from its name and `seed`), `updates_per_frame`
// estimator updates per recorded pair. The tracker is built with T_body_cl identity and fed the
// truth's q_world_cam as the vehicle's attitude.
SequenceScores score_sequences(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                               const estimator::EstimatorParams& params,
                               const control::PoseTrackerParams& tracker,
                               const std::vector<RenderedSequence>& sequences,
                               int updates_per_frame, std::uint64_t seed);

}  // namespace rovctl::app
