// PNG line plots drawn with OpenCV: stacked panels, each with title, axis labels, named line,
// step (discrete state) and labelled scatter series, reference lines, legend and nice ticks.
// For the sim's and the study's figures; not on the real-time path.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rovctl::app {

// Round-number axis ticks covering [lo, hi] (e.g. 0, 0.2, ..., 1.0).
struct AxisTicks {
  double lo = 0.0;    // first tick (<= the data's lo)
  double hi = 1.0;    // last tick (>= the data's hi)
  double step = 0.2;  // 1, 2 or 5 times a power of ten
  std::vector<double> values;
};
AxisTicks nice_ticks(double lo, double hi, int target_count = 6);
// A tick value with as many decimals as `step` needs ("0.25", "1500", "-0.1").
std::string format_tick(double value, double step);

class PlotPanel {
 public:
  enum class Style { line, step, scatter };
  struct Series {
    std::string name;
    std::vector<double> x;
    std::vector<double> y;
    Style style = Style::line;
    std::vector<std::string> labels;   // scatter: text beside each point
    std::optional<cv::Scalar> colour;  // BGR; default: the palette in order
  };
  struct ReferenceLine {
    double y;
    std::string label;
  };

  PlotPanel(std::string title, std::string x_label, std::string y_label, int height_px);

  // A polyline; NaN values break it.
  PlotPanel& line(std::string name, std::vector<double> x, std::vector<double> y,
                  std::optional<cv::Scalar> colour = std::nullopt);
  // A piecewise-constant series (held until the next sample): discrete states over time.
  PlotPanel& step(std::string name, std::vector<double> x, std::vector<double> y,
                  std::optional<cv::Scalar> colour = std::nullopt);
  // Markers, each with an optional text label (e.g. the paper's points "A".."E").
  PlotPanel& scatter(std::string name, std::vector<double> x, std::vector<double> y,
                     std::vector<std::string> labels = {},
                     std::optional<cv::Scalar> colour = std::nullopt);
  // A dashed horizontal line across the panel (a threshold), labelled at its right end.
  PlotPanel& hline(double y, std::string label);
  // Named y ticks instead of numbers (mission states: {0, "search"}, {1, "approach"}, ...).
  PlotPanel& y_categories(std::vector<std::pair<double, std::string>> ticks);
  // Fixed axis limits instead of the data's.
  PlotPanel& x_limits(double lo, double hi);
  PlotPanel& y_limits(double lo, double hi);
  // The legend in a column right of the axes instead of in the emptiest corner inside them:
  // for panels whose data fill every corner (points labelled near all four).
  PlotPanel& legend_outside();

  const std::string& title() const { return title_; }
  const std::vector<Series>& series() const { return series_; }
  int height_px() const { return height_px_; }

  // Draws into `canvas` (CV_8UC3, the panel's own rectangle). `left_px` >= 0 sets the left
  // margin (so stacked panels share one x position); otherwise it fits the tick labels.
  void render(cv::Mat& canvas, int left_px = -1) const;
  // The left margin this panel needs at the given size (tick labels and y label).
  int left_margin_px(int width_px) const;

 private:
  struct Frame;
  Frame frame(int width_px, int height_px) const;

  std::string title_;
  std::string x_label_;
  std::string y_label_;
  int height_px_;
  std::vector<Series> series_;
  std::vector<ReferenceLine> hlines_;
  std::vector<std::pair<double, std::string>> categories_;
  std::optional<std::pair<double, double>> x_limits_;
  std::optional<std::pair<double, double>> y_limits_;
  bool legend_outside_ = false;
};

// A figure: an optional title over panels stacked top to bottom, all the same width.
class Plot {
 public:
  explicit Plot(std::string title = {}, int width_px = 1200);

  PlotPanel& add_panel(std::string title, std::string x_label, std::string y_label,
                       int height_px = 340);
  std::size_t panel_count() const { return panels_.size(); }
  PlotPanel& panel(std::size_t i) { return panels_.at(i); }

  cv::Mat render() const;  // CV_8UC3, width_px wide
  // Writes a PNG; throws std::runtime_error naming `path` if it cannot.
  void save_png(const std::string& path) const;

 private:
  std::string title_;
  int width_px_;
  std::vector<PlotPanel> panels_;
};

}  // namespace rovctl::app
