// Stereo calibration from chessboard views: corners per image (or the named reason a view is left
// out), per-camera then stereo fit with outlier views dropped, coverage of each image and board
// tilts, and the refusal when the views cannot pin the lenses down.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/tools/board_spec.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

// The board's inner corners in one stereo pair, or why the pair cannot be used.
struct BoardView {
  std::string name;  // the pair's file name, as the report names it
  std::vector<cv::Point2f> left_px, right_px;
  std::string reason;        // empty: usable
  double edge_width_px = 0;  // the blurrier image's board edge width (10-90 %), 0 if unseen
};

struct CalibrationLimits {
  int min_views = 10;                // kept views below this: refused
  double min_coverage = 0.5;         // covered grid cells below this fraction: refused
  double uncertain_coverage = 0.75;  // ... below this: uncertain
  double max_edge_width_px = 3.5;    // blurrier than this: no sub-pixel corners
  int grid_cols = 8, grid_rows = 6;  // coverage cells per image
};

// Corners in both images of one pair, with sub-pixel refinement, or a reason.
BoardView detect_board_view(const std::string& name, const cv::Mat& left_bgr,
                            const cv::Mat& right_bgr, const BoardSpec& board,
                            const CalibrationLimits& limits);

struct ViewOutcome {
  std::string name;
  bool kept = false;
  std::string reason;     // why it was left out
  double error_px = 0.0;  // stereo reprojection RMS of the view (kept or dropped as outlier)
  double tilt_deg = 0.0;  // board normal against the left optical axis
};

struct CoverageGrid {
  int cols = 0, rows = 0;
  std::vector<int> views;  // per cell (row-major): kept views with a corner in it
  double fraction() const;
};

struct StereoBoardCalibration {
  hal::StereoRig rig;
  cv::Size image_size;
  std::vector<ViewOutcome> views;
  int views_used = 0;
  double rms_px = 0.0;  // stereo fit, both cameras
  double rms_left_px = 0.0, rms_right_px = 0.0;
  double epipolar_rms_px = 0.0, epipolar_max_px = 0.0;  // |y_left - y_right| after rectifying
  double sigma_fx_pct = 0.0, sigma_fy_pct = 0.0, sigma_c_px = 0.0;  // worse camera, 1 sigma
  CoverageGrid coverage_left, coverage_right;
  std::vector<int> tilt_histogram;     // views per band of kTiltBandsDeg
  std::vector<std::string> uncertain;  // why the answer may be off (empty: none)
  std::string refusal;                 // non-empty: no calibration is to be written
  std::vector<std::vector<cv::Point2f>> kept_left_px, kept_right_px;  // for the picture
};

inline constexpr double kTiltBandsDeg[] = {10.0, 20.0, 30.0, 45.0};  // edges: <10, 10-20, ... >45

StereoBoardCalibration calibrate_stereo_board(const std::vector<BoardView>& views,
                                              cv::Size image_size, const BoardSpec& board,
                                              const CalibrationLimits& limits);

// The calibration file as estimator/stereo_calibration reads it, with the figures as keys.
std::string calibration_yaml(const StereoBoardCalibration& c, const std::string& board_text,
                             const std::string& date_utc);
// Left and right image side by side: the coverage grid shaded by views, each kept board outlined.
cv::Mat coverage_picture(const StereoBoardCalibration& c);
// The coverage grid as text, one row of view counts per grid row.
std::string coverage_table(const CoverageGrid& grid);

}  // namespace rovctl::app
