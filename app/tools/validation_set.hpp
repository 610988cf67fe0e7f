// An independent validation set (stereo pairs rendered outside rovctl, with ground truth and a
// condition per pair: clear, turbid, side light, ...) and the estimator's score on it, per
// condition. The set's format is tests/estimator/water_set/README.md's manifest.json.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "estimator/estimator_params.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct ValidationPair {
  std::string condition;
  std::string name;                 // the manifest's "left" entry: the pair's identity in any set
  std::string left_png, right_png;  // full paths
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  // Visible fraction of each sphere per view, as the generator estimated it (1 = whole).
  std::map<std::string, double> visible_left, visible_right;
  // Every number among the entry's own fields (range_m, jpeg_quality, motion_blur_px, ...): what a
  // condition varies from pair to pair, for splitting its score.
  std::map<std::string, double> numbers;
};

// Reads DIR/manifest.json. Throws std::invalid_argument naming the file and the entry.
std::vector<ValidationPair> load_validation_set(const std::string& dir);

// An image of a set, its size checked against the calibration's from the file's header before it
// is decoded. Throws std::invalid_argument naming the file.
cv::Mat read_set_image(const std::string& path, const hal::CameraModel& camera);

// The estimator's seed for the pair or sequence `name` under the run's `seed`: the same on every
// platform, so a pair scores the same wherever it runs.
std::uint64_t estimator_seed(const std::string& name, std::uint64_t seed);

// An estimate's error against the truth: position in mm, rotation in deg.
void pose_errors(const Eigen::Isometry3d& T, const Eigen::Isometry3d& truth, double& mm,
                 double& deg);

// Right means within these of the truth (the bounds).
constexpr double kRightTranslationMm = 10.0;
constexpr double kRightRotationDeg = 5.0;

struct ConditionScore {
  std::string condition;
  // The marker's true range from the left camera that the row covers: [from, to), m.
  double range_from_m = 0.0;
  double range_to_m = std::numeric_limits<double>::infinity();
  int pairs = 0;
  int ok = 0;        // the estimator said ok
  int success = 0;   // said ok and was right
  int false_ok = 0;  // said ok and was wrong: the failure that matters
  int partial = 0;   // recognised but not ok (approach only): the three below together
  int partial_view = 0, not_refined = 0, bound_over_limit = 0;  // by the first test it failed
  // Over the pairs reported ok (what the vehicle would act on); NaN when none.
  double translation_mm_median = 0.0, translation_mm_p95 = 0.0;
  double rotation_deg_median = 0.0, rotation_deg_p95 = 0.0;
  // Over every pair, ok or not: how far off the best pose was.
  double translation_mm_median_all = 0.0;
  double ms_per_frame_p95 = 0.0;  // NaN in a range row: the time is the condition's
  // Over the pairs reported ok with a bound (improved mode gives one): each error against the
  // bound the estimator gave with it. A true bound keeps every ratio at or below 1; `bound_held`
  // counts the pairs where both did. The ratios are NaN when no ok pair had a bound.
  int bounded = 0, bound_held = 0;
  double rotation_bound_ratio_p99 = 0.0, rotation_bound_ratio_max = 0.0;
  double translation_bound_ratio_p99 = 0.0, translation_bound_ratio_max = 0.0;
};

struct PairResult {
  const ValidationPair* pair = nullptr;
  double range_m = 0.0;  // the truth's, from the left camera
  bool ok = false;
  bool partial = false;  // recognised but not ok
  estimator::NotOkReason not_ok_reason = estimator::NotOkReason::none;
  double translation_mm = 0.0, rotation_deg = 0.0;
  double fitness = 0.0;
  int spheres_seen_left = 0, spheres_seen_right = 0;
  std::array<std::array<double, 3>, 2> sphere_scores{};
  std::array<std::array<double, 3>, 2> sphere_ring_hits{};
  bool rim_refined = false;
  bool mirror_fits = false;  // the images fit the other tilt too: the bound reaches to it
  std::array<std::array<double, 3>, 2> rim_support{};
  double error_bound_mm = 0.0, error_bound_deg = 0.0;
};

// Runs a fresh estimator over each pair for `frames` frames (a still camera) and scores the last
// estimate. Each pair's GA is seeded from its name and `seed`, so a pair scores the same in any
// set that holds it (a subset, a resumed render, another order), and another `seed` shows how much
// a score owes to the GA's draw. One row per condition in the set's order, then "all".
std::vector<ConditionScore> score_validation_set(const hal::StereoRig& rig,
                                                 const hal::MarkerModel& marker,
                                                 const estimator::EstimatorParams& params,
                                                 const std::vector<ValidationPair>& pairs,
                                                 int frames, std::vector<PairResult>* details,
                                                 std::uint64_t seed = 0);

// The same scores split by the marker's true range at `edges_m` (ascending, > 0): where in each
// condition the estimator gives up. One row per condition and non-empty band, in the set's order.
std::vector<ConditionScore> score_by_range(const std::vector<PairResult>& details,
                                           const std::vector<double>& edges_m);

// A condition's score over the pairs whose manifest number `field` lies in [from, to).
struct FieldBandScore {
  std::string field;
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
  ConditionScore score;
};

// The same scores split by one of the pairs' manifest numbers at `edges` (ascending): how a
// condition's score falls with what it varies (jpeg_quality, motion_blur_diameters, ...). Pairs
// without the field are left out. One row per condition and non-empty band, in the set's order.
// Throws std::invalid_argument when the edges are not ascending or no pair has the field.
std::vector<FieldBandScore> score_by_field(const std::vector<PairResult>& details,
                                           const std::string& field,
                                           const std::vector<double>& edges);

}  // namespace rovctl::app
