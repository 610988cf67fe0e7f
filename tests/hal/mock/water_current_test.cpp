// The water current: its mean, the spread and slowness of its random part, reproducibility.
#include "hal/mock/water_current.hpp"

#include <gtest/gtest.h>

namespace rovctl::hal::mock {
namespace {

TEST(WaterCurrent, MeanPlusSlowRandomPartWithTheConfiguredSpread) {
  WaterCurrentParams p;
  p.mean_world_mps = {0.08, -0.02, 0.0};
  p.random_sigma_mps = {0.02, 0.02, 0.0};
  p.correlation_time_s = 5.0;
  WaterCurrent c(p, 42);
  const double dt = 0.01;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum2 = Eigen::Vector3d::Zero();
  double max_step = 0.0;
  const int n = 400000;  // 4000 s, 800 correlation times
  Eigen::Vector3d previous = c.velocity_world_mps();
  for (int i = 0; i < n; ++i) {
    c.step(dt);
    const Eigen::Vector3d v = c.velocity_world_mps();
    sum += v;
    sum2 += v.cwiseProduct(v);
    max_step = std::max(max_step, (v - previous).norm());
    previous = v;
  }
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Vector3d sd = (sum2 / n - mean.cwiseProduct(mean)).cwiseSqrt();
  EXPECT_NEAR(mean.x(), 0.08, 0.006);
  EXPECT_NEAR(mean.y(), -0.02, 0.006);
  EXPECT_DOUBLE_EQ(mean.z(), 0.0);
  EXPECT_NEAR(sd.x(), 0.02, 0.004);
  EXPECT_NEAR(sd.y(), 0.02, 0.004);
  // Slowly varying: no jumps from one step to the next.
  EXPECT_LT(max_step, 0.001);
  EXPECT_LT(c.rate_world_mps2().norm(), 0.05);
}

TEST(WaterCurrent, SameSeedSameCurrent) {
  WaterCurrentParams p;
  WaterCurrent a(p, 7), b(p, 7), other(p, 8);
  for (int i = 0; i < 1000; ++i) {
    a.step(0.002);
    b.step(0.002);
    other.step(0.002);
  }
  EXPECT_EQ(a.velocity_world_mps(), b.velocity_world_mps());
  EXPECT_NE(a.velocity_world_mps(), other.velocity_world_mps());
}

}  // namespace
}  // namespace rovctl::hal::mock
