// Thruster response: deadband, saturation, forward/reverse asymmetry, lag and the ESC timeout.
#include "hal/mock/thruster_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rovctl::hal::mock {
namespace {

ThrusterCommand all(double fraction) {
  ThrusterCommand c;
  c.count = 8;
  c.thrust_fraction.fill(fraction);
  return c;
}

TEST(ThrusterModel, DeadbandSaturationAndAsymmetry) {
  const ThrusterLayout layout = ThrusterLayout::bluerov2_heavy();
  ThrusterModelParams p;
  p.deadband = 0.05;
  const ThrusterModel m(layout, p);
  EXPECT_EQ(m.static_thrust_n(0, 0.04), 0.0);
  EXPECT_EQ(m.static_thrust_n(0, -0.049), 0.0);
  EXPECT_GT(m.static_thrust_n(0, 0.06), 0.0);
  EXPECT_DOUBLE_EQ(m.static_thrust_n(0, 1.0), layout.thrusters[0].max_forward_n);
  EXPECT_DOUBLE_EQ(m.static_thrust_n(0, 3.0), layout.thrusters[0].max_forward_n);  // saturated
  EXPECT_DOUBLE_EQ(m.static_thrust_n(0, -1.0), -layout.thrusters[0].max_reverse_n);
  EXPECT_DOUBLE_EQ(m.static_thrust_n(0, -7.0), -layout.thrusters[0].max_reverse_n);
  // Reverse is weaker than forward for the same command.
  EXPECT_LT(std::abs(m.static_thrust_n(0, -0.5)), m.static_thrust_n(0, 0.5));
  // Linear past the deadband: half-way past it is half thrust.
  EXPECT_NEAR(m.static_thrust_n(0, 0.05 + 0.95 * 0.5), 0.5 * layout.thrusters[0].max_forward_n,
              1e-9);
}

TEST(ThrusterModel, FirstOrderLag) {
  const ThrusterLayout layout = ThrusterLayout::bluerov2_heavy();
  ThrusterModelParams p;
  p.deadband = 0.0;
  p.time_constant_s = 0.1;
  ThrusterModel m(layout, p);
  m.command(all(1.0), 0.0);
  double t = 0.0;
  for (int i = 0; i < 50; ++i) m.step(t += 0.002, 0.002);  // one time constant
  EXPECT_NEAR(m.thrust_n(0) / layout.thrusters[0].max_forward_n, 1.0 - std::exp(-1.0), 1e-9);
  for (int i = 0; i < 50; ++i) m.step(t += 0.002, 0.002);
  EXPECT_NEAR(m.thrust_n(0) / layout.thrusters[0].max_forward_n, 1.0 - std::exp(-2.0), 1e-9);
}

TEST(ThrusterModel, GoesNeutralWhenCommandsStop) {
  ThrusterModelParams p;
  p.time_constant_s = 0.0;
  p.command_timeout_s = 0.2;
  ThrusterModel m(ThrusterLayout::bluerov2_heavy(), p);
  m.command(all(0.8), 1.0);
  m.step(1.1, 0.1);
  EXPECT_GT(m.thrust_n(3), 0.0);
  m.step(1.25, 0.15);  // 0.25 s after the last command
  EXPECT_EQ(m.thrust_n(3), 0.0);
  EXPECT_TRUE(m.timed_out(1.25));
}

TEST(ThrusterModel, NonFiniteCommandIsNeutral) {
  ThrusterModelParams p;
  p.time_constant_s = 0.0;
  ThrusterModel m(ThrusterLayout::bluerov2_heavy(), p);
  ThrusterCommand c = all(0.5);
  c.thrust_fraction[2] = std::numeric_limits<double>::quiet_NaN();
  m.command(c, 0.0);
  m.step(0.002, 0.002);
  EXPECT_EQ(m.thrust_n(2), 0.0);
  EXPECT_GT(m.thrust_n(1), 0.0);
  EXPECT_TRUE(m.wrench_body().allFinite());
}

TEST(ThrusterModel, CommandsFollowTheBusChannel) {
  ThrusterLayout layout = ThrusterLayout::bluerov2_heavy();
  std::swap(layout.thrusters[0].channel, layout.thrusters[1].channel);
  ThrusterModelParams p;
  p.time_constant_s = 0.0;
  ThrusterModel m(layout, p);
  ThrusterCommand c;
  c.count = 8;
  c.thrust_fraction[1] = 1.0;  // channel 1 is now thruster 0
  m.command(c, 0.0);
  m.step(0.002, 0.002);
  EXPECT_GT(m.thrust_n(0), 0.0);
  EXPECT_EQ(m.thrust_n(1), 0.0);
}

}  // namespace
}  // namespace rovctl::hal::mock
