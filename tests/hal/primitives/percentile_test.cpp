// The shared percentile: interpolation between order statistics, failures as infinitely slow.
#include "hal/primitives/percentile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rovctl::hal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(Percentile, InterpolatesBetweenOrderStatistics) {
  EXPECT_DOUBLE_EQ(percentile({3.0, 1.0, 2.0}, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0}, 0.5), 2.5);
  EXPECT_NEAR(percentile({1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0}, 0.9), 9.1, 1e-12);
  EXPECT_DOUBLE_EQ(percentile({5.0}, 0.9), 5.0);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

TEST(Percentile, FailuresCountAsInfinitelySlow) {
  // Two of four failed: the median interpolates into a failure, so it is infinite.
  EXPECT_TRUE(std::isinf(percentile({1.0, kInf, 2.0, kInf}, 0.5)));
  // One of five failed: the median is finite, the p90 is not.
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, 3.0, 4.0, kInf}, 0.5), 3.0);
  EXPECT_TRUE(std::isinf(percentile({1.0, 2.0, 3.0, 4.0, kInf}, 0.9)));
  // Exactly on a finite order statistic next to a failure: finite.
  EXPECT_DOUBLE_EQ(percentile({1.0, 2.0, kInf}, 0.5), 2.0);
}

}  // namespace
}  // namespace rovctl::hal
