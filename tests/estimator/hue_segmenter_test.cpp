// Segmentation on shaded, highlighted, noisy renders and under a water cast, not flat colours.
#include "estimator/hue_segmenter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "estimator/pose_refiner.hpp"
#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

using testing::TestScene;

struct Rates {
  double recall = 0.0;          // pixels of each sphere's disc labelled with its colour
  double false_positive = 0.0;  // background pixels labelled with any colour
};

Rates measure(TestScene& scene, const Eigen::Isometry3d& T) {
  scene.render(T, 3);
  HueSegmenter seg(scene.marker);
  cv::Mat labels;
  seg.segment(scene.left_bgr, labels);
  cv::Mat inside(labels.size(), CV_8UC1, cv::Scalar(0));
  long hits = 0, total = 0;
  for (const hal::MarkerSphere& s : scene.marker.spheres) {
    Eigen::Vector2d uv = Eigen::Vector2d::Zero();
    const Eigen::Vector3d c = T * s.centre_marker_m;
    EXPECT_TRUE(PoseRefiner::silhouette_centroid(scene.rig.left, c, s.radius_m, uv));
    const double r_px = scene.rig.left.fx_px * s.radius_m / c.norm();
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        const double d = std::hypot(u - uv.x(), v - uv.y());
        if (d < 1.5 * r_px) inside.at<std::uint8_t>(v, u) = 1;
        if (d < 0.9 * r_px) {
          ++total;
          hits += labels.at<std::uint8_t>(v, u) == static_cast<std::uint8_t>(s.colour);
        }
      }
    }
  }
  long fp = 0, bg = 0;
  for (int v = 0; v < labels.rows; ++v) {
    for (int u = 0; u < labels.cols; ++u) {
      if (inside.at<std::uint8_t>(v, u)) continue;
      ++bg;
      fp += labels.at<std::uint8_t>(v, u) != 0;
    }
  }
  return {static_cast<double>(hits) / total, static_cast<double>(fp) / bg};
}

TEST(HueSegmenter, ShadedSpheresWithHighlightsAndNoise) {
  TestScene scene;
  const Rates r = measure(scene, hal::make_pose({0.05, 0.0, 0.5}, Eigen::Quaterniond::Identity()));
  EXPECT_GT(r.recall, 0.9);
  EXPECT_LT(r.false_positive, 1e-4);
}

TEST(HueSegmenter, BlueGreenCastOfWater) {
  hal::mock::RenderOptions o;
  o.water_attenuation_per_m = 0.5;
  o.background_top_rgb = {0.05, 0.30, 0.32};  // a strongly tinted water background
  o.background_bottom_rgb = {0.02, 0.12, 0.14};
  o.noise_sigma = 3.0;
  TestScene scene(o);
  const Rates r = measure(scene, hal::make_pose({0.05, 0.0, 1.2}, Eigen::Quaterniond::Identity()));
  EXPECT_GT(r.recall, 0.8);
  EXPECT_LT(r.false_positive, 1e-3);
}

TEST(HueSegmenter, TableAgreesWithTheHsvRule) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  HueSegmenter seg(marker);
  // BGR: a dark shaded red, a bright green, a blue, a grey highlight, black, a cyan background.
  EXPECT_EQ(seg.classify(10, 12, 90), hal::ColourClass::red);
  EXPECT_EQ(seg.classify(40, 200, 30), hal::ColourClass::green);
  EXPECT_EQ(seg.classify(220, 60, 20), hal::ColourClass::blue);
  EXPECT_EQ(seg.classify(240, 240, 245), hal::ColourClass::none);
  EXPECT_EQ(seg.classify(2, 2, 6), hal::ColourClass::none);  // below the value floor
  EXPECT_EQ(seg.classify(160, 150, 120), hal::ColourClass::none);
  for (int b = 2; b < 256; b += 36) {
    for (int g = 2; g < 256; g += 36) {
      for (int r = 2; r < 256; r += 36) {
        EXPECT_EQ(seg.classify(b, g, r), HueSegmenter::classify_exact(marker, b, g, r));
      }
    }
  }
}

// segment() reads four pixels at a time: every pixel, the last ones of an odd row and a view into
// a wider image included, gets the class of its own colour, before and after the water's gains.
TEST(HueSegmenter, EveryPixelGetsTheClassOfItsColourAtAnyRowWidth) {
  const hal::MarkerModel marker = hal::MarkerModel::standard();
  cv::Mat wide(23, 50, CV_8UC3);
  cv::randu(wide, cv::Scalar(0, 0, 0), cv::Scalar(256, 200, 90));  // water's cast: red faded
  for (const int width : {3, 4, 37}) {
    const cv::Mat image = wide(cv::Rect(5, 2, width, 19));  // rows not contiguous
    for (const double correction : {0.0, 0.75}) {
      HueSegmenter seg(marker, correction);
      cv::Mat labels;
      seg.segment(image, labels);
      ASSERT_EQ(labels.size(), image.size());
      const std::array<double, 3>& gain = seg.gains();
      if (correction > 0.0) {
        EXPECT_GT(gain[2], 1.3);  // the red channel raised: the gains are in play
      }
      auto gained = [&](int c, std::uint8_t v) {
        return static_cast<std::uint8_t>(std::min(255.0, std::round(gain[c] * v)));
      };
      int wrong = 0;
      for (int v = 0; v < image.rows; ++v) {
        for (int u = 0; u < image.cols; ++u) {
          const cv::Vec3b p = image.at<cv::Vec3b>(v, u);
          const hal::ColourClass want =
              seg.classify(gained(0, p[0]), gained(1, p[1]), gained(2, p[2]));
          wrong += labels.at<std::uint8_t>(v, u) != static_cast<std::uint8_t>(want);
        }
      }
      EXPECT_EQ(wrong, 0) << "width " << width << ", correction " << correction;
    }
  }
}

// Turbid coastal water, as the POV-Ray set renders it 1.4 m out: the red sphere is a greyish
// brown (BGR 86, 91, 131; saturation 0.34) on a green-blue cast (BGR 129, 146, 72). The standard
// marker's red floor (0.2) keeps it as it is; with the other colours' floor (0.35) it is lost,
// and dividing the water's cast out finds it again.
TEST(HueSegmenter, AFadedRedInTurbidWaterIsFound) {
  cv::Mat image(120, 160, CV_8UC3, cv::Scalar(129, 146, 72));
  image(cv::Rect(70, 50, 12, 12)).setTo(cv::Scalar(86, 91, 131));
  const auto red = static_cast<std::uint8_t>(hal::ColourClass::red);
  const auto none = static_cast<std::uint8_t>(hal::ColourClass::none);
  cv::Mat labels;
  const hal::MarkerModel standard = hal::MarkerModel::standard();
  HueSegmenter plain(standard, 0.0);
  plain.segment(image, labels);
  EXPECT_EQ(labels.at<std::uint8_t>(55, 75), red);
  EXPECT_EQ(labels.at<std::uint8_t>(5, 5), none);

  hal::MarkerModel strict = standard;
  for (hal::MarkerSphere& s : strict.spheres) s.saturation_min = 0.35;
  HueSegmenter strict_plain(strict, 0.0);
  strict_plain.segment(image, labels);
  EXPECT_EQ(labels.at<std::uint8_t>(55, 75), none);
  HueSegmenter corrected(strict, 0.75);
  corrected.segment(image, labels);
  EXPECT_EQ(labels.at<std::uint8_t>(55, 75), red);
  EXPECT_EQ(labels.at<std::uint8_t>(5, 5), none);
}

}  // namespace
}  // namespace rovctl::estimator
