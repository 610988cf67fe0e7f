// Marker colours learnt from the water they will be seen in: locate the spheres in recorded
// pairs with the project's own estimator, measure each sphere's hue, saturation and value as
// the segmenter sees them, propose hue windows and floors with a margin, and judge whether each
// colour can be told from the background. The marker's geometry is never changed.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "estimator/estimator_params.hpp"
#include "hal/model/marker_model.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct ColourTuningOptions {
  int frames = 10;         // estimator frames per pair (a still camera) when locating
  std::uint64_t seed = 1;  // the GA's seed, per pair offset by the pair's index
  // The proposed hue window spans the sphere pixels' 3rd to 97th percentile plus this each side.
  double hue_margin_deg = 8.0;
  // The floors sit at this fraction of the sphere pixels' 10th percentile.
  double floor_fraction = 0.7;
  // Refused when a sphere's inner disc gets its own colour in less than 80 % of its pixels with
  // the proposed windows (it is taken for another sphere), or when, over the located views, the
  // background pixels the proposed window takes for a
  // colour exceed this fraction of that colour's sphere pixels it takes.
  double max_background_fraction = 0.25;
  // Refused when a sphere's hues spread wider than this (3rd to 97th percentile): it has no
  // colour of its own in this water.
  double max_hue_spread_deg = 90.0;
  // The marker's ranges from the camera the windows must hold over. A sphere's hue drifts with
  // range as the water's cast grows over its colour; beyond the recording's ranges the windows
  // follow that drift (measured on the recording) out to these, and the report says the
  // recording falls short of them.
  double range_near_m = 0.3, range_far_m = 1.5;
};

// How a pair's spheres were found, first that worked: the configured windows; each window widened
// 20 then 40 deg each side (never into a neighbour's half of the hue circle) with low floors; one
// sphere's window slid round the hue circle. Each time the estimator had to be ok (every sphere
// seen in both views where the marker's geometry puts it, refined, bound within limits).
struct PairLocation {
  std::string name;  // the pair's left image, relative to the recording
  bool located = false;
  std::string how;  // which windows located it
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
};

// One sphere's colour over every located view, as the segmenter sees it (water_correction's
// gains applied), in degrees (p3 may exceed p97 when the spread wraps through 0). So that the
// window holds the sphere in every view, near or far, p3 / p97 / the p10s are the extremes over
// the views of each view's percentile; the p50s are over all the pixels.
struct SphereSpread {
  std::string name;
  long pixels = 0;
  double hue_p3_deg = 0, hue_p50_deg = 0, hue_p97_deg = 0;
  double saturation_p10 = 0, saturation_p50 = 0;
  double value_p10 = 0, value_p50 = 0;
  // The sphere's ranges over the views that set the extremes, and how each view's p3 and p97
  // move with range (least squares, deg per metre; 0 when the views span under 0.2 m).
  double range_min_m = 0, range_max_m = 0;
  double hue_low_drift_deg_per_m = 0, hue_high_drift_deg_per_m = 0;
  // What the window is built on: p3 / p97, extended over the working range by the drift (a line
  // of that slope under every view's p3, over every view's p97, read at the range's ends).
  double hue_low_deg = 0, hue_high_deg = 0;
};

// Per colour, over the located views: the share of the sphere's inner disc labelled its colour,
// and the background pixels (outside every sphere) labelled that colour, per view.
struct ColourCounts {
  std::string name;
  double inside_before = 0, inside_after = 0;                      // fraction of the disc
  double outside_per_view_before = 0, outside_per_view_after = 0;  // pixels
  double background_fraction_after = 0;  // background / sphere pixels the tuned window takes
};

struct StereoImages {
  std::string name;
  cv::Mat left, right;  // 8-bit BGR
};

struct ColourTuningResult {
  bool refused = false;
  std::string reason;  // why, when refused
  std::vector<PairLocation> pairs;
  std::vector<SphereSpread> spreads;
  std::vector<ColourCounts> counts;
  hal::MarkerModel tuned;          // the configured marker with the proposed windows and floors
  std::vector<std::string> notes;  // what the report should say beside the figures
  // The located pairs' marker ranges from the left camera, and whether they reach the working
  // range's ends (within 0.1 m); the notes say what falls short.
  double located_range_min_m = 0, located_range_max_m = 0;
  bool covers_near = false, covers_far = false;
  int located() const;
};

// Locates, measures and proposes. Never throws on the images' content: a recording in which the
// marker cannot be told apart comes back refused with the reason.
ColourTuningResult tune_marker_colours(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                                       const estimator::EstimatorParams& params,
                                       const std::vector<StereoImages>& pairs,
                                       const ColourTuningOptions& options);

// One view's hue extremes of a sphere (p3 and p97, as offsets in degrees from any fixed hue) at the
// sphere's range from that view's camera.
struct RangedHueExtremes {
  double range_m = 0, low_deg = 0, high_deg = 0;
};

// How the extremes drift with range: the least-squares slope of the lows and of the highs (0 when
// fewer than 3 views or the views span under 0.2 m), and the lowest low / highest high over the
// views and over the working range [near_m, far_m], read off lines of those slopes drawn under
// every low and over every high.
struct HueDrift {
  double low_drift_deg_per_m = 0, high_drift_deg_per_m = 0;
  double low_deg = 0, high_deg = 0;
  double range_min_m = 0, range_max_m = 0;  // the views'
};
HueDrift hue_drift_over_range(const std::vector<RangedHueExtremes>& views, double near_m,
                              double far_m);

// The marker with every window widened by `widen_deg` each side (capped at half the way to each
// neighbour's centre) and floors lowered to at most `saturation_min` / `value_min`.
hal::MarkerModel widened_marker(const hal::MarkerModel& marker, double widen_deg,
                                double saturation_min, double value_min);

// The `marker:` section with the tuned colours and the configured geometry, as YAML a config
// takes; `header` goes first as comment lines.
std::string marker_fragment_yaml(const hal::MarkerModel& tuned, const std::string& header);

// One view's figure: the image, its labels with the configured windows and with the tuned ones,
// side by side, the located spheres outlined.
cv::Mat segmentation_figure(const hal::CameraModel& camera, const Eigen::Isometry3d& T_cam_marker,
                            const hal::MarkerModel& marker, const cv::Mat& image,
                            const cv::Mat& labels_before, const cv::Mat& labels_after);

}  // namespace rovctl::app
