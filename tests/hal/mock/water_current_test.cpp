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

namespace rovctl::hal::mock {
namespace {

TEST(WaterCurrent, TideTurnsTheMeanAndGustsBlowAlongIt) {
  WaterCurrentParams p;
  p.mean_world_mps = {0.1, 0.0, 0.0};
  p.random_sigma_mps.setZero();
  p.tide_turn_degps = 9.0;  // a quarter turn in 10 s
  WaterCurrent c(p, 3);
  for (int i = 0; i < 1000; ++i) c.step(0.01);
  EXPECT_NEAR(c.velocity_world_mps().x(), 0.0, 1e-6);
  EXPECT_NEAR(c.velocity_world_mps().y(), 0.1, 1e-6);

  p.tide_turn_degps = 0.0;
  p.gust_peak_mps = 0.1;
  p.gust_interval_s = 5.0;
  p.gust_duration_s = 2.0;
  WaterCurrent g(p, 3);
  double peak = 0.0;
  double max_step = 0.0;
  Eigen::Vector3d previous = g.velocity_world_mps();
  for (int i = 0; i < 60000; ++i) {  // 600 s: about a hundred gusts
    g.step(0.01);
    const Eigen::Vector3d v = g.velocity_world_mps();
    EXPECT_NEAR(v.y(), 0.0, 1e-12);  // along the mean
    peak = std::max(peak, v.x() - 0.1);
    max_step = std::max(max_step, (v - previous).norm());
    previous = v;
  }
  EXPECT_GT(peak, 0.08);
  EXPECT_LE(peak, 0.1 + 1e-9);
  EXPECT_LT(max_step, 0.002);  // smooth pulses, no jumps
}

TEST(WaterCurrent, NoTideNoGustsLeavesTheCurrentAsItWas) {
  WaterCurrentParams p;
  p.mean_world_mps = {0.05, 0.02, 0.0};
  WaterCurrent a(p, 11);
  p.gust_duration_s = 1.0;  // a gust setting without gusts changes nothing
  WaterCurrent b(p, 11);
  for (int i = 0; i < 1000; ++i) {
    a.step(0.01);
    b.step(0.01);
  }
  EXPECT_EQ(a.velocity_world_mps(), b.velocity_world_mps());
}

}  // namespace
}  // namespace rovctl::hal::mock
