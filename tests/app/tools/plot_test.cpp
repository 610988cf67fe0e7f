// Plot rendering: tick arithmetic, and a three-panel PNG (lines, mission-state steps, labelled
// points) checked for size and content. ROVCTL_KEEP_PLOTS=1 keeps the PNG for a look.
#include "app/tools/plot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <set>

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

TEST(PlotTicks, NiceTicksUseOneTwoFiveSteps) {
  const AxisTicks t = nice_ticks(0.0, 1.0, 5);
  EXPECT_DOUBLE_EQ(t.step, 0.2);
  ASSERT_EQ(t.values.size(), 6u);
  EXPECT_DOUBLE_EQ(t.values.front(), 0.0);
  EXPECT_NEAR(t.values.back(), 1.0, 1e-12);

  const AxisTicks u = nice_ticks(-3.7, 98.2, 6);
  EXPECT_DOUBLE_EQ(u.step, 20.0);
  EXPECT_DOUBLE_EQ(u.lo, -20.0);
  EXPECT_DOUBLE_EQ(u.hi, 100.0);

  const AxisTicks flat = nice_ticks(2.0, 2.0, 5);  // a constant series still gets an axis
  EXPECT_GT(flat.values.size(), 1u);
  EXPECT_LT(flat.lo, 2.0);
  EXPECT_GT(flat.hi, 2.0);
}

TEST(PlotTicks, FormatsWithTheDecimalsTheStepNeeds) {
  EXPECT_EQ(format_tick(0.4, 0.2), "0.4");
  EXPECT_EQ(format_tick(1.25, 0.25), "1.25");
  EXPECT_EQ(format_tick(1500.0, 500.0), "1500");
  EXPECT_EQ(format_tick(-1e-17, 0.1), "0.0");
  EXPECT_EQ(format_tick(2.5, 0.5), "2.5");
}

Plot demo_plot() {
  Plot plot("rovctl sim: demo run", 1200);
  std::vector<double> t, a, b, fit;
  for (int i = 0; i <= 300; ++i) {
    const double s = i * 0.033;
    t.push_back(s);
    a.push_back(0.5 * std::exp(-s / 4.0) * std::cos(2.0 * s));
    b.push_back(i > 120 && i < 140 ? std::numeric_limits<double>::quiet_NaN()
                                   : 0.3 * std::exp(-s / 3.0));
    fit.push_back(std::min(1.0, 0.2 + 0.1 * s));
  }
  plot.add_panel("Pose error", "time [s]", "error [m]")
      .line("x error", t, a)
      .line("z error (gap: marker lost)", t, b)
      .line("fitness", t, fit)
      .hline(0.6, "recognised (0.6)");
  plot.add_panel("Mission state", "time [s]", "state")
      .step("state", {0.0, 1.2, 4.0, 7.5, 9.0}, {0, 1, 2, 3, 3})
      .y_categories({{0, "search"}, {1, "approach"}, {2, "final"}, {3, "docked"}});
  plot.add_panel("Convergence time (paper Fig. 9)", "population size", "time to fitness 0.6 [s]")
      .line("ours", {10, 20, 40, 60, 80}, {0.21, 0.17, 0.13, 0.19, 0.24})
      .scatter("paper", {10, 20, 40, 60, 80}, {0.187, 0.156, 0.125, 0.52, 0.3},
               {"E", "B", "C", "A", "D"});
  return plot;
}

TEST(Plot, RendersStackedPanelsToPng) {
  const Plot plot = demo_plot();
  const fs::path file =
      fs::temp_directory_path() / ("rovctl_plot_" + std::to_string(getpid()) + ".png");
  plot.save_png(file.string());
  ASSERT_TRUE(fs::exists(file));
  const cv::Mat img = cv::imread(file.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 1200);
  EXPECT_EQ(img.rows, 46 + 3 * 340);

  // Non-trivial: a fair share of drawn pixels, and the palette's first colours present.
  int non_white = 0;
  std::set<int> colours;
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (p != cv::Vec3b(255, 255, 255)) ++non_white;
      colours.insert((p[0] / 32) * 64 + (p[1] / 32) * 8 + p[2] / 32);
    }
  }
  EXPECT_GT(non_white, img.rows * img.cols / 50);
  EXPECT_GT(colours.size(), 20u);
  auto has_colour = [&](cv::Vec3b c) {
    for (int y = 0; y < img.rows; ++y) {
      for (int x = 0; x < img.cols; ++x) {
        if (cv::norm(img.at<cv::Vec3b>(y, x), c, cv::NORM_L1) < 12) return true;
      }
    }
    return false;
  };
  EXPECT_TRUE(has_colour({180, 119, 31}));  // first series (blue)
  EXPECT_TRUE(has_colour({14, 127, 255}));  // second (orange)
  const char* keep = std::getenv("ROVCTL_KEEP_PLOTS");
  if (keep != nullptr && std::string(keep) == "1") {
    std::cout << "plot kept at " << file << "\n";
  } else {
    fs::remove(file);
  }
}

TEST(Plot, EmptyPanelStillRenders) {
  Plot plot;
  plot.add_panel("nothing yet", "x", "y");
  const cv::Mat img = plot.render();
  EXPECT_EQ(img.rows, 340);
  EXPECT_LT(cv::countNonZero(img.reshape(1) != 255), img.rows * img.cols * 3);
}

TEST(Plot, UnwritablePathIsAnErrorNamingIt) {
  Plot plot;
  plot.add_panel("p", "x", "y").line("a", {0, 1}, {0, 1});
  try {
    plot.save_png("/nonexistent_dir/plot.png");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/plot.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace rovctl::app
