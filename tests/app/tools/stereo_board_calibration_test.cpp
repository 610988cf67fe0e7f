// The calibration's decisions on corners projected through a known rig (OpenCV's projectPoints,
// not rovctl's camera code): the rig recovered, a misplaced grid dropped and named, too few views
// and too little coverage refused, and the detector's reasons on drawn images.
#include "app/tools/stereo_board_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

namespace rovctl::app {
namespace {

const BoardSpec kBoard{9, 6, 0.03};
const cv::Size kSize(640, 480);

struct TrueRig {
  cv::Mat K1 = (cv::Mat_<double>(3, 3) << 552, 0, 331.5, 0, 549, 236, 0, 0, 1);
  cv::Mat D1 = (cv::Mat_<double>(1, 5) << -0.12, 0.05, 0.001, -0.0008, 0);
  cv::Mat K2 = (cv::Mat_<double>(3, 3) << 558, 0, 312, 0, 556.5, 245, 0, 0, 1);
  cv::Mat D2 = (cv::Mat_<double>(1, 5) << -0.10, 0.03, -0.0006, 0.0012, 0.002);
  cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0, 0.0698, 0);
  cv::Mat T = (cv::Mat_<double>(3, 1) << -0.1776, 0, 0.0124);
};

std::vector<cv::Point3f> corners3d() {
  std::vector<cv::Point3f> p;
  for (int r = 0; r < kBoard.inner_rows; ++r) {
    for (int c = 0; c < kBoard.inner_cols; ++c)
      p.emplace_back(static_cast<float>(c * kBoard.square_m),
                     static_cast<float>(r * kBoard.square_m), 0.f);
  }
  return p;
}

bool inside(const std::vector<cv::Point2f>& pts) {
  for (const cv::Point2f& p : pts) {
    if (p.x < 5 || p.y < 5 || p.x > kSize.width - 6 || p.y > kSize.height - 6) return false;
  }
  return true;
}

// `n` views of the board whole in both images, spread over the image and tilted up to 45 deg,
// with 0.1 px of corner noise; `spread` < 1 keeps them near the image centre.
std::vector<BoardView> views(int n, double spread, unsigned seed) {
  const TrueRig rig;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<float> noise(0.f, 0.1f);
  std::vector<BoardView> out;
  while (static_cast<int>(out.size()) < n) {
    const double z = 0.45 + 0.25 * (uni(rng) + 1.0);
    cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0.6 * uni(rng), 0.6 * uni(rng), 0.3 * uni(rng));
    cv::Mat R;
    cv::Rodrigues(rvec, R);
    const cv::Mat centre = (cv::Mat_<double>(3, 1) << 0.12, 0.075, 0);
    cv::Mat target =
        (cv::Mat_<double>(3, 1) << spread * 0.3 * z * uni(rng), spread * 0.22 * z * uni(rng), z);
    const cv::Mat t = target - R * centre;
    std::vector<cv::Point2f> l, r;
    cv::projectPoints(corners3d(), rvec, t, rig.K1, rig.D1, l);
    cv::Mat R_rl;
    cv::Rodrigues(rig.rvec, R_rl);
    cv::Mat rvec_r;
    cv::Rodrigues(R_rl * R, rvec_r);
    cv::projectPoints(corners3d(), rvec_r, R_rl * t + rig.T, rig.K2, rig.D2, r);
    if (!inside(l) || !inside(r)) continue;
    for (auto* pts : {&l, &r}) {
      for (cv::Point2f& p : *pts) p += cv::Point2f(noise(rng), noise(rng));
    }
    BoardView v;
    v.name = "view" + std::to_string(out.size());
    v.left_px = l;
    v.right_px = r;
    out.push_back(v);
  }
  return out;
}

TEST(StereoBoardCalibration, RecoversTheRigAndDropsAMisplacedGrid) {
  std::vector<BoardView> v = views(24, 1.0, 3);
  // One grid detected shifted by a whole square in the right image: a wrong match, not noise.
  std::rotate(v[5].right_px.begin(), v[5].right_px.begin() + 1, v[5].right_px.end());
  const StereoBoardCalibration c = calibrate_stereo_board(v, kSize, kBoard, CalibrationLimits{});
  ASSERT_EQ(c.refusal, "");
  EXPECT_FALSE(c.views[5].kept);
  EXPECT_EQ(c.views[5].reason.rfind("outlier: reprojection", 0), 0u) << c.views[5].reason;
  EXPECT_EQ(c.views_used, 23);
  EXPECT_NEAR(c.rig.left.fx_px, 552.0, 552.0 * 0.002);
  EXPECT_NEAR(c.rig.right.fy_px, 556.5, 556.5 * 0.002);
  EXPECT_NEAR(c.rig.left.cx_px, 331.5, 1.5);
  EXPECT_NEAR(c.rig.baseline_m(), std::hypot(0.1776, 0.0124), 0.001);
  EXPECT_LT(c.rms_px, 0.2);
  EXPECT_LT(c.epipolar_rms_px, 0.2);
  EXPECT_GT(c.coverage_left.fraction(), 0.5);
  const std::string yaml = calibration_yaml(c, "chessboard:9x6:30", "2026-01-01T00:00:00Z");
  EXPECT_NE(yaml.find("T_unit: m"), std::string::npos);
  EXPECT_NE(yaml.find("views_used: 23"), std::string::npos);
}

TEST(StereoBoardCalibration, RefusesTooFewViewsAndTooLittleCoverage) {
  const StereoBoardCalibration few =
      calibrate_stereo_board(views(6, 1.0, 4), kSize, kBoard, CalibrationLimits{});
  EXPECT_EQ(few.refusal.rfind("too few views: 6 usable", 0), 0u) << few.refusal;
  const StereoBoardCalibration central =
      calibrate_stereo_board(views(14, 0.05, 5), kSize, kBoard, CalibrationLimits{});
  EXPECT_EQ(central.refusal.rfind("too little of the image covered", 0), 0u) << central.refusal;
}

cv::Mat drawn_board(double shift_x_px, double smear_px) {
  // A frontal board drawn square by square, then moved (and smeared along the diagonal).
  cv::Mat img(kSize, CV_8UC3, cv::Scalar(110, 110, 110));
  const int sq = 36, x0 = 140, y0 = 110;
  cv::rectangle(img, cv::Rect(x0 - sq, y0 - sq, sq * 12, sq * 9), cv::Scalar(215, 215, 215),
                cv::FILLED);
  for (int r = 0; r < 7; ++r) {
    for (int c = 0; c < 10; ++c) {
      if ((r + c) % 2 == 0)
        cv::rectangle(img, cv::Rect(x0 + c * sq, y0 + r * sq, sq, sq), cv::Scalar(35, 35, 35),
                      cv::FILLED);
    }
  }
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, shift_x_px, 0, 1, 0);
  cv::warpAffine(img, img, shift, kSize, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                 cv::Scalar(110, 110, 110));
  cv::GaussianBlur(img, img, cv::Size(), 0.7);
  if (smear_px > 0) {
    cv::Mat k = cv::Mat::eye(static_cast<int>(smear_px), static_cast<int>(smear_px), CV_32F);
    cv::filter2D(img, img, -1, k / smear_px);
  }
  return img;
}

TEST(StereoBoardCalibration, NamesWhyAViewIsLeftOut) {
  const CalibrationLimits limits;
  const cv::Mat board = drawn_board(0, 0);
  const cv::Mat empty(kSize, CV_8UC3, cv::Scalar(110, 110, 110));
  EXPECT_EQ(detect_board_view("a", board, board, kBoard, limits).reason, "");
  EXPECT_EQ(detect_board_view("b", board, empty, kBoard, limits).reason,
            "board not in the right image");
  EXPECT_EQ(detect_board_view("c", empty, board, kBoard, limits).reason,
            "board not in the left image");
  EXPECT_EQ(detect_board_view("d", empty, empty, kBoard, limits).reason, "no board");
  const cv::Mat cut = drawn_board(330, 0);
  EXPECT_EQ(detect_board_view("e", cut, cut, kBoard, limits).reason.rfind("board cut by the", 0),
            0u);
  const cv::Mat smeared = drawn_board(0, 25);
  EXPECT_EQ(detect_board_view("f", smeared, smeared, kBoard, limits).reason.rfind("too blurred", 0),
            0u)
      << detect_board_view("f", smeared, smeared, kBoard, limits).reason;
}

}  // namespace
}  // namespace rovctl::app
