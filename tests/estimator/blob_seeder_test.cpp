// BlobSeeder's smear reading: a blob's second moments read as a disc swept along a line, on
// hand-drawn discs and stadiums (the shape a uniformly labelled smear takes).
#include "estimator/blob_seeder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "test_scene.hpp"

namespace rovctl::estimator {
namespace {

constexpr int kColour = static_cast<int>(hal::ColourClass::green);

struct SeederFixture {
  testing::TestScene scene;
  BlobSeeder seeder{scene.rig, scene.marker};
  cv::Mat labels{scene.rig.left.height_px, scene.rig.left.width_px, CV_8UC1, cv::Scalar(0)};
  const Blob& find() {
    seeder.find(0, labels);
    return seeder.blobs()[0][kColour];
  }
};

// What the moments read on a uniform stadium of radius r and straight length L: the square root
// of 12 (I_along - I_across) / area = L (2 L^2 + 3 pi r L + 8 r^2) / (pi r + 2 L), about
// L + 0.8 diameters for L well over r (a blurred image's smear fades at its ends, so its labelled
// part reads closer to the smear itself).
double stadium_reading(double r, double length) {
  const double l = length;
  return std::sqrt(l * (2.0 * l * l + 3.0 * M_PI * r * l + 8.0 * r * r) / (M_PI * r + 2.0 * l));
}

TEST(BlobSeeder, ASharpDiscReadsNoSmearAndItsDiameterAcross) {
  SeederFixture f;
  cv::circle(f.labels, {300, 200}, 12, cv::Scalar(kColour), cv::FILLED);
  const Blob& b = f.find();
  ASSERT_TRUE(b.valid);
  EXPECT_LT(std::hypot(b.smear_u_px, b.smear_v_px), 2.0);
  EXPECT_NEAR(b.width_px, 24.0, 1.0);
}

TEST(BlobSeeder, AStadiumReadsItsLengthAlongItsLine) {
  SeederFixture f;
  for (const double angle_deg : {0.0, 30.0, 90.0, 135.0}) {
    for (const int length : {12, 24, 40}) {
      f.labels.setTo(0);
      const double a = angle_deg * M_PI / 180.0;
      const cv::Point p0(300, 200);
      const cv::Point p1(300 + static_cast<int>(std::lround(length * std::cos(a))),
                         200 + static_cast<int>(std::lround(length * std::sin(a))));
      cv::line(f.labels, p0, p1, cv::Scalar(kColour), 2 * 10 + 1);
      const Blob& b = f.find();
      ASSERT_TRUE(b.valid);
      const double smear = std::hypot(b.smear_u_px, b.smear_v_px);
      EXPECT_NEAR(smear, stadium_reading(10.5, length), 0.06 * length + 2.0)
          << angle_deg << " deg, " << length << " px";
      // Along the line, either way.
      const double along = std::abs(b.smear_u_px * std::cos(a) + b.smear_v_px * std::sin(a));
      EXPECT_GT(along, 0.99 * smear) << angle_deg << " deg, " << length << " px";
      EXPECT_GT(b.width_px, 21.0);
      EXPECT_LT(b.width_px, 27.0);
    }
  }
}

TEST(BlobSeeder, AHalfDiscIsNarrowerThanItsSphere) {
  // A sphere shaded on one side: elongated along the cut, but half as wide as the disc it is
  // part of, which is what keeps the fitness from sweeping it.
  SeederFixture f;
  cv::circle(f.labels, {300, 200}, 12, cv::Scalar(kColour), cv::FILLED);
  f.labels(cv::Rect(288, 201, 30, 20)).setTo(0);
  const Blob& b = f.find();
  ASSERT_TRUE(b.valid);
  EXPECT_LT(b.width_px, 0.6 * 24.0);
}

}  // namespace
}  // namespace rovctl::estimator
