// ThrusterEffectiveness: the matrix matches the layout, asymmetric limits, layout checks.
#include "control/thruster_effectiveness.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace rovctl::control {
namespace {

TEST(ThrusterEffectiveness, MatrixIsTheLayoutsConfigurationMatrix) {
  const hal::ThrusterLayout layout = hal::ThrusterLayout::bluerov2_heavy();
  const ThrusterEffectiveness eff(layout);
  ASSERT_EQ(eff.count(), 8u);
  EXPECT_TRUE(eff.matrix().isApprox(layout.configuration_matrix()));
  // A vertical thruster at (0.12, 0.218, 0) pushing down (+z): Fz = 1, Mx = y * 1, My = -x * 1.
  EXPECT_NEAR(eff.matrix()(2, 4), 1.0, 1e-12);
  EXPECT_NEAR(eff.matrix()(3, 4), 0.218, 1e-12);
  EXPECT_NEAR(eff.matrix()(4, 4), -0.120, 1e-12);
}

TEST(ThrusterEffectiveness, ForwardAndReverseScaleDifferently) {
  hal::ThrusterLayout layout;
  hal::Thruster t;
  t.name = "only";
  t.max_forward_n = 50.0;
  t.max_reverse_n = 40.0;
  layout.thrusters = {t};
  const ThrusterEffectiveness eff(layout);
  EXPECT_DOUBLE_EQ(eff.command_for_thrust(0, 25.0), 0.5);
  EXPECT_DOUBLE_EQ(eff.command_for_thrust(0, -20.0), -0.5);
  EXPECT_DOUBLE_EQ(eff.thrust_for_command(0, -1.0), -40.0);
  EXPECT_DOUBLE_EQ(eff.limit_n(0, -1.0), 40.0);
  EXPECT_DOUBLE_EQ(eff.limit_n(0, 1.0), 50.0);
}

TEST(ThrusterEffectiveness, DeadbandRoundTrip) {
  const ThrusterEffectiveness eff(hal::ThrusterLayout::bluerov2_heavy(), 0.0625);
  for (double f : {-40.2, -10.0, -0.01, 0.0, 0.01, 3.0, 51.5}) {
    EXPECT_NEAR(eff.thrust_for_command(0, eff.command_for_thrust(0, f)), f, 1e-12) << f;
  }
  EXPECT_EQ(eff.thrust_for_command(0, 0.05), 0.0);  // inside the deadband
  EXPECT_NEAR(eff.command_for_thrust(0, 51.5), 1.0, 1e-12);
  EXPECT_THROW(ThrusterEffectiveness(hal::ThrusterLayout::bluerov2_heavy(), 1.0),
               std::invalid_argument);
}

TEST(ThrusterEffectiveness, ForwardModelUsesBusChannels) {
  hal::ThrusterLayout layout;
  hal::Thruster a;
  a.name = "a";
  a.direction_body = Eigen::Vector3d::UnitX();
  a.channel = 3;
  hal::Thruster b;
  b.name = "b";
  b.direction_body = Eigen::Vector3d::UnitZ();
  b.channel = 0;
  layout.thrusters = {a, b};
  const ThrusterEffectiveness eff(layout);
  hal::ThrusterCommand cmd;
  cmd.count = 4;
  cmd.thrust_fraction[3] = 0.5;
  cmd.thrust_fraction[0] = -1.0;
  const Wrench w = eff.wrench_for_command(cmd);
  EXPECT_NEAR(w[0], 0.5 * a.max_forward_n, 1e-12);
  EXPECT_NEAR(w[2], -b.max_reverse_n, 1e-12);
}

TEST(ThrusterEffectiveness, RejectsBadLayouts) {
  hal::ThrusterLayout empty;
  EXPECT_THROW(ThrusterEffectiveness{empty}, std::invalid_argument);

  hal::ThrusterLayout nine = hal::ThrusterLayout::bluerov2_heavy();
  nine.thrusters.push_back(nine.thrusters[0]);
  EXPECT_THROW(ThrusterEffectiveness{nine}, std::invalid_argument);

  hal::ThrusterLayout twice = hal::ThrusterLayout::bluerov2_heavy();
  twice.thrusters[1].channel = twice.thrusters[0].channel;
  try {
    ThrusterEffectiveness eff(twice);
    FAIL() << "duplicate channel accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("t2_front_left"), std::string::npos) << e.what();
  }

  hal::ThrusterLayout zero = hal::ThrusterLayout::bluerov2_heavy();
  zero.thrusters[2].direction_body.setZero();
  EXPECT_THROW(ThrusterEffectiveness{zero}, std::invalid_argument);
}

}  // namespace
}  // namespace rovctl::control
