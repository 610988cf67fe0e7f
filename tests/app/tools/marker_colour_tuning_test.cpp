// Marker colours tuned on the committed POV-Ray sample of green, algal water (a cast that moves
// the blue sphere out of the shipped window): the proposed windows hold every sphere where the
// truth puts it, the estimator then gets every pair right, and a background painted in a sphere's
// colour is refused. The sample is rendered by tests/estimator/water_set/render_water_set.py.
#include "app/tools/marker_colour_tuning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/runtime/app_config.hpp"
#include "app/runtime/config_loader.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/validation_set.hpp"
#include "estimator/hue_segmenter.hpp"

namespace rovctl::app {
namespace {

const std::string kSample = std::string(ROVCTL_TEST_DATA_DIR) + "/marker_colour_cast";

struct Sample {
  AppConfig config = load_app_config(default_config_path());
  hal::StereoRig rig = load_rig(config);
  std::vector<ValidationPair> truth = load_validation_set(kSample);
  std::vector<StereoImages> pairs;
  Sample() {
    for (const ValidationPair& t : truth) {
      pairs.push_back({t.name, cv::imread(t.left_png), cv::imread(t.right_png)});
    }
  }
};

const Sample& sample() {
  static const Sample s;
  return s;
}

// The tuning is the expensive part: once for the tests that read it.
const ColourTuningResult& tuned() {
  static const ColourTuningResult r = tune_marker_colours(
      sample().rig, sample().config.marker, sample().config.estimator, sample().pairs, {});
  return r;
}

// Share of each sphere's inner disc (0.7 of its radius, where the truth puts it) that `marker`'s
// windows label its colour, per view.
std::vector<double> disc_shares(const hal::MarkerModel& marker, const cv::Mat& image,
                                const hal::CameraModel& camera, const Eigen::Isometry3d& T) {
  estimator::HueSegmenter segmenter(marker, sample().config.estimator.water_correction);
  cv::Mat labels;
  segmenter.segment(image, labels);
  std::vector<double> shares;
  for (const hal::MarkerSphere& s : marker.spheres) {
    const Eigen::Vector3d c = T * s.centre_marker_m;
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    EXPECT_TRUE(camera.project(c, uv));
    const double r = 0.7 * camera.fx_px * s.radius_m / c.z();
    long hit = 0, all = 0;
    for (int v = static_cast<int>(uv.y() - r); v <= uv.y() + r; ++v) {
      for (int u = static_cast<int>(uv.x() - r); u <= uv.x() + r; ++u) {
        if ((u - uv.x()) * (u - uv.x()) + (v - uv.y()) * (v - uv.y()) > r * r) continue;
        ++all;
        hit += labels.at<std::uint8_t>(v, u) == static_cast<std::uint8_t>(s.colour);
      }
    }
    shares.push_back(all > 0 ? static_cast<double>(hit) / all : 0.0);
  }
  return shares;
}

TEST(MarkerColourTuning, ShippedWindowsLoseASphereInTheCastSample) {
  double worst = 1.0;
  for (const ValidationPair& t : sample().truth) {
    const std::vector<double> shares = disc_shares(sample().config.marker, cv::imread(t.left_png),
                                                   sample().rig.left, t.T_cl_marker);
    for (double s : shares) worst = std::min(worst, s);
  }
  EXPECT_LT(worst, 0.2) << "the sample should hold a sphere the shipped windows do not see";
  // And a pair the estimator, with its water retry, misses with them.
  std::vector<PairResult> details;
  const std::vector<ConditionScore> scores =
      score_validation_set(sample().rig, sample().config.marker, sample().config.estimator,
                           sample().truth, 10, &details);
  EXPECT_LT(scores.back().success, scores.back().pairs);
  EXPECT_EQ(scores.back().false_ok, 0);
}

TEST(MarkerColourTuning, ProposedWindowsHoldEverySphereWhereTheTruthPutsIt) {
  const ColourTuningResult& r = tuned();
  ASSERT_FALSE(r.refused) << r.reason;
  EXPECT_EQ(r.located(), static_cast<int>(sample().pairs.size()));
  for (const ValidationPair& t : sample().truth) {
    const Eigen::Isometry3d T_cr = sample().rig.T_cr_cl * t.T_cl_marker;
    const std::vector<double> left =
        disc_shares(r.tuned, cv::imread(t.left_png), sample().rig.left, t.T_cl_marker);
    const std::vector<double> right =
        disc_shares(r.tuned, cv::imread(t.right_png), sample().rig.right, T_cr);
    for (std::size_t s = 0; s < left.size(); ++s) {
      EXPECT_GT(left[s], 0.9) << t.name << " " << r.tuned.spheres[s].name;
      EXPECT_GT(right[s], 0.9) << t.name << " " << r.tuned.spheres[s].name;
    }
  }
  for (const ColourCounts& c : r.counts) {
    EXPECT_GT(c.inside_after, 0.9) << c.name;
    EXPECT_LT(c.background_fraction_after, 0.25) << c.name;
  }
}

TEST(MarkerColourTuning, TheEstimatorGetsEveryPairRightWithTheTunedWindows) {
  const ColourTuningResult& r = tuned();
  ASSERT_FALSE(r.refused) << r.reason;
  std::vector<PairResult> details;
  const std::vector<ConditionScore> scores = score_validation_set(
      sample().rig, r.tuned, sample().config.estimator, sample().truth, 10, &details);
  EXPECT_EQ(scores.back().success, scores.back().pairs);
  EXPECT_EQ(scores.back().false_ok, 0);
}

TEST(MarkerColourTuning, ARecordingShortOfTheWorkingRangeIsSaidSo) {
  // The sample's three pairs lie 1.06-1.11 m out, inside the default working range 0.3-1.5 m.
  const ColourTuningResult& r = tuned();
  EXPECT_NEAR(r.located_range_min_m, 1.06, 0.02);
  EXPECT_NEAR(r.located_range_max_m, 1.11, 0.02);
  EXPECT_FALSE(r.covers_far);
  EXPECT_FALSE(r.covers_near);
  int said = 0;
  for (const std::string& note : r.notes) {
    said += note.find("does not cover far range") != std::string::npos;
    said += note.find("does not cover near range") != std::string::npos;
  }
  EXPECT_EQ(said, 2);
}

// A sphere whose hues fall 80 deg per metre (lows) and 50 (highs), with +-3 deg of scatter, seen
// 0.4-1.2 m out: over a working range of 0.3-1.5 m the window follows the lows to 1.5 m and the
// highs to 0.3 m, below and above every view.
TEST(MarkerColourTuning, TheWindowFollowsTheHueDriftOverTheWorkingRange) {
  std::vector<RangedHueExtremes> views;
  for (int i = 0; i <= 8; ++i) {
    const double r = 0.4 + 0.1 * i;
    const double scatter = (i % 3 - 1) * 3.0;
    views.push_back({r, 200.0 - 80.0 * r + scatter, 210.0 - 50.0 * r - scatter});
  }
  const HueDrift d = hue_drift_over_range(views, 0.3, 1.5);
  EXPECT_NEAR(d.low_drift_deg_per_m, -80.0, 5.0);
  EXPECT_NEAR(d.high_drift_deg_per_m, -50.0, 5.0);
  EXPECT_NEAR(d.range_min_m, 0.4, 1e-9);
  EXPECT_NEAR(d.range_max_m, 1.2, 1e-9);
  EXPECT_NEAR(d.low_deg, 200.0 - 80.0 * 1.5, 8.0);
  EXPECT_NEAR(d.high_deg, 210.0 - 50.0 * 0.3, 8.0);
  double low = 1e9, high = -1e9;
  for (const RangedHueExtremes& v : views) {
    low = std::min(low, v.low_deg);
    high = std::max(high, v.high_deg);
  }
  EXPECT_LT(d.low_deg, low - 5.0);
  EXPECT_GT(d.high_deg, high + 3.0);
  // A working range inside the views' adds nothing to their own extremes.
  const HueDrift inside = hue_drift_over_range(views, 0.5, 1.1);
  EXPECT_NEAR(inside.low_deg, low, 1e-9);
  EXPECT_NEAR(inside.high_deg, high, 1e-9);
  // Views spanning under 0.2 m give no drift to follow.
  const std::vector<RangedHueExtremes> close = {views[3], views[4]};
  const HueDrift none = hue_drift_over_range(close, 0.3, 1.5);
  EXPECT_EQ(none.low_drift_deg_per_m, 0.0);
  EXPECT_NEAR(none.low_deg, std::min(views[3].low_deg, views[4].low_deg), 1e-9);
}

TEST(MarkerColourTuning, TheFragmentLoadsAsTheConfigsMarkerSectionWithItsGeometry) {
  const ColourTuningResult& r = tuned();
  hal::MarkerModel loaded = hal::MarkerModel::standard();
  load_yaml_text(marker_fragment_yaml(r.tuned, "a header\nof two lines"), "fragment.yaml", ".",
                 [&loaded](hal::ParamVisitor& v) {
                   v.section("marker", "the marker",
                             [&loaded](hal::ParamVisitor& s) { hal::describe(s, loaded); });
                 });
  ASSERT_EQ(loaded.spheres.size(), r.tuned.spheres.size());
  for (std::size_t s = 0; s < loaded.spheres.size(); ++s) {
    EXPECT_NEAR(loaded.spheres[s].hue_min_deg, r.tuned.spheres[s].hue_min_deg, 1e-9);
    EXPECT_NEAR(loaded.spheres[s].hue_max_deg, r.tuned.spheres[s].hue_max_deg, 1e-9);
    EXPECT_NEAR(loaded.spheres[s].saturation_min, r.tuned.spheres[s].saturation_min, 1e-9);
    EXPECT_NEAR(loaded.spheres[s].value_min, r.tuned.spheres[s].value_min, 1e-9);
    const hal::MarkerSphere& configured = sample().config.marker.spheres[s];
    EXPECT_EQ(loaded.spheres[s].name, configured.name);
    EXPECT_EQ(loaded.spheres[s].centre_marker_m, configured.centre_marker_m);
    EXPECT_EQ(loaded.spheres[s].radius_m, configured.radius_m);
  }
}

TEST(MarkerColourTuning, ABackgroundInASpheresColourIsRefused) {
  // The blue sphere's own colour (as tuned) painted over a third of every image, away from the
  // spheres: no window can hold that sphere without the background.
  const ColourTuningResult& r = tuned();
  ASSERT_FALSE(r.refused) << r.reason;
  std::vector<StereoImages> painted = sample().pairs;
  for (std::size_t i = 0; i < painted.size(); ++i) {
    const ValidationPair& t = sample().truth[i];
    for (int side = 0; side < 2; ++side) {
      cv::Mat& image = side == 0 ? painted[i].left : painted[i].right;
      image = image.clone();
      const hal::CameraModel& camera = side == 0 ? sample().rig.left : sample().rig.right;
      const Eigen::Isometry3d T = side == 0 ? t.T_cl_marker : sample().rig.T_cr_cl * t.T_cl_marker;
      const Eigen::Vector3d c = T * sample().config.marker.spheres[2].centre_marker_m;
      Eigen::Vector2d uv = Eigen::Vector2d::Zero();
      ASSERT_TRUE(camera.project(c, uv));
      const cv::Vec3b colour =
          image.at<cv::Vec3b>(static_cast<int>(uv.y()), static_cast<int>(uv.x()));
      // The half of the image the marker's centre is not in, across its shorter side.
      const bool marker_left = uv.x() < image.cols / 2;
      const cv::Rect half(marker_left ? image.cols * 3 / 4 : 0, 0, image.cols / 4, image.rows);
      image(half).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
    }
  }
  const ColourTuningResult refused = tune_marker_colours(sample().rig, sample().config.marker,
                                                         sample().config.estimator, painted, {});
  EXPECT_TRUE(refused.refused);
  EXPECT_NE(refused.reason.find("background"), std::string::npos) << refused.reason;
}

bool in_window(const hal::MarkerSphere& s, double h) {
  return s.hue_min_deg <= s.hue_max_deg ? h >= s.hue_min_deg && h <= s.hue_max_deg
                                        : h >= s.hue_min_deg || h <= s.hue_max_deg;
}

TEST(MarkerColourTuning, WidenedWindowsHoldTheConfiguredOnesAndStayApart) {
  const hal::MarkerModel shipped = hal::MarkerModel::standard();
  const hal::MarkerModel wide = widened_marker(shipped, 40.0, 0.1, 0.06);
  for (std::size_t s = 0; s < shipped.spheres.size(); ++s) {
    for (double h = 0.0; h < 360.0; h += 0.5) {
      if (in_window(shipped.spheres[s], h)) {
        EXPECT_TRUE(in_window(wide.spheres[s], h)) << shipped.spheres[s].name << " " << h;
      }
      for (std::size_t o = s + 1; o < shipped.spheres.size(); ++o) {
        EXPECT_FALSE(in_window(wide.spheres[s], h) && in_window(wide.spheres[o], h))
            << wide.spheres[s].name << " and " << wide.spheres[o].name << " at " << h;
      }
    }
    EXPECT_DOUBLE_EQ(wide.spheres[s].saturation_min,
                     std::min(shipped.spheres[s].saturation_min, 0.1));
  }
}

}  // namespace
}  // namespace rovctl::app
