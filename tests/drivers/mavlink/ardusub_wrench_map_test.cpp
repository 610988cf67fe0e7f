// The allocator's fractions back to the wrench, and the wrench as MANUAL_CONTROL axes: scale,
// pilot gain, ArduSub's z convention (500 neutral, climb above), clamping, and NaN as neutral.
#include "drivers/mavlink/ardusub_wrench_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rovctl::drivers {
namespace {

hal::ThrusterCommand command(std::initializer_list<double> fractions) {
  hal::ThrusterCommand c;
  for (double f : fractions) c.thrust_fraction[c.count++] = f;
  return c;
}

TEST(ArdusubWrenchMap, NeutralFractionsAreNeutralAxes) {
  const ArdusubWrenchMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 0.5);
  EXPECT_EQ(map.axes(command({0, 0, 0, 0, 0, 0, 0, 0})), (ArdusubAxes{0, 0, 500, 0}));
}

TEST(ArdusubWrenchMap, WrenchIsTheLayoutsConfigurationTimesThrust) {
  const hal::ThrusterLayout layout = hal::ThrusterLayout::bluerov2_heavy();
  const ArdusubWrenchMap map(layout, ArdusubAxisScale{}, 1.0);
  const hal::ThrusterCommand c = command({0.3, -0.2, 0.1, 0.4, -0.5, 0.6, 0.0, -0.1});
  Eigen::VectorXd thrust_n(8);
  for (int i = 0; i < 8; ++i) {
    const double f = c.thrust_fraction[static_cast<std::size_t>(i)];
    const auto& t = layout.thrusters[static_cast<std::size_t>(i)];
    thrust_n(i) = f >= 0 ? f * t.max_forward_n : f * t.max_reverse_n;
  }
  const Eigen::Matrix<double, 6, 1> expected = layout.configuration_matrix() * thrust_n;
  EXPECT_LT((map.wrench(c) - expected).norm(), 1e-9);
}

TEST(ArdusubWrenchMap, SurgeScalesByFullStickAndPilotGain) {
  // The four horizontal thrusters of the Heavy all forward: pure surge, 4 cos45 f F_max.
  const hal::ThrusterCommand c = command({0.5, 0.5, 0.5, 0.5, 0, 0, 0, 0});
  const double fx = 4.0 * std::sqrt(0.5) * 0.5 * 51.5;
  const ArdusubWrenchMap gain1(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 1.0);
  const ArdusubAxes a = gain1.axes(c);
  EXPECT_EQ(a.x, std::lround(1000.0 * fx / 130.0));
  EXPECT_EQ(a.y, 0);
  EXPECT_EQ(a.z, 500);
  EXPECT_EQ(a.r, 0);
  // Half the gain needs twice the stick for the same force; here that saturates.
  const ArdusubWrenchMap gain_half(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 0.5);
  EXPECT_EQ(gain_half.axes(c).x, 1000);
  EXPECT_EQ(gain_half.axes(command({-1, -1, -1, -1, 0, 0, 0, 0})).x, -1000);
}

TEST(ArdusubWrenchMap, UpwardForceRaisesZAboveNeutral) {
  // The vertical thrusters push down (body +z) at a positive command: reversed, the vehicle
  // climbs, which ArduSub reads as throttle above 500.
  const ArdusubWrenchMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 1.0);
  const double up_n = 4.0 * 0.5 * 40.2;
  const ArdusubAxes up = map.axes(command({0, 0, 0, 0, -0.5, -0.5, -0.5, -0.5}));
  EXPECT_EQ(up.z, std::lround(500.0 + 500.0 * up_n / 183.0));
  const ArdusubAxes down = map.axes(command({0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(down.z, 0);  // 206 N down is beyond full stick: clamped
}

TEST(ArdusubWrenchMap, YawAndSwayFollowTheBodyFrame) {
  const ArdusubWrenchMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 1.0);
  // Equal newtons forward and reversed (the T200 is weaker in reverse).
  const double fwd = 0.4 * 40.2 / 51.5;
  // t1 and t4 (front right, rear left) point forward-left; reversed they push starboard, the
  // others forward: t2/t3 reversed too makes pure starboard sway.
  const ArdusubAxes sway = map.axes(command({-0.4, fwd, fwd, -0.4, 0, 0, 0, 0}));
  EXPECT_GT(sway.y, 0);
  EXPECT_EQ(sway.x, 0);
  EXPECT_EQ(sway.r, 0);
  // Front left and rear right forward, the others reversed: clockwise from above (+ yaw).
  const ArdusubAxes yaw = map.axes(command({-0.4, fwd, -0.4, fwd, 0, 0, 0, 0}));
  EXPECT_GT(yaw.r, 0);
  EXPECT_EQ(yaw.x, 0);
  EXPECT_EQ(yaw.y, 0);
}

TEST(ArdusubWrenchMap, NonFiniteFractionsNeverLeaveAsFullStick) {
  const ArdusubWrenchMap map(hal::ThrusterLayout::bluerov2_heavy(), ArdusubAxisScale{}, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(map.axes(command({nan, 0, 0, 0, 0, 0, 0, nan})), (ArdusubAxes{0, 0, 500, 0}));
}

}  // namespace
}  // namespace rovctl::drivers
