// The estimator on the committed sample of the independent (POV-Ray) validation set: it may
// refuse a hard pair, but what it calls ok must be right. And a broken manifest is named.
#include "app/tools/validation_set.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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
  for (const char* c :
       {"clear", "turbid_near", "turbid_far", "side_light", "bubbles", "occlusion", "edge",
        "noise_jpeg", "distortion", "overexposed", "underexposed", "motion_blur"}) {
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
