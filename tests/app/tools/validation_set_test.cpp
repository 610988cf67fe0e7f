// The estimator on the committed sample of the independent (POV-Ray) validation set: it may
// refuse a hard pair, but what it calls ok must be right. And a broken manifest is named.
#include "app/tools/validation_set.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

const std::string kSample = std::string(ROVCTL_TEST_DATA_DIR) + "/water_set";

TEST(ValidationSet, SampleLoadsWithEveryCondition) {
  const std::vector<ValidationPair> pairs = load_validation_set(kSample);
  std::set<std::string> conditions;
  for (const ValidationPair& p : pairs) {
    conditions.insert(p.condition);
    EXPECT_TRUE(fs::is_regular_file(p.left_png)) << p.left_png;
    EXPECT_TRUE(fs::is_regular_file(p.right_png)) << p.right_png;
    EXPECT_GT(p.T_cl_marker.translation().z(), 0.2);
  }
  for (const char* c : {"clear", "turbid_near", "turbid_far", "side_light", "bubbles", "occlusion",
                        "edge", "noise_jpeg", "distortion", "overexposed", "underexposed",
                        "motion_blur", "noise_yuyv", "noise_mjpg90"}) {
    EXPECT_EQ(conditions.count(c), 1u) << c;
  }
}

TEST(ValidationSet, WhatTheEstimatorCallsOkIsRight) {
  const AppConfig config = load_app_config(default_config_path());
  const hal::StereoRig rig = load_rig(config);
  const std::vector<ValidationPair> pairs = load_validation_set(kSample);
  std::vector<PairResult> details;
  const std::vector<ConditionScore> scores =
      score_validation_set(rig, config.marker, config.estimator, pairs, 10, &details);
  for (const PairResult& r : details) {
    if (r.ok) {
      EXPECT_LT(r.translation_mm, kRightTranslationMm) << r.pair->left_png;
      EXPECT_LT(r.rotation_deg, kRightRotationDeg) << r.pair->left_png;
    }
  }
  for (const ConditionScore& s : scores) {
    EXPECT_EQ(s.false_ok, 0) << s.condition;
    if (s.condition == "clear" || s.condition == "distortion") {
      EXPECT_EQ(s.success, s.pairs) << s.condition;
    }
    if (s.condition == "all") {
      EXPECT_GE(s.success, s.pairs / 2) << "fewer than half of the sample located";
    }
  }
}

TEST(ValidationSet, APairScoresTheSameInAnySetThatHoldsIt) {
  const AppConfig config = load_app_config(default_config_path());
  const hal::StereoRig rig = load_rig(config);
  const std::vector<ValidationPair> sample = load_validation_set(kSample);
  ASSERT_GE(sample.size(), 3u);
  const std::vector<ValidationPair> three(sample.begin(), sample.begin() + 3);
  const std::vector<ValidationPair> alone = {three[2]};
  std::vector<PairResult> in_three, by_itself;
  score_validation_set(rig, config.marker, config.estimator, three, 3, &in_three);
  score_validation_set(rig, config.marker, config.estimator, alone, 3, &by_itself);
  ASSERT_EQ(in_three.size(), 3u);
  ASSERT_EQ(by_itself.size(), 1u);
  EXPECT_EQ(in_three[2].pair->name, by_itself[0].pair->name);
  // Seeded by its name, not its place: the same GA, the same estimate to the bit.
  EXPECT_EQ(in_three[2].translation_mm, by_itself[0].translation_mm);
  EXPECT_EQ(in_three[2].rotation_deg, by_itself[0].rotation_deg);
  EXPECT_EQ(in_three[2].ok, by_itself[0].ok);
}

PairResult result_at(const ValidationPair& pair, double range_m, bool ok, double error_mm,
                     estimator::NotOkReason reason = estimator::NotOkReason::partial_view) {
  PairResult r;
  r.pair = &pair;
  r.range_m = range_m;
  r.ok = ok;
  r.partial = !ok;
  r.not_ok_reason = ok ? estimator::NotOkReason::none : reason;
  r.translation_mm = error_mm;
  return r;
}

TEST(ValidationSet, ScoresByRangeSplitEachConditionAtTheEdges) {
  ValidationPair noise, clear;
  noise.condition = "noise_jpeg";
  clear.condition = "clear";
  const std::vector<PairResult> details = {
      result_at(noise, 0.40, true, 1.0),
      result_at(clear, 0.45, true, 0.5),
      result_at(noise, 0.90, true, 12.0),
      result_at(noise, 1.00, false, 3.0),
      result_at(noise, 1.44, false, 6.0, estimator::NotOkReason::bound_over_limit),
      result_at(noise, 1.46, true, 2.0),
  };
  const std::vector<ConditionScore> rows = score_by_range(details, {0.5, 1.0});
  // noise: [0, 0.5) 1 pair; [0.5, 1.0) 1 (a false ok); [1.0, inf) 3 (1.00 is in the upper band).
  // clear: [0, 0.5) only; empty bands give no row.
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].condition, "noise_jpeg");
  EXPECT_EQ(rows[0].range_from_m, 0.0);
  EXPECT_EQ(rows[0].range_to_m, 0.5);
  EXPECT_EQ(rows[0].pairs, 1);
  EXPECT_EQ(rows[0].success, 1);
  EXPECT_EQ(rows[1].pairs, 1);
  EXPECT_EQ(rows[1].false_ok, 1);
  EXPECT_EQ(rows[1].success, 0);
  EXPECT_EQ(rows[2].range_from_m, 1.0);
  EXPECT_TRUE(std::isinf(rows[2].range_to_m));
  EXPECT_EQ(rows[2].pairs, 3);
  EXPECT_EQ(rows[2].success, 1);
  EXPECT_EQ(rows[2].partial, 2);
  // Split by the first test each failed: one partial view, one bound over the line.
  EXPECT_EQ(rows[2].partial_view, 1);
  EXPECT_EQ(rows[2].bound_over_limit, 1);
  EXPECT_EQ(rows[2].not_refined, 0);
  EXPECT_EQ(rows[3].condition, "clear");
  EXPECT_EQ(rows[3].pairs, 1);
  EXPECT_THROW(score_by_range(details, {1.0, 0.5}), std::invalid_argument);
  EXPECT_THROW(score_by_range(details, {0.0}), std::invalid_argument);
}

TEST(ValidationSet, ScoresSetEachErrorAgainstItsBound) {
  ValidationPair noise;
  noise.condition = "noise_jpeg";
  auto bounded = [&noise](double mm, double deg, double bound_mm, double bound_deg) {
    PairResult r = result_at(noise, 0.8, true, mm);
    r.rotation_deg = deg;
    r.error_bound_mm = bound_mm;
    r.error_bound_deg = bound_deg;
    return r;
  };
  PairResult paper = result_at(noise, 0.8, true, 1.0);  // paper mode: ok without a bound
  paper.error_bound_mm = paper.error_bound_deg = std::numeric_limits<double>::quiet_NaN();
  const std::vector<PairResult> details = {
      bounded(1.0, 0.5, 4.0, 2.0),         // 0.25, 0.25: held
      bounded(3.0, 3.0, 6.0, 2.0),         // rotation 1.5 times its bound: not held
      bounded(4.5, 0.2, 3.0, 1.0),         // translation 1.5 times its bound: not held
      result_at(noise, 0.8, false, 20.0),  // not ok: no promise to keep
      paper,
  };
  const std::vector<ConditionScore> rows = score_by_range(details, {});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].ok, 4);
  EXPECT_EQ(rows[0].bounded, 3);
  EXPECT_EQ(rows[0].bound_held, 1);
  EXPECT_DOUBLE_EQ(rows[0].rotation_bound_ratio_max, 1.5);
  EXPECT_DOUBLE_EQ(rows[0].translation_bound_ratio_max, 1.5);
  EXPECT_GT(rows[0].rotation_bound_ratio_p99, 1.4);
  EXPECT_LT(rows[0].rotation_bound_ratio_p99, 1.5);
  const std::vector<ConditionScore> unbounded = score_by_range({paper}, {});
  ASSERT_EQ(unbounded.size(), 1u);
  EXPECT_EQ(unbounded[0].bounded, 0);
  EXPECT_TRUE(std::isnan(unbounded[0].rotation_bound_ratio_max));
}

TEST(ValidationSet, ScoresByFieldSplitOnlyThePairsThatHaveIt) {
  ValidationPair q45, q62, q90, clear;
  q45.condition = q62.condition = q90.condition = "noise_jpeg";
  q45.numbers["jpeg_quality"] = 45;
  q62.numbers["jpeg_quality"] = 62;
  q90.numbers["jpeg_quality"] = 90;
  clear.condition = "clear";
  clear.numbers["range_m"] = 0.8;
  const std::vector<PairResult> details = {
      result_at(q45, 1.2, false, 4.0, estimator::NotOkReason::bound_over_limit),
      result_at(clear, 0.8, true, 0.5),
      result_at(q62, 1.2, true, 2.0),
      result_at(q90, 1.2, true, 11.0),
  };
  const std::vector<FieldBandScore> rows = score_by_field(details, "jpeg_quality", {50, 62});
  // [-inf, 50): q45; [50, 62): empty, no row; [62, inf): q62 (on the edge) and q90. The clear
  // pair has no JPEG quality and is in no row.
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].field, "jpeg_quality");
  EXPECT_TRUE(std::isinf(rows[0].from) && rows[0].from < 0);
  EXPECT_EQ(rows[0].to, 50);
  EXPECT_EQ(rows[0].score.condition, "noise_jpeg");
  EXPECT_EQ(rows[0].score.pairs, 1);
  EXPECT_EQ(rows[0].score.bound_over_limit, 1);
  EXPECT_EQ(rows[1].from, 62);
  EXPECT_TRUE(std::isinf(rows[1].to));
  EXPECT_EQ(rows[1].score.pairs, 2);
  EXPECT_EQ(rows[1].score.success, 1);
  EXPECT_EQ(rows[1].score.false_ok, 1);
  EXPECT_THROW(score_by_field(details, "jpeg_quality", {62, 50}), std::invalid_argument);
  EXPECT_THROW(score_by_field(details, "motion_blur_px", {10}), std::invalid_argument);
}

TEST(ValidationSet, TheSampleCarriesWhatEachConditionVaries) {
  for (const ValidationPair& p : load_validation_set(kSample)) {
    EXPECT_EQ(p.numbers.count("range_m"), 1u) << p.name;
    EXPECT_NEAR(p.numbers.at("range_m"), p.T_cl_marker.translation().norm(), 1e-3) << p.name;
    EXPECT_EQ(p.numbers.count("condition"), 0u) << p.name;  // words are not numbers
    if (p.condition == "noise_jpeg") {
      EXPECT_EQ(p.numbers.count("jpeg_quality"), 1u) << p.name;
      EXPECT_EQ(p.numbers.count("full_well_e"), 1u) << p.name;
    }
    if (p.condition == "motion_blur") {
      EXPECT_EQ(p.numbers.count("motion_blur_px"), 1u) << p.name;
      EXPECT_EQ(p.numbers.count("motion_blur_diameters"), 1u) << p.name;
    }
  }
}

TEST(ValidationSet, ABrokenManifestIsNamed) {
  const fs::path dir = fs::temp_directory_path() / "rovctl_validation_set_test";
  fs::create_directories(dir);
  std::ofstream(dir / "manifest.json")
      << R"({"pairs": [{"condition": "clear", "left": "a.png", "right": "b.png",)"
      << R"( "t_cl_marker_m": [0, 0], "q_cl_marker_wxyz": [1, 0, 0, 0]}]})";
  try {
    load_validation_set(dir.string());
    FAIL() << "a translation of two numbers was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("manifest.json"), std::string::npos) << what;
    EXPECT_NE(what.find("pairs[0]"), std::string::npos) << what;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rovctl::app
