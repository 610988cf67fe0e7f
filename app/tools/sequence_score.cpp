// Loading rendered sequences (sequences.json, sequence.json, frames.csv; JSON read with yaml-cpp)
// and scoring the still and the tracked arm on them frame by frame.
#include "app/tools/sequence_score.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "app/runtime/pose_measurement.hpp"
#include "app/tools/validation_set.hpp"
#include "drivers/replay/recording_format.hpp"
#include "estimator/pose_confirmation.hpp"
#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw std::invalid_argument(file + ": " + what);
}

YAML::Node load_json(const std::string& file) {
  if (!fs::is_regular_file(file)) fail(file, "missing");
  try {
    return YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    fail(file, std::string("not JSON: ") + e.what());
  }
}

Eigen::Quaterniond quaternion(const YAML::Node& wxyz, const std::string& where) {
  if (!wxyz || !wxyz.IsSequence() || wxyz.size() != 4) throw std::invalid_argument(where);
  const Eigen::Quaterniond q(wxyz[0].as<double>(), wxyz[1].as<double>(), wxyz[2].as<double>(),
                             wxyz[3].as<double>());
  if (!q.coeffs().allFinite() || q.norm() < 0.5) throw std::invalid_argument(where);
  return q.normalized();
}

SequenceFrame truth_of(const YAML::Node& f, const std::string& where) {
  SequenceFrame out;
  const YAML::Node t = f["t_cl_marker_m"];
  if (!t || !t.IsSequence() || t.size() != 3) {
    throw std::invalid_argument(where + ": no t_cl_marker_m [x, y, z]");
  }
  out.T_cl_marker.translation() =
      Eigen::Vector3d(t[0].as<double>(), t[1].as<double>(), t[2].as<double>());
  out.T_cl_marker.linear() =
      quaternion(f["q_cl_marker_wxyz"], where + ": no q_cl_marker_wxyz [w, x, y, z]")
          .toRotationMatrix();
  out.q_world_cam = quaternion(f["q_world_cam_wxyz"], where + ": no q_world_cam_wxyz [w, x, y, z]");
  out.hidden_sphere = f["hidden_sphere"] && !f["hidden_sphere"].IsNull();
  out.bubbles_on_sight_lines =
      f["bubbles_on_sight_lines"] ? f["bubbles_on_sight_lines"].as<int>() : 0;
  return out;
}

RenderedSequence load_sequence(const std::string& folder, const std::string& name) {
  const std::string file = (fs::path(folder) / "sequence.json").string();
  const YAML::Node doc = load_json(file);
  RenderedSequence seq;
  seq.name = name;
  std::map<std::string, SequenceFrame> truth;  // by the left image's file
  try {
    seq.kind = doc["kind"].as<std::string>();
    const YAML::Node frames = doc["frames"];
    if (!frames || !frames.IsSequence()) fail(file, "no \"frames\" list");
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const std::string where = file + ": frames[" + std::to_string(i) + "]";
      truth[frames[i]["left"].as<std::string>()] = truth_of(frames[i], where);
    }
  } catch (const YAML::Exception& e) {
    fail(file, e.what());
  }
  std::vector<drivers::RecordedFrame> rows;
  std::string error;
  if (!drivers::read_frames_csv(folder, rows, error)) throw std::invalid_argument(error);
  for (const drivers::RecordedFrame& row : rows) {
    const auto it = truth.find(row.left_file);
    if (it == truth.end()) {
      fail(file, "no truth for frames.csv's " + row.left_file);
    }
    SequenceFrame f = it->second;
    f.frame = row.sequence;
    f.stamp = row.left_stamp;
    f.left_png = (fs::path(folder) / row.left_file).string();
    f.right_png = (fs::path(folder) / row.right_file).string();
    seq.frames.push_back(f);
  }
  return seq;
}

bool right(double mm, double deg) { return mm <= kRightTranslationMm && deg <= kRightRotationDeg; }

SequenceScoreRow& row_of(std::vector<SequenceScoreRow>& rows, const std::string& label) {
  for (SequenceScoreRow& r : rows) {
    if (r.label == label) return r;
  }
  rows.push_back(SequenceScoreRow{label, {}, {}});
  return rows.back();
}

void score_one(const hal::StereoRig& rig, const hal::MarkerModel& marker,
               const estimator::EstimatorParams& params,
               const control::PoseTrackerParams& tracker_params, const RenderedSequence& seq,
               int updates_per_frame, std::uint64_t seed, std::vector<FrameScore>& out) {
  // Two estimators from one seed: the still arm looks at every frame as far as it can; the
  // tracked arm looks as the loop does with the tracker on (Looks::as_needed).
  estimator::PoseEstimator still(rig, marker, params, estimator_seed(seq.name, seed));
  estimator::PoseEstimator looked(rig, marker, params, estimator_seed(seq.name, seed));
  estimator::PoseConfirmation still_confirmation(params.confirm);
  estimator::PoseConfirmation looked_confirmation(params.confirm);
  control::PoseTracker tracker(tracker_params, Eigen::Isometry3d::Identity(),
                               params.ok_bound_mm / 1000.0, params.ok_bound_deg);
  for (const SequenceFrame& f : seq.frames) {
    const cv::Mat left = read_set_image(f.left_png, rig.left);
    const cv::Mat right_image = read_set_image(f.right_png, rig.right);
    estimator::PoseEstimate e, seen;
    for (int u = 0; u < updates_per_frame; ++u) {
      e = still.update(left, right_image);
      if (e.input_error != nullptr) fail(f.left_png, e.input_error);
      seen = looked.update(left, right_image, estimator::Looks::as_needed);
    }
    if (params.improved()) {
      still_confirmation.judge(e, f.stamp);
      looked_confirmation.judge(seen, f.stamp);
    }
    const control::PoseMeasurement m = pose_measurement(seen, marker, params.rim_support);
    const control::TrackedPose& t = tracker.update(f.stamp, f.q_world_cam, true, m);
    FrameScore s;
    s.sequence = &seq;
    s.frame = &f;
    pose_errors(e.T_cl_marker, f.T_cl_marker, s.still_mm, s.still_deg);
    pose_errors(t.T_cl_marker, f.T_cl_marker, s.tracked_mm, s.tracked_deg);
    s.still_ok = e.ok;
    s.still_bound_mm = e.error_bound_m * 1000.0;
    s.still_bound_deg = e.error_bound_deg;
    s.still_right = right(s.still_mm, s.still_deg);
    s.tracked_ok = t.ok;
    s.tracked_right = right(s.tracked_mm, s.tracked_deg);
    s.source = t.source;
    s.bound_mm = t.bound_m * 1000.0;
    s.bound_deg = t.bound_deg;
    out.push_back(s);
  }
}

}  // namespace

void ArmCount::add(bool ok, bool right_pose) {
  ++frames;
  if (!ok) {
    ++not_ok;
  } else if (right_pose) {
    ++right;
  } else {
    ++wrong;
  }
}

std::vector<RenderedSequence> load_sequences(const std::string& dir) {
  if (!fs::is_directory(dir)) fail(dir, "not a folder");
  const std::string index = (fs::path(dir) / "sequences.json").string();
  if (!fs::exists(index)) {
    return {load_sequence(dir, fs::path(dir).lexically_normal().filename().string())};
  }
  const YAML::Node doc = load_json(index);
  std::vector<RenderedSequence> out;
  try {
    const YAML::Node list = doc["sequences"];
    if (!list || !list.IsSequence()) fail(index, "no \"sequences\" list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string name = list[i]["name"].as<std::string>();
      out.push_back(
          load_sequence((fs::path(dir) / list[i]["path"].as<std::string>()).string(), name));
    }
  } catch (const YAML::Exception& e) {
    fail(index, e.what());
  }
  if (out.empty()) fail(index, "lists no sequence");
  return out;
}

SequenceScores score_sequences(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                               const estimator::EstimatorParams& params,
                               const control::PoseTrackerParams& tracker,
                               const std::vector<RenderedSequence>& sequences,
                               int updates_per_frame, std::uint64_t seed) {
  SequenceScores scores;
  for (const RenderedSequence& seq : sequences) {
    score_one(rig, marker, params, tracker, seq, updates_per_frame, seed, scores.frames);
  }
  const auto add = [](std::vector<SequenceScoreRow>& rows, const std::string& label,
                      const FrameScore& s) {
    SequenceScoreRow& r = row_of(rows, label);
    r.still.add(s.still_ok, s.still_right);
    r.tracked.add(s.tracked_ok, s.tracked_right);
  };
  for (const FrameScore& s : scores.frames) {
    add(scores.by_sequence, s.sequence->name, s);
    add(scores.by_kind, s.sequence->kind, s);
    if (s.frame->hidden_sphere) add(scores.by_event, "hidden-sphere frames", s);
    if (s.frame->bubbles_on_sight_lines > 0) add(scores.by_event, "bubble frames", s);
  }
  SequenceScoreRow all{"all", {}, {}};
  for (const SequenceScoreRow& r : scores.by_kind) {
    for (auto [from, to] : {std::pair{&r.still, &all.still}, std::pair{&r.tracked, &all.tracked}}) {
      to->frames += from->frames;
      to->right += from->right;
      to->wrong += from->wrong;
      to->not_ok += from->not_ok;
    }
  }
  scores.by_event.push_back(all);
  return scores;
}

}  // namespace rovctl::app
