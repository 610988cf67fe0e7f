// OpenCV does the solving (findChessboardCornersSB, calibrateCamera, stereoCalibrate,
// stereoRectify); this file decides what goes in, what is dropped and what the figures mean.
#include "app/tools/stereo_board_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "estimator/stereo_calibration.hpp"

namespace rovctl::app {
namespace {

enum class Sighting { found, partial, none };

struct ImageBoard {
  Sighting sighting = Sighting::none;
  std::vector<cv::Point2f> corners;
  double edge_width_px = 0.0;
};

// Edge width (10-90 %) of the board's edges around `corners`: a step of contrast C blurred to
// width w rises at most about 0.8 C / w per pixel, so the steepest slopes (99.5th percentile,
// above the noise) against the contrast (2nd to 98th percentile) give it. A sharp board reads
// about 1.8 px; one smeared by motion, 4 and more.
double edge_width_px(const cv::Mat& gray, const std::vector<cv::Point2f>& corners) {
  const cv::Rect box = cv::boundingRect(corners);
  const cv::Rect grown(box.x - box.width / 2, box.y - box.height / 2, 2 * box.width,
                       2 * box.height);
  cv::Mat roi;
  gray(grown & cv::Rect(0, 0, gray.cols, gray.rows)).convertTo(roi, CV_32F);
  cv::Mat gx, gy, magnitude;
  cv::Sobel(roi, gx, CV_32F, 1, 0, 3, 0.125);
  cv::Sobel(roi, gy, CV_32F, 0, 1, 3, 0.125);
  cv::magnitude(gx, gy, magnitude);
  auto percentile = [](const cv::Mat& m, double q) {
    std::vector<float> v(m.begin<float>(), m.end<float>());
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return static_cast<double>(v[static_cast<std::size_t>(k)]);
  };
  const double contrast = percentile(roi, 0.98) - percentile(roi, 0.02);
  const double steepest = percentile(magnitude, 0.995);
  return steepest > 0 ? 0.8 * contrast / steepest : 0.0;
}

// The sector detector's corners move with blur (about 0.03 px under an underwater blur of 1 px);
// the gradient-orthogonality refinement does not, and halves the scatter on a clear board. Its
// window must stay inside the squares around a corner: 0.4 of the corner spacing, 2..10 px.
void refine_corners(const cv::Mat& gray, std::vector<cv::Point2f>& corners) {
  std::vector<double> spacing;
  for (std::size_t i = 1; i < corners.size(); ++i)
    spacing.push_back(cv::norm(corners[i] - corners[i - 1]));
  std::nth_element(spacing.begin(), spacing.begin() + static_cast<long>(spacing.size() / 2),
                   spacing.end());
  const int half = std::clamp(static_cast<int>(0.4 * spacing[spacing.size() / 2]), 2, 10);
  cv::cornerSubPix(gray, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
}

// The sector-based detector is the most accurate of OpenCV's; a board it cannot find whole may
// still show part of itself to a small pattern that is allowed to be larger (CALIB_CB_LARGER).
ImageBoard find_board(const cv::Mat& bgr, const BoardSpec& board) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  ImageBoard out;
  const cv::Size pattern(board.inner_cols, board.inner_rows);
  const int flags = cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY;
  if (cv::findChessboardCornersSB(gray, pattern, out.corners, flags)) {
    out.sighting = Sighting::found;
    refine_corners(gray, out.corners);
  } else if (cv::findChessboardCornersSB(gray, cv::Size(3, 3), out.corners,
                                         flags | cv::CALIB_CB_LARGER)) {
    out.sighting = Sighting::partial;
  }
  if (out.sighting != Sighting::none) out.edge_width_px = edge_width_px(gray, out.corners);
  return out;
}

}  // namespace

double CoverageGrid::fraction() const {
  if (views.empty()) return 0.0;
  const auto covered = std::count_if(views.begin(), views.end(), [](int v) { return v > 0; });
  return static_cast<double>(covered) / static_cast<double>(views.size());
}

BoardView detect_board_view(const std::string& name, const cv::Mat& left_bgr,
                            const cv::Mat& right_bgr, const BoardSpec& board,
                            const CalibrationLimits& limits) {
  BoardView view;
  view.name = name;
  ImageBoard l = find_board(left_bgr, board);
  ImageBoard r = find_board(right_bgr, board);
  // Both cameras expose together, so motion smears both: a blurred part of a board in one image
  // beside a sharp board in the other is a pattern in the background, not the board.
  const double limit = limits.max_edge_width_px;
  auto sharp = [limit](const ImageBoard& b) {
    return b.sighting != Sighting::none && b.edge_width_px <= limit;
  };
  for (auto [one, other] : {std::pair{&l, &r}, {&r, &l}}) {
    if (one->sighting == Sighting::partial && one->edge_width_px > limit && sharp(*other)) {
      one->sighting = Sighting::none;
      one->edge_width_px = 0.0;
    }
  }
  // Blur first: a smeared board is often found only in part, which is not the image edge's doing.
  view.edge_width_px = std::max(l.edge_width_px, r.edge_width_px);
  if (view.edge_width_px > limits.max_edge_width_px) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "too blurred for sub-pixel corners (%s edge width %.1f px, limit %.1f px)",
                  l.edge_width_px >= r.edge_width_px ? "left" : "right", view.edge_width_px,
                  limits.max_edge_width_px);
    view.reason = text;
    return view;
  }
  if (l.sighting == Sighting::found && r.sighting == Sighting::found) {
    view.left_px = l.corners;
    view.right_px = r.corners;
    // The detector may start the grid at either end of the board in each image; the cameras look
    // the same way, so the grid runs the same way in both.
    const cv::Point2f run_left = l.corners.back() - l.corners.front();
    const cv::Point2f run_right = r.corners.back() - r.corners.front();
    if (run_left.dot(run_right) < 0) std::reverse(view.right_px.begin(), view.right_px.end());
    return view;
  }
  const char* side = l.sighting != Sighting::found && r.sighting != Sighting::found ? "both images"
                     : l.sighting != Sighting::found                                ? "left image"
                                                                                    : "right image";
  if (l.sighting == Sighting::partial || r.sighting == Sighting::partial) {
    view.reason = std::string("board cut by the image edge (") + side + ")";
  } else if (l.sighting == Sighting::found) {
    view.reason = "board not in the right image";
  } else if (r.sighting == Sighting::found) {
    view.reason = "board not in the left image";
  } else {
    view.reason = "no board";
  }
  return view;
}

namespace {

struct Fit {
  cv::Mat K1, D1, K2, D2, R, T;
  double rms_left = 0, rms_right = 0, rms = 0;
  std::vector<double> view_error_px;  // per kept view: the worse camera's stereo RMS
  std::vector<double> tilt_deg;
  cv::Mat sigma1, sigma2;  // intrinsics' standard deviations (fx fy cx cy k1 ...)
};

std::vector<cv::Point3f> board_points(const BoardSpec& board) {
  std::vector<cv::Point3f> points;
  for (int r = 0; r < board.inner_rows; ++r) {
    for (int c = 0; c < board.inner_cols; ++c) {
      points.emplace_back(static_cast<float>(c * board.square_m),
                          static_cast<float>(r * board.square_m), 0.0f);
    }
  }
  return points;
}

// Each camera alone (its own distortion from its own views), then both together with every
// intrinsic refined from the joint fit: the pair's shared geometry sharpens what one camera's
// corners leave loose.
Fit fit_views(const std::vector<std::vector<cv::Point2f>>& left,
              const std::vector<std::vector<cv::Point2f>>& right, cv::Size size,
              const BoardSpec& board) {
  const std::vector<std::vector<cv::Point3f>> object(left.size(), board_points(board));
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12);
  // k3 stays 0, as ROS's camera_calibration keeps it: the sixth power of the radius is known only
  // from corners in the image's far corners, and fitted from fewer it bends the edges wildly.
  const int flags = cv::CALIB_FIX_K3;
  Fit fit;
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat extrinsic_sigma, view_errors;
  fit.rms_left = cv::calibrateCamera(object, left, size, fit.K1, fit.D1, rvecs, tvecs, fit.sigma1,
                                     extrinsic_sigma, view_errors, flags, criteria);
  std::vector<cv::Mat> rvecs_right, tvecs_right;
  fit.rms_right = cv::calibrateCamera(object, right, size, fit.K2, fit.D2, rvecs_right, tvecs_right,
                                      fit.sigma2, extrinsic_sigma, view_errors, flags, criteria);
  cv::Mat E, F, stereo_errors;
  fit.rms =
      cv::stereoCalibrate(object, left, right, fit.K1, fit.D1, fit.K2, fit.D2, size, fit.R, fit.T,
                          E, F, stereo_errors, flags | cv::CALIB_USE_INTRINSIC_GUESS, criteria);
  for (int i = 0; i < stereo_errors.rows; ++i) {
    fit.view_error_px.push_back(
        std::max(stereo_errors.at<double>(i, 0), stereo_errors.at<double>(i, 1)));
    cv::Mat rotation;
    cv::Rodrigues(rvecs[static_cast<std::size_t>(i)], rotation);
    const double cos_tilt = std::abs(rotation.at<double>(2, 2));
    fit.tilt_deg.push_back(std::acos(std::min(1.0, cos_tilt)) * 180.0 / M_PI);
  }
  return fit;
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The worst view when it stands out from the rest (its error beyond 2.5 times the median, five
// robust sigmas and a quarter pixel above it), else -1. The quarter pixel keeps a fit whose views
// all sit near 0.05 px from shedding good views over a few hundredths.
int outlier_index(const std::vector<double>& errors, double& median, double& limit) {
  median = median_of(errors);
  std::vector<double> deviation;
  for (double e : errors) deviation.push_back(std::abs(e - median));
  limit = std::max({2.5 * median, median + 5.0 * 1.4826 * median_of(deviation), median + 0.25});
  const auto worst = std::max_element(errors.begin(), errors.end());
  return worst != errors.end() && *worst > limit ? static_cast<int>(worst - errors.begin()) : -1;
}

hal::CameraModel camera_of(const cv::Mat& K, const cv::Mat& D, cv::Size size) {
  hal::CameraModel cam;
  cam.fx_px = K.at<double>(0, 0);
  cam.fy_px = K.at<double>(1, 1);
  cam.cx_px = K.at<double>(0, 2);
  cam.cy_px = K.at<double>(1, 2);
  const double* d = D.ptr<double>(0);
  cam.k1 = d[0];
  cam.k2 = d[1];
  cam.p1 = d[2];
  cam.p2 = d[3];
  cam.k3 = D.total() > 4 ? d[4] : 0.0;
  cam.width_px = size.width;
  cam.height_px = size.height;
  return cam;
}

CoverageGrid coverage_of(const std::vector<std::vector<cv::Point2f>>& views, cv::Size size,
                         const CalibrationLimits& limits) {
  CoverageGrid grid;
  grid.cols = limits.grid_cols;
  grid.rows = limits.grid_rows;
  grid.views.assign(static_cast<std::size_t>(grid.cols * grid.rows), 0);
  for (const auto& corners : views) {
    std::vector<bool> hit(grid.views.size(), false);
    for (const cv::Point2f& p : corners) {
      const int c = std::clamp(static_cast<int>(p.x * grid.cols / size.width), 0, grid.cols - 1);
      const int r = std::clamp(static_cast<int>(p.y * grid.rows / size.height), 0, grid.rows - 1);
      hit[static_cast<std::size_t>(r * grid.cols + c)] = true;
    }
    for (std::size_t i = 0; i < hit.size(); ++i) grid.views[i] += hit[i] ? 1 : 0;
  }
  return grid;
}

// |y_left - y_right| of every kept corner after rectification: what the rectified pair's rows
// disagree by, whatever the reprojection error says.
void epipolar_error(StereoBoardCalibration& c, const Fit& fit) {
  cv::Mat R1, R2, P1, P2, Q;
  cv::stereoRectify(fit.K1, fit.D1, fit.K2, fit.D2, c.image_size, fit.R, fit.T, R1, R2, P1, P2, Q,
                    cv::CALIB_ZERO_DISPARITY, 0);
  double sum2 = 0.0, worst = 0.0;
  std::size_t n = 0;
  for (std::size_t v = 0; v < c.kept_left_px.size(); ++v) {
    std::vector<cv::Point2f> l, r;
    cv::undistortPoints(c.kept_left_px[v], l, fit.K1, fit.D1, R1, P1);
    cv::undistortPoints(c.kept_right_px[v], r, fit.K2, fit.D2, R2, P2);
    for (std::size_t i = 0; i < l.size(); ++i) {
      const double dy = std::abs(l[i].y - r[i].y);
      sum2 += dy * dy;
      worst = std::max(worst, dy);
      ++n;
    }
  }
  c.epipolar_rms_px = n > 0 ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
  c.epipolar_max_px = worst;
}

void judge_uncertainty(StereoBoardCalibration& c, const Fit& fit, const CalibrationLimits& limits) {
  char text[200];
  for (const cv::Mat* sigma : {&fit.sigma1, &fit.sigma2}) {
    const cv::Mat& K = sigma == &fit.sigma1 ? fit.K1 : fit.K2;
    c.sigma_fx_pct = std::max(c.sigma_fx_pct, 100.0 * sigma->at<double>(0) / K.at<double>(0, 0));
    c.sigma_fy_pct = std::max(c.sigma_fy_pct, 100.0 * sigma->at<double>(1) / K.at<double>(1, 1));
    c.sigma_c_px = std::max({c.sigma_c_px, sigma->at<double>(2), sigma->at<double>(3)});
  }
  if (std::max(c.sigma_fx_pct, c.sigma_fy_pct) > 0.15 || c.sigma_c_px > 1.0) {
    std::snprintf(text, sizeof text,
                  "focal length or principal point loosely held (1 sigma: fx %.2f %%, fy %.2f %%, "
                  "centre %.1f px): add views tilted and near the image corners",
                  c.sigma_fx_pct, c.sigma_fy_pct, c.sigma_c_px);
    c.uncertain.emplace_back(text);
  }
  const double cover = std::min(c.coverage_left.fraction(), c.coverage_right.fraction());
  if (cover < limits.uncertain_coverage) {
    std::snprintf(text, sizeof text,
                  "the boards cover %.0f %% of the image (below %.0f %%): the distortion near the "
                  "uncovered cells is extrapolated",
                  100.0 * cover, 100.0 * limits.uncertain_coverage);
    c.uncertain.emplace_back(text);
  }
  const int tilted = std::accumulate(c.tilt_histogram.begin() + 2, c.tilt_histogram.end(), 0);
  if (tilted < 3) {
    c.uncertain.emplace_back(
        "fewer than 3 views tilted 20 degrees or more: focal length and distance trade off");
  }
  if (c.rms_px > 1.0) {
    std::snprintf(text, sizeof text, "reprojection RMS %.2f px is over 1 px", c.rms_px);
    c.uncertain.emplace_back(text);
  }
}

std::string refusal_of(const StereoBoardCalibration& c, const CalibrationLimits& limits) {
  char text[240];
  if (c.views_used < limits.min_views) {
    std::snprintf(text, sizeof text,
                  "too few views: %d usable of %zu, at least %d needed (record more pairs of the "
                  "board, whole in both images)",
                  c.views_used, c.views.size(), limits.min_views);
    return text;
  }
  const double left = c.coverage_left.fraction(), right = c.coverage_right.fraction();
  if (std::min(left, right) < limits.min_coverage) {
    std::snprintf(text, sizeof text,
                  "too little of the image covered: %.0f %% of the left and %.0f %% of the right "
                  "image's cells, at least %.0f %% needed for the distortion to be known (move "
                  "the board into the empty cells of the coverage table)",
                  100.0 * left, 100.0 * right, 100.0 * limits.min_coverage);
    return text;
  }
  return "";
}

}  // namespace

StereoBoardCalibration calibrate_stereo_board(const std::vector<BoardView>& views,
                                              cv::Size image_size, const BoardSpec& board,
                                              const CalibrationLimits& limits) {
  StereoBoardCalibration c;
  c.image_size = image_size;
  std::vector<std::size_t> kept;  // indices into views
  for (std::size_t i = 0; i < views.size(); ++i) {
    ViewOutcome o;
    o.name = views[i].name;
    o.reason = views[i].reason;
    if (o.reason.empty()) kept.push_back(i);
    c.views.push_back(o);
  }
  c.views_used = static_cast<int>(kept.size());
  if (c.views_used < limits.min_views) {
    c.refusal = refusal_of(c, limits);
    return c;
  }
  Fit fit;
  const std::size_t max_drops = kept.size() / 4;
  for (std::size_t drops = 0;; ++drops) {
    c.kept_left_px.clear();
    c.kept_right_px.clear();
    for (std::size_t i : kept) {
      c.kept_left_px.push_back(views[i].left_px);
      c.kept_right_px.push_back(views[i].right_px);
    }
    fit = fit_views(c.kept_left_px, c.kept_right_px, image_size, board);
    double median = 0, limit = 0;
    const int worst = outlier_index(fit.view_error_px, median, limit);
    if (worst < 0 || drops >= max_drops || static_cast<int>(kept.size()) <= limits.min_views) break;
    ViewOutcome& o = c.views[kept[static_cast<std::size_t>(worst)]];
    char text[200];
    std::snprintf(text, sizeof text,
                  "outlier: reprojection %.2f px against the views' median %.2f px (limit %.2f px)",
                  fit.view_error_px[static_cast<std::size_t>(worst)], median, limit);
    o.reason = text;
    o.error_px = fit.view_error_px[static_cast<std::size_t>(worst)];
    kept.erase(kept.begin() + worst);
  }
  c.views_used = static_cast<int>(kept.size());
  c.tilt_histogram.assign(std::size(kTiltBandsDeg) + 1, 0);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    ViewOutcome& o = c.views[kept[k]];
    o.kept = true;
    o.error_px = fit.view_error_px[k];
    o.tilt_deg = fit.tilt_deg[k];
    const auto band =
        std::upper_bound(std::begin(kTiltBandsDeg), std::end(kTiltBandsDeg), o.tilt_deg) -
        std::begin(kTiltBandsDeg);
    ++c.tilt_histogram[static_cast<std::size_t>(band)];
  }
  c.rig.left = camera_of(fit.K1, fit.D1, image_size);
  c.rig.right = camera_of(fit.K2, fit.D2, image_size);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) R(r, col) = fit.R.at<double>(r, col);
  }
  c.rig.T_cr_cl.linear() = R;
  c.rig.T_cr_cl.translation() =
      Eigen::Vector3d(fit.T.at<double>(0), fit.T.at<double>(1), fit.T.at<double>(2));
  c.rms_px = fit.rms;
  c.rms_left_px = fit.rms_left;
  c.rms_right_px = fit.rms_right;
  c.coverage_left = coverage_of(c.kept_left_px, image_size, limits);
  c.coverage_right = coverage_of(c.kept_right_px, image_size, limits);
  epipolar_error(c, fit);
  judge_uncertainty(c, fit, limits);
  c.refusal = refusal_of(c, limits);
  return c;
}

std::string calibration_yaml(const StereoBoardCalibration& c, const std::string& board_text,
                             const std::string& date_utc) {
  cv::FileStorage fs(
      ".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "image_size" << std::vector<int>{c.image_size.width, c.image_size.height};
  estimator::write_stereo_rig(fs, c.rig);
  fs << "T_unit"
     << "m";
  fs << "rms_reprojection_px" << c.rms_px;
  fs << "epipolar_rms_px" << c.epipolar_rms_px;
  fs << "epipolar_max_px" << c.epipolar_max_px;
  fs << "views_used" << c.views_used;
  fs << "board" << board_text;
  fs << "calibrated_utc" << date_utc;
  std::string text = fs.releaseAndGetString();
  const std::string header = "---\n";
  const std::size_t at = text.find(header);
  const std::string comment =
      "# Written by rovctl calibrate. OpenCV's stereoCalibrate convention: x_right = R * x_left "
      "+ T,\n# T in metres (the board's squares were given in mm). D: k1 k2 p1 p2 k3.\n";
  if (at != std::string::npos) text.insert(at + header.size(), comment);
  return text;
}

std::string coverage_table(const CoverageGrid& grid) {
  std::string out;
  for (int r = 0; r < grid.rows; ++r) {
    out += "   ";
    for (int c = 0; c < grid.cols; ++c) {
      char cell[8];
      std::snprintf(cell, sizeof cell, "%4d",
                    grid.views[static_cast<std::size_t>(r * grid.cols + c)]);
      out += cell;
    }
    out += "\n";
  }
  return out;
}

namespace {

void draw_coverage(cv::Mat& canvas, const CoverageGrid& grid,
                   const std::vector<std::vector<cv::Point2f>>& boards) {
  const int w = canvas.cols, h = canvas.rows;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const int n = grid.views[static_cast<std::size_t>(r * grid.cols + c)];
      const cv::Rect cell(c * w / grid.cols, r * h / grid.rows, w / grid.cols, h / grid.rows);
      // Red: no view; green deepening with the views in the cell.
      const cv::Scalar colour =
          n == 0 ? cv::Scalar(60, 60, 200) : cv::Scalar(60, 120 + std::min(n, 9) * 15, 60);
      cv::rectangle(canvas, cell, colour, cv::FILLED);
      cv::rectangle(canvas, cell, cv::Scalar(30, 30, 30), 1);
      cv::putText(canvas, std::to_string(n), cell.tl() + cv::Point(4, 16), cv::FONT_HERSHEY_SIMPLEX,
                  0.45, cv::Scalar(255, 255, 255), 1);
    }
  }
  for (const auto& corners : boards) {
    std::vector<cv::Point2f> hull32;
    cv::convexHull(corners, hull32);
    std::vector<cv::Point> hull(hull32.begin(), hull32.end());
    cv::polylines(canvas, hull, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
}

}  // namespace

cv::Mat coverage_picture(const StereoBoardCalibration& c) {
  cv::Mat picture(c.image_size.height, 2 * c.image_size.width, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::Mat left = picture(cv::Rect(0, 0, c.image_size.width, c.image_size.height));
  cv::Mat right = picture(cv::Rect(c.image_size.width, 0, c.image_size.width, c.image_size.height));
  draw_coverage(left, c.coverage_left, c.kept_left_px);
  draw_coverage(right, c.coverage_right, c.kept_right_px);
  cv::putText(picture, "left", cv::Point(8, c.image_size.height - 10), cv::FONT_HERSHEY_SIMPLEX,
              0.7, cv::Scalar(255, 255, 255), 2);
  cv::putText(picture, "right", cv::Point(c.image_size.width + 8, c.image_size.height - 10),
              cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(255, 255, 255), 2);
  return picture;
}

}  // namespace rovctl::app
