// Loading a validation set's manifest (JSON, read with yaml-cpp: JSON is YAML) and scoring the
// estimator on it the way a vehicle would use it: what it said was ok, and whether it was right.
#include "app/tools/validation_set.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <stdexcept>

#include "estimator/pose_estimator.hpp"
#include "hal/primitives/image_header.hpp"
#include "hal/primitives/percentile.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& file, std::size_t index, const std::string& what) {
  throw std::invalid_argument(file + ": pairs[" + std::to_string(index) + "]: " + what);
}

std::map<std::string, double> visible(const YAML::Node& node) {
  std::map<std::string, double> out;
  if (!node || !node.IsMap()) return out;
  for (const auto& kv : node) out[kv.first.as<std::string>()] = kv.second.as<double>();
  return out;
}

ConditionScore summarise(const std::string& condition, const std::vector<PairResult>& results,
                         const std::vector<double>& ms) {
  ConditionScore s;
  s.condition = condition;
  std::vector<double> t_ok, r_ok, t_all, r_ratio, t_ratio;
  for (const PairResult& r : results) {
    ++s.pairs;
    t_all.push_back(r.translation_mm);
    if (r.partial) ++s.partial;
    switch (r.not_ok_reason) {
      case estimator::NotOkReason::partial_view:
        ++s.partial_view;
        break;
      case estimator::NotOkReason::not_refined:
        ++s.not_refined;
        break;
      case estimator::NotOkReason::bound_over_limit:
        ++s.bound_over_limit;
        break;
      case estimator::NotOkReason::unconfirmed:  // a loop's test: a pair alone never fails it
      case estimator::NotOkReason::none:
        break;
    }
    if (!r.ok) continue;
    ++s.ok;
    t_ok.push_back(r.translation_mm);
    r_ok.push_back(r.rotation_deg);
    if (std::isfinite(r.error_bound_deg) && std::isfinite(r.error_bound_mm)) {
      ++s.bounded;
      r_ratio.push_back(r.rotation_deg / r.error_bound_deg);
      t_ratio.push_back(r.translation_mm / r.error_bound_mm);
      if (r.rotation_deg <= r.error_bound_deg && r.translation_mm <= r.error_bound_mm) {
        ++s.bound_held;
      }
    }
    const bool right = r.translation_mm < kRightTranslationMm && r.rotation_deg < kRightRotationDeg;
    if (right) {
      ++s.success;
    } else {
      ++s.false_ok;
    }
  }
  s.translation_mm_median = hal::percentile(t_ok, 0.5);
  s.translation_mm_p95 = hal::percentile(t_ok, 0.95);
  s.rotation_deg_median = hal::percentile(r_ok, 0.5);
  s.rotation_deg_p95 = hal::percentile(r_ok, 0.95);
  s.translation_mm_median_all = hal::percentile(t_all, 0.5);
  s.ms_per_frame_p95 = hal::percentile(ms, 0.95);
  s.rotation_bound_ratio_p99 = hal::percentile(r_ratio, 0.99);
  s.rotation_bound_ratio_max = hal::percentile(r_ratio, 1.0);
  s.translation_bound_ratio_p99 = hal::percentile(t_ratio, 0.99);
  s.translation_bound_ratio_max = hal::percentile(t_ratio, 1.0);
  return s;
}

// The conditions as the set first names them: the order of every table the tool prints.
std::vector<std::string> conditions_in_set_order(const std::vector<PairResult>& results) {
  std::vector<std::string> order;
  for (const PairResult& r : results) {
    if (std::find(order.begin(), order.end(), r.pair->condition) == order.end()) {
      order.push_back(r.pair->condition);
    }
  }
  return order;
}

// Each condition's pairs split at `edges` by `value_of` (pairs without a value left out), the
// lowest band starting at `lowest`. `what` names the edges in the error.
std::vector<FieldBandScore> score_by_band(
    const std::vector<PairResult>& details, const std::vector<double>& edges, double lowest,
    const std::string& what,
    const std::function<std::optional<double>(const PairResult&)>& value_of) {
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (!std::isfinite(edges[i]) || !(edges[i] > lowest) || (i > 0 && !(edges[i] > edges[i - 1]))) {
      throw std::invalid_argument(what + " must be finite and ascending");
    }
  }
  std::vector<FieldBandScore> rows;
  for (const std::string& c : conditions_in_set_order(details)) {
    for (std::size_t band = 0; band <= edges.size(); ++band) {
      FieldBandScore row;
      row.from = band == 0 ? lowest : edges[band - 1];
      row.to = band == edges.size() ? std::numeric_limits<double>::infinity() : edges[band];
      std::vector<PairResult> in_band;
      for (const PairResult& r : details) {
        const std::optional<double> v = value_of(r);
        if (r.pair->condition == c && v && *v >= row.from && *v < row.to) in_band.push_back(r);
      }
      if (in_band.empty()) continue;
      row.score = summarise(c, in_band, {});
      rows.push_back(row);
    }
  }
  return rows;
}

}  // namespace

cv::Mat read_set_image(const std::string& path, const hal::CameraModel& camera) {
  // The size from the header, before decoding: a small file can declare a huge image.
  const std::string problem =
      hal::check_image_file(path, camera.width_px, camera.height_px, "the calibration");
  if (!problem.empty()) throw std::invalid_argument(problem);
  cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) throw std::invalid_argument(path + ": cannot read image");
  return image;
}

std::uint64_t estimator_seed(const std::string& name, std::uint64_t seed) {
  // FNV-1a: fixed across platforms and standard libraries, unlike std::hash.
  std::uint64_t h = 14695981039346656037ull;
  const auto mix = [&h](unsigned char c) {
    h ^= c;
    h *= 1099511628211ull;
  };
  for (const unsigned char c : name) mix(c);
  for (int byte = 0; byte < 8; ++byte) mix(static_cast<unsigned char>(seed >> (8 * byte)));
  return h;
}

void pose_errors(const Eigen::Isometry3d& T, const Eigen::Isometry3d& truth, double& mm,
                 double& deg) {
  mm = (T.translation() - truth.translation()).norm() * 1000.0;
  deg = Eigen::AngleAxisd(T.linear().transpose() * truth.linear()).angle() * 180.0 / M_PI;
}

std::vector<ValidationPair> load_validation_set(const std::string& dir) {
  const std::string file = (fs::path(dir) / "manifest.json").string();
  if (!fs::is_regular_file(file)) throw std::invalid_argument(file + ": no such file");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  const YAML::Node list = root["pairs"];
  if (!list || !list.IsSequence() || list.size() == 0) {
    throw std::invalid_argument(file + ": 'pairs' must be a non-empty list");
  }
  std::vector<ValidationPair> pairs;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node p = list[i];
    try {
      ValidationPair v;
      v.condition = p["condition"].as<std::string>();
      v.name = p["left"].as<std::string>();
      v.left_png = (fs::path(dir) / v.name).string();
      v.right_png = (fs::path(dir) / p["right"].as<std::string>()).string();
      const auto t = p["t_cl_marker_m"].as<std::vector<double>>();
      const auto q = p["q_cl_marker_wxyz"].as<std::vector<double>>();
      if (t.size() != 3 || q.size() != 4) fail(file, i, "t_cl_marker_m needs 3 and q 4 numbers");
      const Eigen::Quaterniond rotation(q[0], q[1], q[2], q[3]);
      if (std::abs(rotation.norm() - 1.0) > 1e-3) fail(file, i, "q_cl_marker_wxyz is not unit");
      v.T_cl_marker.linear() = rotation.normalized().toRotationMatrix();
      v.T_cl_marker.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
      v.visible_left = visible(p["spheres_visible_left"]);
      v.visible_right = visible(p["spheres_visible_right"]);
      for (const auto& kv : p) {
        double value = 0.0;
        if (kv.second.IsScalar() && YAML::convert<double>::decode(kv.second, value) &&
            std::isfinite(value)) {
          v.numbers[kv.first.as<std::string>()] = value;
        }
      }
      pairs.push_back(std::move(v));
    } catch (const YAML::Exception& e) {
      fail(file, i, std::string("missing or malformed field (") + e.msg + ")");
    }
  }
  return pairs;
}

std::vector<ConditionScore> score_validation_set(const hal::StereoRig& rig,
                                                 const hal::MarkerModel& marker,
                                                 const estimator::EstimatorParams& params,
                                                 const std::vector<ValidationPair>& pairs,
                                                 int frames, std::vector<PairResult>* details,
                                                 std::uint64_t seed) {
  std::map<std::string, std::vector<PairResult>> by_condition;
  std::map<std::string, std::vector<double>> ms_by_condition;
  std::vector<PairResult> all;
  std::vector<double> all_ms;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const ValidationPair& pair = pairs[i];
    const cv::Mat left = read_set_image(pair.left_png, rig.left);
    const cv::Mat right = read_set_image(pair.right_png, rig.right);
    estimator::PoseEstimator estimator(rig, marker, params, estimator_seed(pair.name, seed));
    estimator::PoseEstimate e;
    for (int f = 0; f < frames; ++f) {
      e = estimator.update(left, right);
      if (e.input_error != nullptr) {
        throw std::invalid_argument(pair.left_png + ": " + e.input_error);
      }
      const double ms = std::chrono::duration<double, std::milli>(e.compute_time).count();
      ms_by_condition[pair.condition].push_back(ms);
      all_ms.push_back(ms);
    }
    PairResult r;
    r.pair = &pair;
    r.range_m = pair.T_cl_marker.translation().norm();
    r.ok = e.ok;
    r.partial = !e.ok && e.recognised;
    r.not_ok_reason = e.not_ok_reason;
    r.fitness = e.fitness;
    r.spheres_seen_left = e.spheres_seen[0];
    r.spheres_seen_right = e.spheres_seen[1];
    r.sphere_scores = e.sphere_scores;
    r.sphere_ring_hits = e.sphere_ring_hits;
    r.rim_refined = e.rim_refined;
    r.mirror_fits = e.mirror_fits;
    r.rim_support = e.rim_support;
    r.error_bound_mm = 1000.0 * e.error_bound_m;
    r.error_bound_deg = e.error_bound_deg;
    pose_errors(e.T_cl_marker, pair.T_cl_marker, r.translation_mm, r.rotation_deg);
    by_condition[pair.condition].push_back(r);
    all.push_back(r);
    if (details != nullptr) details->push_back(r);
  }
  std::vector<ConditionScore> scores;
  for (const std::string& c : conditions_in_set_order(all))
    scores.push_back(summarise(c, by_condition[c], ms_by_condition[c]));
  scores.push_back(summarise("all", all, all_ms));
  return scores;
}

std::vector<ConditionScore> score_by_range(const std::vector<PairResult>& details,
                                           const std::vector<double>& edges_m) {
  if (!edges_m.empty() && !(edges_m.front() > 0.0)) {
    throw std::invalid_argument("range edges must be positive and ascending");
  }
  std::vector<ConditionScore> rows;
  for (const FieldBandScore& band :
       score_by_band(details, edges_m, 0.0, "range edges",
                     [](const PairResult& r) { return std::optional<double>(r.range_m); })) {
    ConditionScore s = band.score;
    s.range_from_m = band.from;
    s.range_to_m = band.to;
    rows.push_back(s);
  }
  return rows;
}

std::vector<FieldBandScore> score_by_field(const std::vector<PairResult>& details,
                                           const std::string& field,
                                           const std::vector<double>& edges) {
  const auto value = [&field](const PairResult& r) -> std::optional<double> {
    const auto it = r.pair->numbers.find(field);
    if (it == r.pair->numbers.end()) return std::nullopt;
    return it->second;
  };
  if (std::none_of(details.begin(), details.end(),
                   [&value](const PairResult& r) { return value(r).has_value(); })) {
    throw std::invalid_argument("no pair of the set has a number '" + field + "'");
  }
  std::vector<FieldBandScore> rows = score_by_band(
      details, edges, -std::numeric_limits<double>::infinity(), field + " edges", value);
  for (FieldBandScore& row : rows) row.field = field;
  return rows;
}

}  // namespace rovctl::app
