// colour_edge: where a run of a colour ends along a ray, by hand-drawn cases, and the walk from
// the far end agreeing with the walk from the inside on random label images.
#include "estimator/colour_edge.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

namespace {

using namespace rovctl::estimator;

constexpr std::uint8_t kColour = 2;

// One row of labels 40 px wide, the colour on [from, to] of row 5.
cv::Mat row_labels(int from, int to) {
  cv::Mat labels(10, 40, CV_8UC1, cv::Scalar(0));
  labels.row(5).colRange(from, to + 1).setTo(kColour);
  return labels;
}

const Eigen::Vector2d kRowStart(0.0, 5.0);
const Eigen::Vector2d kAlongRow(1.0, 0.0);

TEST(ColourEdge, IsHalfwayPastTheLastSampleOfTheLastRun) {
  const cv::Mat labels = row_labels(10, 20);
  // Pixel 20 holds samples 19.5 and 20.0; 20.5 rounds to pixel 21.
  EXPECT_DOUBLE_EQ(colour_edge_t(labels, kRowStart, kAlongRow, 5.0, 30.0, kColour), 20.25);
  EXPECT_DOUBLE_EQ(colour_edge_t_from_inside(labels, kRowStart, kAlongRow, 5.0, 30.0, kColour),
                   20.25);
  EXPECT_DOUBLE_EQ(colour_edge_t_from_far_end(labels, kRowStart, kAlongRow, 5.0, 30.0, kColour),
                   20.25);
  // Another colour is no edge of this one.
  EXPECT_EQ(colour_edge_t(labels, kRowStart, kAlongRow, 5.0, 30.0, kColour + 1), -1.0);
}

TEST(ColourEdge, ALoneSampleIsASpeckAndTwoAreTheRim) {
  // Three pixels a step: x = 3 t reads pixels 6, 8, 9, 11, 12, 14, 15, 17, 18, 20, 21, 23, 24...
  const Eigen::Vector2d fast(3.0, 0.0);
  cv::Mat labels = row_labels(8, 18);  // the last sample in colour is t = 6 (pixel 18)
  EXPECT_DOUBLE_EQ(colour_edge_t(labels, kRowStart, fast, 2.0, 9.5, kColour), 6.25);
  labels.at<std::uint8_t>(5, 23) = kColour;  // t = 7.5 alone
  EXPECT_DOUBLE_EQ(colour_edge_t(labels, kRowStart, fast, 2.0, 9.5, kColour), 6.25);
  labels.at<std::uint8_t>(5, 24) = kColour;  // t = 7.5 and 8: a run
  EXPECT_DOUBLE_EQ(colour_edge_t(labels, kRowStart, fast, 2.0, 9.5, kColour), 8.25);
}

TEST(ColourEdge, ColourToTheFarEndOrTheBorderIsNoEdge) {
  // To the far end: the rim is beyond the ray.
  EXPECT_EQ(colour_edge_t(row_labels(10, 35), kRowStart, kAlongRow, 5.0, 30.0, kColour), -1.0);
  // To the image border: the rim is outside the image, and the far end's walk cannot start.
  const cv::Mat to_border = row_labels(10, 39);
  EXPECT_EQ(colour_edge_t_from_far_end(to_border, kRowStart, kAlongRow, 5.0, 50.0, kColour), -2.0);
  EXPECT_EQ(colour_edge_t(to_border, kRowStart, kAlongRow, 5.0, 50.0, kColour), -1.0);
  // Past the border after the edge: the edge stands, found from the inside.
  const cv::Mat before_border = row_labels(10, 20);
  EXPECT_EQ(colour_edge_t_from_far_end(before_border, kRowStart, kAlongRow, 5.0, 50.0, kColour),
            -2.0);
  EXPECT_DOUBLE_EQ(colour_edge_t(before_border, kRowStart, kAlongRow, 5.0, 50.0, kColour), 20.25);
  // No colour at all, and an empty ray.
  EXPECT_EQ(colour_edge_t(row_labels(0, -1), kRowStart, kAlongRow, 5.0, 30.0, kColour), -1.0);
  EXPECT_EQ(colour_edge_t(before_border, kRowStart, kAlongRow, 5.0, 4.0, kColour), -1.0);
}

TEST(ColourEdge, BothWalksFindTheSameEdgeOnRandomLabels) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int compared = 0, edges = 0, none = 0, off_image = 0;
  for (int image = 0; image < 40; ++image) {
    // Discs of the colour and of another, and specks of the colour, as segmented water shows.
    cv::Mat labels(48, 64, CV_8UC1, cv::Scalar(0));
    for (int d = 0; d < 4; ++d) {
      cv::circle(
          labels, cv::Point(static_cast<int>(64 * unit(rng)), static_cast<int>(48 * unit(rng))),
          2 + static_cast<int>(14 * unit(rng)), cv::Scalar(d % 2 == 0 ? kColour : 1), cv::FILLED);
    }
    const double speckle = 0.3 * unit(rng);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        if (unit(rng) < speckle) labels.at<std::uint8_t>(v, u) = kColour;
      }
    }
    for (int ray = 0; ray < 100; ++ray) {
      const Eigen::Vector2d centre(64 * unit(rng), 48 * unit(rng));
      const double angle = 2.0 * M_PI * unit(rng);
      const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
      const double t_from = 5.0 * unit(rng), t_to = t_from + 40.0 * unit(rng);
      const double inside = colour_edge_t_from_inside(labels, centre, d, t_from, t_to, kColour);
      const double far_end = colour_edge_t_from_far_end(labels, centre, d, t_from, t_to, kColour);
      // Bit for bit: the refiner's fit must not depend on which walk found its points.
      EXPECT_EQ(colour_edge_t(labels, centre, d, t_from, t_to, kColour), inside)
          << "image " << image << " ray " << ray;
      if (far_end == -2.0) {
        ++off_image;
        continue;
      }
      ++compared;
      EXPECT_EQ(far_end, inside) << "image " << image << " ray " << ray;
      (inside >= 0.0 ? edges : none) += 1;
    }
  }
  // Each kind of ray was met often enough for the comparison to mean something.
  EXPECT_GT(compared, 1000);
  EXPECT_GT(edges, 300);
  EXPECT_GT(none, 100);
  EXPECT_GT(off_image, 300);
}

}  // namespace
