// Locating the spheres with the estimator, measuring their colours through the segmenter's own
// white balance, and proposing windows that hold the spheres but not the background.
#include "app/tools/marker_colour_tuning.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "estimator/hue_segmenter.hpp"
#include "estimator/pose_estimator.hpp"

namespace rovctl::app {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Widening steps tried, in order, when the configured windows do not locate a pair: enough to
// follow a cast that moves a sphere's hue by up to about 40 degrees.
constexpr double kWidenStepsDeg[] = {0.0, 20.0, 40.0};
// The floors while locating with widened windows: low enough for a sphere greyed by the water.
constexpr double kLocateSaturationMin = 0.1;
constexpr double kLocateValueMin = 0.06;
// Measured inside this fraction of a sphere's projected radius (its rim mixes with the
// background); the background is everything outside kBackgroundRadius of every sphere.
constexpr double kMeasureRadius = 0.7;
constexpr double kBackgroundRadius = 1.6;

double wrap_deg(double a) {
  a = std::fmod(a, 360.0);
  return a < 0.0 ? a + 360.0 : a;
}

// Signed difference a - b in (-180, 180].
double hue_difference_deg(double a, double b) {
  double d = wrap_deg(a - b);
  return d > 180.0 ? d - 360.0 : d;
}

struct Hsv {
  double hue_deg = 0, saturation = 0, value = 0;
};

// The segmenter's HSV (HueSegmenter::classify_exact) with its numbers kept.
Hsv hsv_of(double b, double g, double r) {
  Hsv out;
  const double mx = std::max({r, g, b});
  const double mn = std::min({r, g, b});
  const double chroma = mx - mn;
  out.value = mx / 255.0;
  if (mx <= 0.0 || chroma <= 0.0) return out;
  out.saturation = chroma / mx;
  if (mx == r) {
    out.hue_deg = 60.0 * std::fmod((g - b) / chroma + 6.0, 6.0);
  } else if (mx == g) {
    out.hue_deg = 60.0 * ((b - r) / chroma + 2.0);
  } else {
    out.hue_deg = 60.0 * ((r - g) / chroma + 4.0);
  }
  return out;
}

double window_centre_deg(const hal::MarkerSphere& s) {
  const double width = wrap_deg(s.hue_max_deg - s.hue_min_deg);
  return wrap_deg(s.hue_min_deg + width / 2.0);
}

double window_half_deg(const hal::MarkerSphere& s) {
  return wrap_deg(s.hue_max_deg - s.hue_min_deg) / 2.0;
}

struct Disc {
  cv::Point2d centre_px;
  double radius_px = 0.0;
  bool whole = false;  // every pixel of the disc (at kBackgroundRadius) inside the image
};

std::vector<Disc> sphere_discs(const hal::CameraModel& camera,
                               const Eigen::Isometry3d& T_cam_marker,
                               const hal::MarkerModel& marker) {
  std::vector<Disc> discs;
  for (const hal::MarkerSphere& s : marker.spheres) {
    Disc d;
    const Eigen::Vector3d c = T_cam_marker * s.centre_marker_m;
    Eigen::Vector2d uv;
    if (camera.project(c, uv)) {
      d.centre_px = {uv.x(), uv.y()};
      d.radius_px = camera.fx_px * s.radius_m / c.z();
      const double reach = kBackgroundRadius * d.radius_px;
      d.whole = uv.x() - reach >= 0 && uv.y() - reach >= 0 && uv.x() + reach < camera.width_px &&
                uv.y() + reach < camera.height_px;
    }
    discs.push_back(d);
  }
  return discs;
}

bool in_disc(const Disc& d, int u, int v, double fraction) {
  const double du = u - d.centre_px.x, dv = v - d.centre_px.y;
  const double r = fraction * d.radius_px;
  return du * du + dv * dv <= r * r;
}

struct View {
  const cv::Mat* image = nullptr;
  const hal::CameraModel* camera = nullptr;
  Eigen::Isometry3d T_cam_marker = Eigen::Isometry3d::Identity();
  std::vector<Disc> discs;
};

std::vector<View> located_views(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                                const std::vector<StereoImages>& pairs,
                                const std::vector<PairLocation>& where) {
  std::vector<View> views;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!where[i].located) continue;
    for (int side = 0; side < 2; ++side) {
      View v;
      v.image = side == 0 ? &pairs[i].left : &pairs[i].right;
      v.camera = side == 0 ? &rig.left : &rig.right;
      v.T_cam_marker = side == 0 ? where[i].T_cl_marker : rig.T_cr_cl * where[i].T_cl_marker;
      v.discs = sphere_discs(*v.camera, v.T_cam_marker, marker);
      views.push_back(v);
    }
  }
  return views;
}

bool ok_after(const hal::StereoRig& rig, const hal::MarkerModel& marker,
              const estimator::EstimatorParams& params, const StereoImages& pair,
              std::uint64_t seed, int frames, Eigen::Isometry3d& T_cl_marker) {
  estimator::PoseEstimator est(rig, marker, params, seed);
  estimator::PoseEstimate e;
  for (int f = 0; f < frames; ++f) e = est.update(pair.left, pair.right);
  if (e.ok) T_cl_marker = e.T_cl_marker;
  return e.ok;
}

// The last resort, for a cast that moved one sphere's hue far from its window: that sphere's
// window slid round the hue circle (kSlideHalfDeg each side, low floors, never within
// kSlideClearDeg of another sphere's centre), the others widened by the first step. Only an ok
// estimate counts, so the three spheres must fit the marker's geometry in both views.
constexpr double kSlideStepDeg = 10.0;
constexpr double kSlideHalfDeg = 25.0;
constexpr double kSlideClearDeg = 35.0;

bool locate_by_sliding(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                       const estimator::EstimatorParams& params, const StereoImages& pair,
                       std::uint64_t seed, int frames, PairLocation& out) {
  const hal::MarkerModel base =
      widened_marker(marker, kWidenStepsDeg[1], kLocateSaturationMin, kLocateValueMin);
  for (std::size_t i = 0; i < marker.spheres.size(); ++i) {
    for (double c = 0.0; c < 360.0; c += kSlideStepDeg) {
      bool clear = true;
      for (std::size_t j = 0; j < marker.spheres.size(); ++j) {
        const double d = hue_difference_deg(c, window_centre_deg(marker.spheres[j]));
        clear = clear && (j == i || std::abs(d) >= kSlideClearDeg);
      }
      if (!clear) continue;
      hal::MarkerModel m = base;
      m.spheres[i].hue_min_deg = wrap_deg(c - kSlideHalfDeg);
      m.spheres[i].hue_max_deg = wrap_deg(c + kSlideHalfDeg);
      if (ok_after(rig, m, params, pair, seed, frames, out.T_cl_marker)) {
        char how[96];
        std::snprintf(how, sizeof how, "the %s window slid to %.0f+-%.0f deg",
                      marker.spheres[i].name.c_str(), c, kSlideHalfDeg);
        out.how = how;
        return true;
      }
    }
  }
  return false;
}

PairLocation locate_pair(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                         estimator::EstimatorParams params, const StereoImages& pair,
                         std::uint64_t seed, int frames) {
  // Locating needs the improved mode's ok (refined, bounded): the paper's GA alone has no bound.
  params.mode = "improved";
  PairLocation out;
  out.name = pair.name;
  for (const double widen : kWidenStepsDeg) {
    const hal::MarkerModel m =
        widen == 0.0 ? marker
                     : widened_marker(marker, widen, kLocateSaturationMin, kLocateValueMin);
    if (ok_after(rig, m, params, pair, seed, frames, out.T_cl_marker)) {
      out.located = true;
      char how[96];
      std::snprintf(how, sizeof how, "windows widened %.0f deg each side, low floors", widen);
      out.how = widen == 0.0 ? "the configured windows" : how;
      return out;
    }
  }
  out.located = locate_by_sliding(rig, marker, params, pair, seed, frames, out);
  return out;
}

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return std::nan("");
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(p / 100.0 * v.size()));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

struct Samples {
  std::vector<double> hue_deg, saturation, value;
  std::vector<std::size_t> view_start;  // where each view's pixels begin
  std::vector<double> view_range_m;     // the sphere's distance from that view's camera
};

// Each sphere's pixels in every located view where it is whole, through the segmenter's gains.
std::vector<Samples> sample_spheres(const hal::MarkerModel& marker, double water_correction,
                                    const std::vector<View>& views) {
  std::vector<Samples> samples(marker.spheres.size());
  estimator::HueSegmenter segmenter(marker, water_correction);
  cv::Mat labels;
  for (const View& view : views) {
    segmenter.segment(*view.image, labels);
    const std::array<double, 3> gain = segmenter.gains();
    for (std::size_t s = 0; s < view.discs.size(); ++s) {
      const Disc& d = view.discs[s];
      if (!d.whole) continue;
      samples[s].view_start.push_back(samples[s].hue_deg.size());
      samples[s].view_range_m.push_back(
          (view.T_cam_marker * marker.spheres[s].centre_marker_m).norm());
      const int r = static_cast<int>(std::ceil(d.radius_px));
      for (int v = static_cast<int>(d.centre_px.y) - r; v <= d.centre_px.y + r; ++v) {
        for (int u = static_cast<int>(d.centre_px.x) - r; u <= d.centre_px.x + r; ++u) {
          if (!in_disc(d, u, v, kMeasureRadius)) continue;
          const cv::Vec3b p = view.image->at<cv::Vec3b>(v, u);
          double c[3];
          for (int k = 0; k < 3; ++k) c[k] = std::min(255.0, std::round(gain[k] * p[k]));
          const Hsv hsv = hsv_of(c[0], c[1], c[2]);
          samples[s].hue_deg.push_back(hsv.hue_deg);
          samples[s].saturation.push_back(hsv.saturation);
          samples[s].value.push_back(hsv.value);
        }
      }
    }
  }
  return samples;
}

// A view's sphere with fewer pixels than this adds to the pooled figures but sets no extreme.
constexpr std::size_t kMinViewPixels = 20;

// The window must hold the sphere in every view, near or far (a far sphere has few pixels and
// would vanish in pooled percentiles): the extremes are the lowest 3rd and highest 97th hue
// percentile, and the lowest 10th saturation and value percentile, over the views.
// Views spanning less than this in range give no drift: the slope would be noise.
constexpr double kMinDriftSpanM = 0.2;

SphereSpread spread_of(const std::string& name, Samples& s, const ColourTuningOptions& options) {
  SphereSpread out;
  out.name = name;
  out.pixels = static_cast<long>(s.hue_deg.size());
  if (s.hue_deg.empty()) return out;
  // Hue is an angle: percentiles of the offsets from the circular mean.
  double sx = 0, sy = 0;
  for (double h : s.hue_deg) {
    sx += std::cos(h * kPi / 180.0);
    sy += std::sin(h * kPi / 180.0);
  }
  const double mean_hue_deg = wrap_deg(std::atan2(sy, sx) * 180.0 / kPi);
  std::vector<double> offsets;
  offsets.reserve(s.hue_deg.size());
  for (double h : s.hue_deg) offsets.push_back(hue_difference_deg(h, mean_hue_deg));
  double low = 180.0, high = -180.0, sat = 1.0, val = 1.0;
  std::vector<RangedHueExtremes> extremes;
  s.view_start.push_back(offsets.size());
  for (std::size_t k = 0; k + 1 < s.view_start.size(); ++k) {
    const auto a = static_cast<long>(s.view_start[k]), b = static_cast<long>(s.view_start[k + 1]);
    if (b - a < static_cast<long>(kMinViewPixels)) continue;
    std::vector<double> o(offsets.begin() + a, offsets.begin() + b);
    std::vector<double> sv(s.saturation.begin() + a, s.saturation.begin() + b);
    std::vector<double> vv(s.value.begin() + a, s.value.begin() + b);
    extremes.push_back({s.view_range_m[k], percentile(o, 3), percentile(o, 97)});
    low = std::min(low, extremes.back().low_deg);
    high = std::max(high, extremes.back().high_deg);
    sat = std::min(sat, percentile(sv, 10));
    val = std::min(val, percentile(vv, 10));
  }
  if (high < low) return SphereSpread{name, 0};  // no view with enough of the sphere
  out.hue_p3_deg = wrap_deg(mean_hue_deg + low);
  out.hue_p50_deg = wrap_deg(mean_hue_deg + percentile(offsets, 50));
  out.hue_p97_deg = wrap_deg(mean_hue_deg + high);
  const HueDrift drift = hue_drift_over_range(extremes, options.range_near_m, options.range_far_m);
  low = drift.low_deg;
  high = drift.high_deg;
  out.range_min_m = drift.range_min_m;
  out.range_max_m = drift.range_max_m;
  out.hue_low_drift_deg_per_m = drift.low_drift_deg_per_m;
  out.hue_high_drift_deg_per_m = drift.high_drift_deg_per_m;
  // Never past half the circle from the mean: the spread check refuses long before.
  out.hue_low_deg = wrap_deg(mean_hue_deg + std::max(low, -179.0));
  out.hue_high_deg = wrap_deg(mean_hue_deg + std::min(high, 179.0));
  out.saturation_p10 = sat;
  out.saturation_p50 = percentile(s.saturation, 50);
  out.value_p10 = val;
  out.value_p50 = percentile(s.value, 50);
  return out;
}

// Rounded to what a config reader needs: a tenth of a degree, a hundredth of a floor.
double round_to(double x, double step) { return std::round(x / step) * step; }

// Each window spans its sphere's spread plus the margin, but stops halfway to a neighbouring
// sphere's spread; spreads that overlap leave no room and are refused (refusal()).
void propose(const std::vector<SphereSpread>& spreads, const ColourTuningOptions& options,
             hal::MarkerModel& tuned) {
  for (std::size_t i = 0; i < spreads.size(); ++i) {
    const SphereSpread& s = spreads[i];
    if (s.pixels == 0) continue;
    double below = options.hue_margin_deg, above = options.hue_margin_deg;
    for (std::size_t j = 0; j < spreads.size(); ++j) {
      if (j == i || spreads[j].pixels == 0) continue;
      // The free hue between this spread's top and the other's bottom, and the other way round.
      const double gap_above = wrap_deg(spreads[j].hue_low_deg - s.hue_high_deg);
      const double gap_below = wrap_deg(s.hue_low_deg - spreads[j].hue_high_deg);
      if (gap_above < 180.0) above = std::min(above, gap_above / 2.0);
      if (gap_below < 180.0) below = std::min(below, gap_below / 2.0);
    }
    hal::MarkerSphere& sphere = tuned.spheres[i];
    sphere.hue_min_deg = round_to(wrap_deg(s.hue_low_deg - below), 0.1);
    sphere.hue_max_deg = round_to(wrap_deg(s.hue_high_deg + above), 0.1);
    if (sphere.hue_min_deg >= 360.0) sphere.hue_min_deg = 0.0;
    if (sphere.hue_max_deg >= 360.0) sphere.hue_max_deg = 0.0;
    sphere.saturation_min = round_to(options.floor_fraction * s.saturation_p10, 0.01);
    sphere.value_min = round_to(options.floor_fraction * s.value_p10, 0.01);
  }
}

// Sphere and background pixels labelled each colour, with one marker's windows.
struct Tally {
  std::vector<long> inside_hits, inside_total, outside;
};

Tally tally(const hal::MarkerModel& marker, double water_correction,
            const std::vector<View>& views) {
  const std::size_t n = marker.spheres.size();
  Tally t{std::vector<long>(n, 0), std::vector<long>(n, 0), std::vector<long>(n, 0)};
  estimator::HueSegmenter segmenter(marker, water_correction);
  cv::Mat labels;
  for (const View& view : views) {
    segmenter.segment(*view.image, labels);
    for (int v = 0; v < labels.rows; ++v) {
      const std::uint8_t* row = labels.ptr<std::uint8_t>(v);
      for (int u = 0; u < labels.cols; ++u) {
        bool near_sphere = false;
        for (std::size_t s = 0; s < n; ++s) {
          const Disc& d = view.discs[s];
          if (d.whole && in_disc(d, u, v, kMeasureRadius)) {
            ++t.inside_total[s];
            if (row[u] == static_cast<std::uint8_t>(marker.spheres[s].colour)) ++t.inside_hits[s];
          }
          near_sphere = near_sphere || in_disc(d, u, v, kBackgroundRadius);
        }
        if (near_sphere || row[u] == 0) continue;
        for (std::size_t s = 0; s < n; ++s) {
          if (row[u] == static_cast<std::uint8_t>(marker.spheres[s].colour)) ++t.outside[s];
        }
      }
    }
  }
  return t;
}

std::vector<ColourCounts> counts_of(const hal::MarkerModel& before, const hal::MarkerModel& after,
                                    double water_correction, const std::vector<View>& views) {
  const Tally b = tally(before, water_correction, views);
  const Tally a = tally(after, water_correction, views);
  std::vector<ColourCounts> out;
  const double n_views = std::max<std::size_t>(1, views.size());
  for (std::size_t s = 0; s < before.spheres.size(); ++s) {
    ColourCounts c;
    c.name = before.spheres[s].name;
    const double total = std::max<long>(1, b.inside_total[s]);
    c.inside_before = b.inside_hits[s] / total;
    c.inside_after = a.inside_hits[s] / total;
    c.outside_per_view_before = b.outside[s] / n_views;
    c.outside_per_view_after = a.outside[s] / n_views;
    c.background_fraction_after = static_cast<double>(a.outside[s]) /
                                  static_cast<double>(std::max<long>(1, a.inside_hits[s]));
    out.push_back(c);
  }
  return out;
}

// With the proposed windows at least this share of each sphere's inner disc must get its colour.
constexpr double kMinOwnShare = 0.8;

// Two spheres' hue spreads share hues: there only the floors (and the segmenter's order: the
// first sphere whose window and floors a pixel meets) tell them apart.
bool spreads_overlap(const SphereSpread& a, const SphereSpread& b) {
  auto inside = [](double h, const SphereSpread& s) {
    return wrap_deg(h - s.hue_low_deg) <= wrap_deg(s.hue_high_deg - s.hue_low_deg);
  };
  return inside(a.hue_low_deg, b) || inside(a.hue_high_deg, b) || inside(b.hue_low_deg, a);
}

std::string refusal(const ColourTuningResult& r, const ColourTuningOptions& options) {
  char text[400];
  for (const SphereSpread& s : r.spreads) {
    const double spread = wrap_deg(s.hue_p97_deg - s.hue_p3_deg);
    if (s.pixels == 0) return "the " + s.name + " sphere was never whole in a located view";
    if (spread > options.max_hue_spread_deg) {
      std::snprintf(text, sizeof text,
                    "the %s sphere's hues spread over %.0f deg (3rd to 97th percentile), more than "
                    "%.0f: it has no colour of its own in this water",
                    s.name.c_str(), spread, options.max_hue_spread_deg);
      return text;
    }
  }
  for (const ColourCounts& c : r.counts) {
    if (c.inside_after >= kMinOwnShare) continue;
    std::snprintf(text, sizeof text,
                  "the %s sphere cannot be told from the other spheres: the proposed windows give "
                  "only %.0f %% of its disc its colour (at least %.0f %% needed)",
                  c.name.c_str(), 100.0 * c.inside_after, 100.0 * kMinOwnShare);
    return text;
  }
  for (const ColourCounts& c : r.counts) {
    if (c.background_fraction_after <= options.max_background_fraction) continue;
    std::snprintf(text, sizeof text,
                  "the %s sphere cannot be told from the background: the proposed window takes "
                  "%.0f background pixels per view, %.0f %% of the sphere pixels it takes (limit "
                  "%.0f %%)",
                  c.name.c_str(), c.outside_per_view_after, 100.0 * c.background_fraction_after,
                  100.0 * options.max_background_fraction);
    return text;
  }
  return {};
}

// The share of a sphere's own pixels its window takes from the background, with this marker.
double background_share(const hal::MarkerModel& marker, double water_correction,
                        const std::vector<View>& views, std::size_t sphere) {
  const Tally t = tally(marker, water_correction, views);
  return static_cast<double>(t.outside[sphere]) /
         static_cast<double>(std::max<long>(1, t.inside_hits[sphere]));
}

// Far off, a sphere's colour tends to the water's own: the window that follows the drift there
// can reach the background's hues. Where it takes more background than the limit allows, each
// window edge the drift moved is drawn back (bisection, 1/32 of the way) toward the recording's
// own extremes until it does not; the note says how far the window now reaches.
void trim_drift_into_background(ColourTuningResult& r, const hal::MarkerModel& observed,
                                double water_correction, const std::vector<View>& views,
                                const ColourTuningOptions& options) {
  for (std::size_t i = 0; i < r.tuned.spheres.size(); ++i) {
    const hal::MarkerSphere a = observed.spheres[i], b = r.tuned.spheres[i];
    if (a.hue_min_deg == b.hue_min_deg && a.hue_max_deg == b.hue_max_deg) continue;
    auto at = [&](double t) {
      hal::MarkerModel m = r.tuned;
      m.spheres[i].hue_min_deg = round_to(
          wrap_deg(a.hue_min_deg + t * hue_difference_deg(b.hue_min_deg, a.hue_min_deg)), 0.1);
      m.spheres[i].hue_max_deg = round_to(
          wrap_deg(a.hue_max_deg + t * hue_difference_deg(b.hue_max_deg, a.hue_max_deg)), 0.1);
      return m;
    };
    if (background_share(r.tuned, water_correction, views, i) <= options.max_background_fraction) {
      continue;
    }
    double lo = 0.0, hi = 1.0;  // lo: within the limit (the recording's own extremes)
    for (int k = 0; k < 5; ++k) {
      const double mid = 0.5 * (lo + hi);
      const bool fits =
          background_share(at(mid), water_correction, views, i) <= options.max_background_fraction;
      (fits ? lo : hi) = mid;
    }
    r.tuned = at(lo);
    char note[320];
    std::snprintf(note, sizeof note,
                  "the %s window follows the drift only to hue %.1f-%.1f deg (the drift reached "
                  "%.1f-%.1f): further it takes the background, whose colour the sphere takes "
                  "on far off in this water",
                  b.name.c_str(), r.tuned.spheres[i].hue_min_deg, r.tuned.spheres[i].hue_max_deg,
                  b.hue_min_deg, b.hue_max_deg);
    r.notes.emplace_back(note);
  }
}

// A recording reaches a working range's end when a located pair is this close to it.
constexpr double kRangeCoverageSlackM = 0.1;

// Where the located pairs put the marker against the working range; what falls short is said,
// with how far the windows were carried beyond the recording by the measured drift.
void judge_range_coverage(ColourTuningResult& r, const ColourTuningOptions& options) {
  double near = 1e9, far = 0.0;
  for (const PairLocation& p : r.pairs) {
    if (!p.located) continue;
    near = std::min(near, p.T_cl_marker.translation().norm());
    far = std::max(far, p.T_cl_marker.translation().norm());
  }
  r.located_range_min_m = near;
  r.located_range_max_m = far;
  r.covers_near = near <= options.range_near_m + kRangeCoverageSlackM;
  r.covers_far = far >= options.range_far_m - kRangeCoverageSlackM;
  char note[320];
  if (!r.covers_far) {
    std::snprintf(note, sizeof note,
                  "the recording does not cover far range: the farthest located pair is %.2f m "
                  "out, the working range reaches %.2f m (--range-m); beyond %.2f m the windows "
                  "follow the hue drift measured with range, not a view: record the marker out "
                  "to %.2f m",
                  far, options.range_far_m, far, options.range_far_m);
    r.notes.emplace_back(note);
  }
  if (!r.covers_near) {
    std::snprintf(note, sizeof note,
                  "the recording does not cover near range: the nearest located pair is %.2f m "
                  "out, the working range starts at %.2f m (--range-m); nearer, the windows "
                  "follow the measured drift: record the marker in to %.2f m",
                  near, options.range_near_m, options.range_near_m);
    r.notes.emplace_back(note);
  }
}

}  // namespace

HueDrift hue_drift_over_range(const std::vector<RangedHueExtremes>& views, double near_m,
                              double far_m) {
  HueDrift out;
  if (views.empty()) return out;
  double r_mean = 0.0, low_mean = 0.0, high_mean = 0.0;
  out.range_min_m = 1e9;
  out.low_deg = 1e9;
  out.high_deg = -1e9;
  const auto n = static_cast<double>(views.size());
  for (const RangedHueExtremes& v : views) {
    out.range_min_m = std::min(out.range_min_m, v.range_m);
    out.range_max_m = std::max(out.range_max_m, v.range_m);
    out.low_deg = std::min(out.low_deg, v.low_deg);
    out.high_deg = std::max(out.high_deg, v.high_deg);
    r_mean += v.range_m / n;
    low_mean += v.low_deg / n;
    high_mean += v.high_deg / n;
  }
  if (views.size() < 3 || out.range_max_m - out.range_min_m < kMinDriftSpanM) return out;
  double srr = 0.0, srl = 0.0, srh = 0.0;
  for (const RangedHueExtremes& v : views) {
    srr += (v.range_m - r_mean) * (v.range_m - r_mean);
    srl += (v.range_m - r_mean) * (v.low_deg - low_mean);
    srh += (v.range_m - r_mean) * (v.high_deg - high_mean);
  }
  out.low_drift_deg_per_m = srl / srr;
  out.high_drift_deg_per_m = srh / srr;
  double under = 1e9, over = -1e9;  // the lines' values at range 0
  for (const RangedHueExtremes& v : views) {
    under = std::min(under, v.low_deg - out.low_drift_deg_per_m * v.range_m);
    over = std::max(over, v.high_deg - out.high_drift_deg_per_m * v.range_m);
  }
  for (const double r : {near_m, far_m}) {
    out.low_deg = std::min(out.low_deg, under + out.low_drift_deg_per_m * r);
    out.high_deg = std::max(out.high_deg, over + out.high_drift_deg_per_m * r);
  }
  return out;
}

int ColourTuningResult::located() const {
  return static_cast<int>(
      std::count_if(pairs.begin(), pairs.end(), [](const PairLocation& p) { return p.located; }));
}

hal::MarkerModel widened_marker(const hal::MarkerModel& marker, double widen_deg,
                                double saturation_min, double value_min) {
  hal::MarkerModel out = marker;
  for (std::size_t i = 0; i < marker.spheres.size(); ++i) {
    const hal::MarkerSphere& s = marker.spheres[i];
    const double centre = window_centre_deg(s);
    double half = window_half_deg(s) + widen_deg;
    for (std::size_t j = 0; j < marker.spheres.size(); ++j) {
      if (j == i) continue;
      const double gap = std::abs(hue_difference_deg(window_centre_deg(marker.spheres[j]), centre));
      half = std::min(half, std::max(window_half_deg(s), gap / 2.0 - 1.0));
    }
    hal::MarkerSphere& w = out.spheres[i];
    w.hue_min_deg = wrap_deg(centre - half);
    w.hue_max_deg = wrap_deg(centre + half);
    w.saturation_min = std::min(s.saturation_min, saturation_min);
    w.value_min = std::min(s.value_min, value_min);
  }
  return out;
}

ColourTuningResult tune_marker_colours(const hal::StereoRig& rig, const hal::MarkerModel& marker,
                                       const estimator::EstimatorParams& params,
                                       const std::vector<StereoImages>& pairs,
                                       const ColourTuningOptions& options) {
  ColourTuningResult r;
  r.tuned = marker;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    r.pairs.push_back(locate_pair(rig, marker, params, pairs[i], options.seed + i, options.frames));
  }
  if (r.located() == 0) {
    r.refused = true;
    r.reason =
        "the marker was not located in any pair, with the configured hue windows, "
        "widened ones or one slid round the hue circle: record with all three spheres in "
        "both views";
    return r;
  }
  const std::vector<View> views = located_views(rig, marker, pairs, r.pairs);
  std::vector<Samples> samples = sample_spheres(marker, params.water_correction, views);
  for (std::size_t s = 0; s < marker.spheres.size(); ++s) {
    r.spreads.push_back(spread_of(marker.spheres[s].name, samples[s], options));
  }
  propose(r.spreads, options, r.tuned);
  std::vector<SphereSpread> observed_spreads = r.spreads;
  for (SphereSpread& s : observed_spreads) {
    s.hue_low_deg = s.hue_p3_deg;
    s.hue_high_deg = s.hue_p97_deg;
  }
  hal::MarkerModel observed = marker;
  propose(observed_spreads, options, observed);
  judge_range_coverage(r, options);
  trim_drift_into_background(r, observed, params.water_correction, views, options);
  r.counts = counts_of(marker, r.tuned, params.water_correction, views);
  for (std::size_t i = 0; i < r.spreads.size(); ++i) {
    for (std::size_t j = i + 1; j < r.spreads.size(); ++j) {
      if (r.spreads[i].pixels == 0 || r.spreads[j].pixels == 0) continue;
      if (!spreads_overlap(r.spreads[i], r.spreads[j])) continue;
      char note[200];
      std::snprintf(note, sizeof note,
                    "the %s and %s spheres' hues overlap: told apart by the floors (%s, checked "
                    "first, needs saturation >= %.2f)",
                    r.spreads[i].name.c_str(), r.spreads[j].name.c_str(),
                    r.tuned.spheres[i].name.c_str(), r.tuned.spheres[i].saturation_min);
      r.notes.push_back(note);
    }
  }
  r.reason = refusal(r, options);
  r.refused = !r.reason.empty();
  return r;
}

std::string marker_fragment_yaml(const hal::MarkerModel& tuned, const std::string& header) {
  std::ostringstream y;
  std::istringstream lines(header);
  for (std::string line; std::getline(lines, line);) y << "# " << line << "\n";
  auto num = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", x);
    return std::string(b);
  };
  y << "marker:\n  spheres:\n";
  for (const hal::MarkerSphere& s : tuned.spheres) {
    const Eigen::Vector3d& c = s.centre_marker_m;
    const Eigen::Vector3d& a = s.albedo_rgb;
    y << "    - name: " << s.name << "\n"
      << "      centre_m: [" << num(c.x()) << ", " << num(c.y()) << ", " << num(c.z()) << "]\n"
      << "      radius_m: " << num(s.radius_m) << "\n"
      << "      hue_min_deg: " << num(s.hue_min_deg) << "\n"
      << "      hue_max_deg: " << num(s.hue_max_deg) << "\n"
      << "      saturation_min: " << num(s.saturation_min) << "\n"
      << "      value_min: " << num(s.value_min) << "\n"
      << "      albedo_rgb: [" << num(a.x()) << ", " << num(a.y()) << ", " << num(a.z()) << "]\n";
  }
  return y.str();
}

namespace {

cv::Mat labels_over(const cv::Mat& image, const cv::Mat& labels) {
  // Labelled pixels in their class's pure colour, the rest the image at a third: what the
  // estimator's fitness sees as each sphere.
  static const cv::Vec3b kColour[4] = {
      {0, 0, 0}, {40, 40, 255}, {40, 255, 40}, {255, 90, 40}};  // BGR: none, red, green, blue
  cv::Mat out = image / 3;
  for (int v = 0; v < labels.rows; ++v) {
    for (int u = 0; u < labels.cols; ++u) {
      const std::uint8_t l = labels.at<std::uint8_t>(v, u);
      if (l > 0 && l < 4) out.at<cv::Vec3b>(v, u) = kColour[l];
    }
  }
  return out;
}

}  // namespace

cv::Mat segmentation_figure(const hal::CameraModel& camera, const Eigen::Isometry3d& T_cam_marker,
                            const hal::MarkerModel& marker, const cv::Mat& image,
                            const cv::Mat& labels_before, const cv::Mat& labels_after) {
  std::vector<cv::Mat> panels = {image.clone(), labels_over(image, labels_before),
                                 labels_over(image, labels_after)};
  const std::vector<Disc> discs = sphere_discs(camera, T_cam_marker, marker);
  const char* titles[3] = {"image", "configured windows", "tuned windows"};
  for (int i = 0; i < 3; ++i) {
    for (const Disc& d : discs) {
      if (d.radius_px <= 0.0) continue;
      cv::circle(panels[i], cv::Point(cvRound(d.centre_px.x), cvRound(d.centre_px.y)),
                 cvRound(d.radius_px), cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
    cv::putText(panels[i], titles[i], cv::Point(8, 22), cv::FONT_HERSHEY_SIMPLEX, 0.6,
                cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  cv::Mat out;
  cv::hconcat(panels, out);
  return out;
}

}  // namespace rovctl::app
