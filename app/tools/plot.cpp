// Plot rendering with OpenCV's drawing primitives: anti-aliased lines at sub-pixel precision,
// Hershey fonts, a tab10 palette, and a legend placed in the emptiest corner.
#include "app/tools/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace rovctl::app {
namespace {

constexpr int kShift = 4;  // sub-pixel bits for cv::line/circle
constexpr double kSubPixel = 1 << kShift;

const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kText(40, 40, 40);
const cv::Scalar kTickText(80, 80, 80);
const cv::Scalar kAxis(90, 90, 90);
const cv::Scalar kGrid(228, 228, 228);
const cv::Scalar kReference(110, 110, 110);

constexpr int kTitleFont = cv::FONT_HERSHEY_DUPLEX;
constexpr double kTitleScale = 0.62;
constexpr int kLabelFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kLabelScale = 0.52;
constexpr double kTickScale = 0.45;
constexpr double kLegendScale = 0.47;

// matplotlib's tab10, BGR.
const cv::Scalar kPalette[] = {{180, 119, 31},  {14, 127, 255}, {44, 160, 44},   {40, 39, 214},
                               {189, 103, 148}, {75, 86, 140},  {194, 119, 227}, {127, 127, 127},
                               {34, 189, 188},  {207, 190, 23}};

cv::Size text_size(const std::string& s, int font, double scale, int thickness = 1) {
  int baseline = 0;
  return cv::getTextSize(s, font, scale, thickness, &baseline);
}

// Text with its left end at x and its vertical centre at y.
void put_text(cv::Mat& img, const std::string& s, double x, double y, int font, double scale,
              const cv::Scalar& colour, int thickness = 1) {
  const cv::Size sz = text_size(s, font, scale, thickness);
  cv::putText(img, s,
              cv::Point(static_cast<int>(std::lround(x)),
                        static_cast<int>(std::lround(y + sz.height / 2.0))),
              font, scale, colour, thickness, cv::LINE_AA);
}

// Text with a white halo, readable over grid lines and data.
void put_text_halo(cv::Mat& img, const std::string& s, double x, double y, double scale,
                   const cv::Scalar& colour) {
  put_text(img, s, x, y, kLabelFont, scale, kBackground, 4);
  put_text(img, s, x, y, kLabelFont, scale, colour, 1);
}

cv::Point sub(double x, double y) {
  return {static_cast<int>(std::lround(x * kSubPixel)),
          static_cast<int>(std::lround(y * kSubPixel))};
}

struct Rect {
  double x0, y0, x1, y1;
};

// Liang-Barsky: clips the segment to `r`; false when nothing is left.
bool clip(double& ax, double& ay, double& bx, double& by, const Rect& r) {
  double t0 = 0.0;
  double t1 = 1.0;
  const double dx = bx - ax;
  const double dy = by - ay;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax - r.x0, r.x1 - ax, ay - r.y0, r.y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) return false;
  }
  const double ox = ax;
  const double oy = ay;
  ax = ox + t0 * dx;
  ay = oy + t0 * dy;
  bx = ox + t1 * dx;
  by = oy + t1 * dy;
  return true;
}

void draw_segment(cv::Mat& img, double ax, double ay, double bx, double by, const Rect& r,
                  const cv::Scalar& colour, int thickness) {
  if (!clip(ax, ay, bx, by, r)) return;
  cv::line(img, sub(ax, ay), sub(bx, by), colour, thickness, cv::LINE_AA, kShift);
}

void draw_dashed(cv::Mat& img, double ax, double y, double bx, const cv::Scalar& colour) {
  for (double x = ax; x < bx; x += 13.0) {
    cv::line(img, sub(x, y), sub(std::min(x + 8.0, bx), y), colour, 1, cv::LINE_AA, kShift);
  }
}

void draw_marker(cv::Mat& img, double x, double y, const cv::Scalar& colour) {
  cv::circle(img, sub(x, y), static_cast<int>(6 * kSubPixel), colour, cv::FILLED, cv::LINE_AA,
             kShift);
  cv::circle(img, sub(x, y), static_cast<int>(6 * kSubPixel), colour * 0.6, 1, cv::LINE_AA, kShift);
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
  // A range with room: padded by `pad` of its span, never of zero width.
  Range padded(double pad) const {
    Range r = *this;
    if (r.empty()) return {0.0, 1.0};
    if (r.hi - r.lo < 1e-12) {
      const double half = std::max(std::abs(r.lo) * 0.1, 0.5);
      return {r.lo - half, r.hi + half};
    }
    const double span = r.hi - r.lo;
    return {r.lo - pad * span, r.hi + pad * span};
  }
};

}  // namespace

AxisTicks nice_ticks(double lo, double hi, int target_count) {
  AxisTicks t;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return t;
  if (hi < lo) std::swap(lo, hi);
  if (hi - lo < 1e-12) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double raw = (hi - lo) / std::max(1, target_count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double mult = norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0;
  t.step = mult * mag;
  t.lo = std::floor(lo / t.step + 1e-9) * t.step;
  t.hi = std::ceil(hi / t.step - 1e-9) * t.step;
  const auto n = static_cast<int>(std::lround((t.hi - t.lo) / t.step));
  for (int i = 0; i <= n; ++i) {
    double v = t.lo + i * t.step;
    if (std::abs(v) < t.step * 1e-9) v = 0.0;
    t.values.push_back(v);
  }
  return t;
}

std::string format_tick(double value, double step) {
  if (std::abs(value) < step * 1e-9) value = 0.0;
  char buf[64];
  if (std::abs(value) >= 1e6 || (value != 0.0 && std::abs(value) < 1e-4)) {
    std::snprintf(buf, sizeof buf, "%.3g", value);
    return buf;
  }
  int decimals = 0;
  if (step > 0.0 && std::isfinite(step)) {
    decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
    // 0.25 or 2.5 steps need one more digit than their power of ten says.
    const double scaled = step * std::pow(10.0, decimals);
    if (std::abs(scaled - std::round(scaled)) > 1e-6) ++decimals;
  }
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 9), value);
  return buf;
}

PlotPanel::PlotPanel(std::string title, std::string x_label, std::string y_label, int height_px)
    : title_(std::move(title)),
      x_label_(std::move(x_label)),
      y_label_(std::move(y_label)),
      height_px_(height_px) {}

PlotPanel& PlotPanel::line(std::string name, std::vector<double> x, std::vector<double> y,
                           std::optional<cv::Scalar> colour) {
  series_.push_back({std::move(name), std::move(x), std::move(y), Style::line, {}, colour});
  return *this;
}

PlotPanel& PlotPanel::step(std::string name, std::vector<double> x, std::vector<double> y,
                           std::optional<cv::Scalar> colour) {
  series_.push_back({std::move(name), std::move(x), std::move(y), Style::step, {}, colour});
  return *this;
}

PlotPanel& PlotPanel::scatter(std::string name, std::vector<double> x, std::vector<double> y,
                              std::vector<std::string> labels, std::optional<cv::Scalar> colour) {
  series_.push_back(
      {std::move(name), std::move(x), std::move(y), Style::scatter, std::move(labels), colour});
  return *this;
}

PlotPanel& PlotPanel::hline(double y, std::string label) {
  hlines_.push_back({y, std::move(label)});
  return *this;
}

PlotPanel& PlotPanel::y_categories(std::vector<std::pair<double, std::string>> ticks) {
  categories_ = std::move(ticks);
  return *this;
}

PlotPanel& PlotPanel::x_limits(double lo, double hi) {
  x_limits_ = std::make_pair(lo, hi);
  return *this;
}

PlotPanel& PlotPanel::y_limits(double lo, double hi) {
  y_limits_ = std::make_pair(lo, hi);
  return *this;
}

PlotPanel& PlotPanel::legend_outside() {
  legend_outside_ = true;
  return *this;
}

struct PlotPanel::Frame {
  double x_lo, x_hi, y_lo, y_hi;
  AxisTicks xt, yt;
  std::vector<std::pair<double, std::string>> y_labels;
  bool no_data;
  int left_px;
  bool x_inside(double v) const {
    return v >= x_lo - (x_hi - x_lo) * 1e-9 && v <= x_hi + (x_hi - x_lo) * 1e-9;
  }
  bool y_inside(double v) const {
    return v >= y_lo - (y_hi - y_lo) * 1e-9 && v <= y_hi + (y_hi - y_lo) * 1e-9;
  }
};

PlotPanel::Frame PlotPanel::frame(int W, int H) const {
  Range xr;
  Range yr;
  bool has_scatter = false;
  for (const Series& s : series_) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xr.add(s.x[i]);
      yr.add(s.y[i]);
    }
    has_scatter = has_scatter || s.style == Style::scatter;
  }
  const bool no_data = xr.empty();
  for (const ReferenceLine& h : hlines_) yr.add(h.y);
  for (const auto& c : categories_) yr.add(c.first);

  Range xa =
      x_limits_ ? Range{x_limits_->first, x_limits_->second} : xr.padded(has_scatter ? 0.06 : 0.0);
  if (xa.hi - xa.lo < 1e-12) xa = xa.padded(0.0);
  Range ya = y_limits_             ? Range{y_limits_->first, y_limits_->second}
             : categories_.empty() ? yr.padded(0.06)
                                   : yr.padded(0.0);
  if (!y_limits_ && !categories_.empty()) {
    ya.lo -= 0.5;
    ya.hi += 0.5;
  }
  if (ya.hi - ya.lo < 1e-12) ya = ya.padded(0.0);

  Frame f{xa.lo,
          xa.hi,
          ya.lo,
          ya.hi,
          nice_ticks(xa.lo, xa.hi, std::max(4, W / 130)),
          nice_ticks(ya.lo, ya.hi, std::max(3, H / 70)),
          {},
          no_data,
          0};
  if (categories_.empty()) {
    for (const double v : f.yt.values) {
      if (f.y_inside(v)) f.y_labels.emplace_back(v, format_tick(v, f.yt.step));
    }
  } else {
    for (const auto& c : categories_) {
      if (f.y_inside(c.first)) f.y_labels.push_back(c);
    }
  }
  int y_tick_width = 0;
  for (const auto& l : f.y_labels) {
    y_tick_width = std::max(y_tick_width, text_size(l.second, kLabelFont, kTickScale).width);
  }
  f.left_px = 14 + (y_label_.empty() ? 0 : 30) + y_tick_width + 10;
  return f;
}

int PlotPanel::left_margin_px(int width_px) const { return frame(width_px, height_px_).left_px; }

void PlotPanel::render(cv::Mat& img, int left_px) const {
  img.setTo(kBackground);
  const int W = img.cols;
  const int H = img.rows;
  const Frame f = frame(W, H);
  const Range xa{f.x_lo, f.x_hi};
  const Range ya{f.y_lo, f.y_hi};
  const AxisTicks& xt = f.xt;
  const bool no_data = f.no_data;
  const auto& y_labels = f.y_labels;
  auto inside = [](double v, const Range& r) {
    const double eps = (r.hi - r.lo) * 1e-9;
    return v >= r.lo - eps && v <= r.hi + eps;
  };
  std::vector<std::size_t> entries;
  for (std::size_t i = 0; i < series_.size(); ++i) {
    if (!series_[i].name.empty()) entries.push_back(i);
  }
  int text_w = 0;
  for (const std::size_t i : entries) {
    text_w = std::max(text_w, text_size(series_[i].name, kLabelFont, kLegendScale).width);
  }
  const int row_h = 21;
  const int box_w = 10 + 30 + 8 + text_w + 12;
  const int box_h = 8 + row_h * static_cast<int>(entries.size()) + 4;
  const bool outside = legend_outside_ && !entries.empty();
  const Rect plot{static_cast<double>(left_px >= 0 ? left_px : f.left_px),
                  title_.empty() ? 16.0 : 42.0,
                  static_cast<double>(W - 28 - (outside ? box_w + 14 : 0)),
                  static_cast<double>(H - (x_label_.empty() ? 34 : 60))};
  auto px = [&](double x) { return plot.x0 + (x - xa.lo) / (xa.hi - xa.lo) * (plot.x1 - plot.x0); };
  auto py = [&](double y) { return plot.y1 - (y - ya.lo) / (ya.hi - ya.lo) * (plot.y1 - plot.y0); };

  // Grid and tick labels.
  for (const auto& [v, label] : y_labels) {
    const double y = py(v);
    draw_segment(img, plot.x0, y, plot.x1, y, plot, kGrid, 1);
    cv::line(img, sub(plot.x0 - 5, y), sub(plot.x0, y), kAxis, 1, cv::LINE_AA, kShift);
    const int w = text_size(label, kLabelFont, kTickScale).width;
    put_text(img, label, plot.x0 - 9 - w, y, kLabelFont, kTickScale, kTickText);
  }
  for (const double v : xt.values) {
    if (!inside(v, xa)) continue;
    const double x = px(v);
    draw_segment(img, x, plot.y0, x, plot.y1, plot, kGrid, 1);
    cv::line(img, sub(x, plot.y1), sub(x, plot.y1 + 5), kAxis, 1, cv::LINE_AA, kShift);
    const std::string label = format_tick(v, xt.step);
    const int w = text_size(label, kLabelFont, kTickScale).width;
    put_text(img, label, x - w / 2.0, plot.y1 + 17, kLabelFont, kTickScale, kTickText);
  }

  // Reference lines under the data.
  for (const ReferenceLine& h : hlines_) {
    if (!inside(h.y, ya)) continue;
    const double y = py(h.y);
    draw_dashed(img, plot.x0, y, plot.x1, kReference);
    if (!h.label.empty()) {
      const int w = text_size(h.label, kLabelFont, kTickScale).width;
      // Below the line: labelled points sitting on a threshold carry their text above it.
      put_text_halo(img, h.label, plot.x1 - w - 6, y + 14, kTickScale, kReference);
    }
  }

  // Data.
  std::vector<cv::Scalar> colours;
  std::size_t next_colour = 0;
  for (const Series& s : series_) {
    colours.push_back(s.colour ? *s.colour
                               : kPalette[next_colour++ % (sizeof kPalette / sizeof kPalette[0])]);
  }
  std::vector<cv::Point2d> marker_points;  // for the legend's placement
  for (std::size_t si = 0; si < series_.size(); ++si) {
    const Series& s = series_[si];
    const cv::Scalar& c = colours[si];
    const std::size_t n = std::min(s.x.size(), s.y.size());
    auto ok = [&](std::size_t i) { return std::isfinite(s.x[i]) && std::isfinite(s.y[i]); };
    if (s.style == Style::scatter) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!ok(i) || !inside(s.x[i], xa) || !inside(s.y[i], ya)) continue;
        const double x = px(s.x[i]);
        const double y = py(s.y[i]);
        draw_marker(img, x, y, c);
        marker_points.emplace_back(x, y);
        if (i < s.labels.size() && !s.labels[i].empty()) {
          const int w = text_size(s.labels[i], kLabelFont, kLabelScale).width;
          const double lx = x + 10 + w < plot.x1 ? x + 10 : x - 10 - w;
          put_text_halo(img, s.labels[i], lx, y - 12, kLabelScale, c * 0.75);
        }
      }
      continue;
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
      if (!ok(i)) continue;
      marker_points.emplace_back(px(s.x[i]), py(s.y[i]));
      if (!ok(i + 1)) continue;
      // Points along the segment, so the legend avoids lines as well as vertices.
      const double ax = px(s.x[i]);
      const double ay = py(s.y[i]);
      const double bx = px(s.x[i + 1]);
      const double by = py(s.y[i + 1]);
      const int samples =
          static_cast<int>(std::min(200.0, (std::abs(bx - ax) + std::abs(by - ay)) / 6.0));
      for (int k = 1; k <= samples; ++k) {
        const double u = static_cast<double>(k) / (samples + 1);
        if (s.style == Style::line) {
          marker_points.emplace_back(ax + u * (bx - ax), ay + u * (by - ay));
        } else {
          marker_points.emplace_back(ax + u * (bx - ax), ay);
          marker_points.emplace_back(bx, ay + u * (by - ay));
        }
      }
      if (s.style == Style::line) {
        draw_segment(img, px(s.x[i]), py(s.y[i]), px(s.x[i + 1]), py(s.y[i + 1]), plot, c, 2);
      } else {
        draw_segment(img, px(s.x[i]), py(s.y[i]), px(s.x[i + 1]), py(s.y[i]), plot, c, 2);
        draw_segment(img, px(s.x[i + 1]), py(s.y[i]), px(s.x[i + 1]), py(s.y[i + 1]), plot, c, 2);
      }
    }
    if (n == 1 && ok(0)) draw_marker(img, px(s.x[0]), py(s.y[0]), c);
    if (n > 0 && ok(n - 1)) marker_points.emplace_back(px(s.x[n - 1]), py(s.y[n - 1]));
  }

  // Axes box on top of the data's clipped ends.
  cv::rectangle(img, sub(plot.x0, plot.y0), sub(plot.x1, plot.y1), kAxis, 1, cv::LINE_AA, kShift);

  if (no_data) {
    const std::string msg = "no data";
    const int w = text_size(msg, kLabelFont, kLabelScale).width;
    put_text(img, msg, (plot.x0 + plot.x1 - w) / 2, (plot.y0 + plot.y1) / 2, kLabelFont,
             kLabelScale, kTickText);
  }

  // Titles and axis labels.
  if (!title_.empty()) {
    const int w = text_size(title_, kTitleFont, kTitleScale).width;
    put_text(img, title_, (plot.x0 + plot.x1 - w) / 2, 21, kTitleFont, kTitleScale, kText);
  }
  if (!x_label_.empty()) {
    const int w = text_size(x_label_, kLabelFont, kLabelScale).width;
    put_text(img, x_label_, (plot.x0 + plot.x1 - w) / 2, H - 16, kLabelFont, kLabelScale, kText);
  }
  if (!y_label_.empty()) {
    const cv::Size sz = text_size(y_label_, kLabelFont, kLabelScale);
    cv::Mat band(sz.height + 12, sz.width + 8, CV_8UC3, kBackground);
    put_text(band, y_label_, 4, band.rows / 2.0, kLabelFont, kLabelScale, kText);
    cv::Mat rotated;
    cv::rotate(band, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int cy = static_cast<int>((plot.y0 + plot.y1) / 2) - rotated.rows / 2;
    const cv::Rect dst(10, std::max(0, cy), rotated.cols, std::min(rotated.rows, H));
    if (dst.y + dst.height <= H && dst.x + dst.width <= W) {
      rotated(cv::Rect(0, 0, dst.width, dst.height)).copyTo(img(dst));
    }
  }

  // Legend right of the axes, or in the corner covering the fewest data points.
  if (entries.empty()) return;
  const double m = 10.0;
  const cv::Point2d corners[] = {{plot.x1 - m - box_w, plot.y0 + m},
                                 {plot.x0 + m, plot.y0 + m},
                                 {plot.x1 - m - box_w, plot.y1 - m - box_h},
                                 {plot.x0 + m, plot.y1 - m - box_h},
                                 {plot.x1 + 14, plot.y0}};
  std::size_t best = outside ? 4 : 0;
  std::size_t best_count = std::numeric_limits<std::size_t>::max();
  for (std::size_t k = 0; k < 4 && !outside; ++k) {
    const cv::Rect2d r(corners[k].x, corners[k].y, box_w, box_h);
    std::size_t count = 0;
    for (const auto& p : marker_points) count += r.contains(p) ? 1 : 0;
    if (count < best_count) {
      best = k;
      best_count = count;
    }
  }
  const cv::Rect box(static_cast<int>(corners[best].x), static_cast<int>(corners[best].y), box_w,
                     box_h);
  const cv::Rect safe = box & cv::Rect(0, 0, W, H);
  cv::Mat roi = img(safe);
  cv::Mat white(roi.size(), roi.type(), kBackground);
  cv::addWeighted(roi, 0.15, white, 0.85, 0.0, roi);
  cv::rectangle(img, safe, cv::Scalar(200, 200, 200), 1, cv::LINE_AA);
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const Series& s = series_[entries[e]];
    const cv::Scalar& c = colours[entries[e]];
    const double y = box.y + 8 + row_h * (static_cast<double>(e) + 0.5);
    const double x = box.x + 10;
    if (s.style == Style::scatter) {
      draw_marker(img, x + 15, y, c);
    } else {
      cv::line(img, sub(x, y), sub(x + 30, y), c, 2, cv::LINE_AA, kShift);
    }
    put_text(img, s.name, x + 38, y, kLabelFont, kLegendScale, kText);
  }
}

Plot::Plot(std::string title, int width_px) : title_(std::move(title)), width_px_(width_px) {}

PlotPanel& Plot::add_panel(std::string title, std::string x_label, std::string y_label,
                           int height_px) {
  panels_.emplace_back(std::move(title), std::move(x_label), std::move(y_label), height_px);
  return panels_.back();
}

cv::Mat Plot::render() const {
  const int title_h = title_.empty() ? 0 : 46;
  int height = title_h;
  for (const PlotPanel& p : panels_) height += p.height_px();
  cv::Mat img(std::max(height, 1), width_px_, CV_8UC3, kBackground);
  if (!title_.empty()) {
    const double scale = 0.8;
    const int w = text_size(title_, kTitleFont, scale).width;
    put_text(img, title_, (width_px_ - w) / 2.0, 26, kTitleFont, scale, kText);
  }
  // One left margin for all panels, so their x axes line up.
  int left = 0;
  for (const PlotPanel& p : panels_) left = std::max(left, p.left_margin_px(width_px_));
  int y = title_h;
  for (const PlotPanel& p : panels_) {
    cv::Mat roi = img(cv::Rect(0, y, width_px_, p.height_px()));
    p.render(roi, left);
    y += p.height_px();
  }
  return img;
}

void Plot::save_png(const std::string& path) const {
  bool ok = false;
  try {
    ok = cv::imwrite(path, render());
  } catch (const cv::Exception& e) {
    throw std::runtime_error("plot: cannot write " + path + ": " + e.what());
  }
  if (!ok) throw std::runtime_error("plot: cannot write " + path);
}

}  // namespace rovctl::app
