// DisturbanceEstimate: integration and its clamp (configured and the thrusters' share), carried
// round as the body turns, held axes, frozen while saturated, settled, beyond hold.
#include "control/disturbance_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rovctl::control {
namespace {

using Vector6d = DisturbanceEstimate::Vector6d;

Vector6d gains() { return (Vector6d() << 10.0, 10.0, 10.0, 0.0, 0.0, 0.3).finished(); }
Vector6d limits() { return (Vector6d() << 50.0, 50.0, 20.0, 1.0, 1.0, 1.0).finished(); }

Vector6d along(int axis, double value) {
  Vector6d e = Vector6d::Zero();
  e[axis] = value;
  return e;
}

Eigen::Matrix3d yaw(double rad) {
  return Eigen::AngleAxisd(rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

TEST(DisturbanceEstimate, IntegratesTheErrorWithinTheThrustersShare) {
  DisturbanceParams p;
  p.hold_fraction = 0.5;
  DisturbanceEstimate d(gains(), limits(), p);
  for (int k = 0; k < 10; ++k) d.integrate(along(1, 0.1), 0.1, false);  // 1 s at 0.1 m
  EXPECT_NEAR(d.wrench_body()[1], 10.0 * 0.1 * 1.0, 1e-9);
  EXPECT_EQ(d.wrench_body()[3], 0.0);  // no gain, no estimate
  for (int k = 0; k < 1000; ++k) d.integrate(along(1, 0.1), 0.1, false);
  EXPECT_NEAR(d.wrench_body()[1], 50.0, 1e-9);  // the configured limit
  // The thrusters make 40 N along y: half of it is the estimate's.
  Vector6d capacity = Vector6d::Constant(100.0);
  capacity[1] = 40.0;
  d.set_capacity(capacity);
  EXPECT_NEAR(d.wrench_body()[1], 20.0, 1e-9);
  EXPECT_TRUE(d.at_limit());
  d.set_axis(1, -100.0);
  EXPECT_NEAR(d.wrench_body()[1], -20.0, 1e-9);
}

TEST(DisturbanceEstimate, TurnsBackAsTheBodyTurns) {
  DisturbanceEstimate d(gains(), limits(), DisturbanceParams{});
  d.set_axis(0, 6.0);  // pushing forward against a current from ahead
  // The body turns 90 deg to starboard: the current now comes from port, the push is to port
  // (body -y) in the new body frame.
  d.turn(yaw(M_PI / 2.0).transpose());
  EXPECT_NEAR(d.wrench_body()[0], 0.0, 1e-9);
  EXPECT_NEAR(d.wrench_body()[1], -6.0, 1e-9);
  // A held axis keeps its body value.
  d.set_axis(0, 3.0);
  d.hold_axis(0, true);
  d.turn(yaw(0.3));
  EXPECT_NEAR(d.wrench_body()[0], 3.0, 1e-12);
  d.integrate(along(0, 1.0), 0.1, false);
  EXPECT_NEAR(d.wrench_body()[0], 3.0, 1e-12);
  d.reset();
  EXPECT_TRUE(d.wrench_body().isZero());
  d.integrate(along(0, 1.0), 0.1, false);  // released by reset()
  EXPECT_GT(d.wrench_body()[0], 0.0);
}

TEST(DisturbanceEstimate, OnlyShrinksWhileTheThrustersSaturate) {
  DisturbanceEstimate d(gains(), limits(), DisturbanceParams{});
  d.set_axis(1, 5.0);
  d.integrate(along(1, 0.1), 0.1, true);
  EXPECT_NEAR(d.wrench_body()[1], 5.0, 1e-12);
  d.integrate(along(1, -0.1), 0.1, true);
  EXPECT_NEAR(d.wrench_body()[1], 4.9, 1e-12);
}

TEST(DisturbanceEstimate, SettlesOnceItStopsChanging) {
  DisturbanceParams p;
  p.settle_rate_nps = 0.5;
  p.settle_s = 1.0;
  DisturbanceEstimate d(gains(), limits(), p);
  // Learning a 0.1 m offset: 1 N/s, not settled.
  for (int k = 0; k < 60; ++k) d.integrate(along(1, 0.1), 1.0 / 30.0, false);
  EXPECT_FALSE(d.settled());
  EXPECT_GT(d.rate_nps(), 0.5);
  // The error gone: the rate decays under the threshold, then a second passes.
  int ticks_to_settle = 0;
  while (!d.settled() && ticks_to_settle < 300) {
    d.integrate(Vector6d::Zero(), 1.0 / 30.0, false);
    ++ticks_to_settle;
  }
  EXPECT_TRUE(d.settled());
  EXPECT_GT(ticks_to_settle, 30);   // at least settle_s
  EXPECT_LT(ticks_to_settle, 150);  // and not much more than the low-pass takes
  // A push that changes (a 0.2 m error: 2 N/s) unsettles it within half a second.
  int ticks_to_unsettle = 0;
  while (d.settled() && ticks_to_unsettle < 300) {
    d.integrate(along(0, 0.2), 1.0 / 30.0, false);
    ++ticks_to_unsettle;
  }
  EXPECT_FALSE(d.settled());
  EXPECT_LT(ticks_to_unsettle, 15);
}

// The servo integrates its error plus kd / kp of its rate, so the estimator's frame-to-frame
// noise reaches the estimate as jitter (here 10 x 0.67 x 20 mm: about 0.13 N) whose derivative
// is several N/s; the steady push has not changed, and it stays settled.
TEST(DisturbanceEstimate, StaysSettledThroughTheEstimatorsNoise) {
  DisturbanceParams p;
  p.settle_rate_nps = 0.5;
  p.settle_s = 1.0;
  DisturbanceEstimate d(gains(), limits(), p);
  d.set_axis(1, 8.0);
  const double dt_s = 1.0 / 30.0;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise_m(0.0, 0.02);
  double last_m = 0.0;
  int settled_ticks = 0;
  for (int k = 0; k < 900; ++k) {
    const double now_m = noise_m(rng);
    d.integrate(along(1, 0.67 * (now_m - last_m) / dt_s), dt_s, false);
    last_m = now_m;
    if (k >= 60) settled_ticks += d.settled() ? 1 : 0;
  }
  EXPECT_EQ(settled_ticks, 900 - 60);
  EXPECT_NEAR(d.wrench_body()[1], 8.0, 0.5);
}

TEST(DisturbanceEstimate, BeyondHoldAfterItsTimeAtTheLimit) {
  DisturbanceParams p;
  p.beyond_hold_s = 2.0;
  DisturbanceEstimate d(gains(), limits(), p);
  d.set_axis(1, 50.0);
  for (int k = 0; k < 59; ++k) d.integrate(along(1, 0.1), 1.0 / 30.0, false);
  EXPECT_TRUE(d.at_limit());
  EXPECT_FALSE(d.beyond_hold());
  d.integrate(along(1, 0.1), 1.0 / 30.0, false);
  d.integrate(along(1, 0.1), 1.0 / 30.0, false);
  EXPECT_TRUE(d.beyond_hold());
  EXPECT_NEAR(d.hold_ratio(), 1.0, 1e-9);
  // Back off the limit: no longer.
  d.integrate(along(1, -10.0), 1.0 / 30.0, false);
  EXPECT_FALSE(d.at_limit());
  EXPECT_FALSE(d.beyond_hold());
  // Saturated thrusters count too, the estimate anywhere.
  d.set_axis(1, 1.0);
  for (int k = 0; k < 61; ++k) d.integrate(Vector6d::Zero(), 1.0 / 30.0, true);
  EXPECT_TRUE(d.beyond_hold());
}

TEST(DisturbanceEstimate, RisesUntilItSettlesOncePastItsSweptFraction) {
  DisturbanceParams p;
  p.settle_s = 1.0;
  p.swept_fraction = 0.3;
  DisturbanceEstimate d(gains(), limits(), p);
  // Growing along itself, but still under 30 % of its 50 N limit: not counted.
  for (int k = 0; k < 30; ++k) d.integrate(along(1, 0.5), 1.0 / 30.0, false);
  EXPECT_LT(d.hold_ratio(), 0.3);
  EXPECT_FALSE(d.rising());
  // Past it and still growing.
  for (int k = 0; k < 90; ++k) d.integrate(along(1, 0.5), 1.0 / 30.0, false);
  EXPECT_GT(d.hold_ratio(), 0.3);
  EXPECT_TRUE(d.rising());
  // Stopped by saturated thrusters: it no longer grows, yet has not found the push.
  for (int k = 0; k < 120; ++k) d.integrate(along(1, 0.5), 1.0 / 30.0, true);
  EXPECT_LT(d.rate_nps(), 0.1);
  EXPECT_TRUE(d.rising());
  // The thrusters hold it: the error gone, it settles and no longer rises.
  for (int k = 0; k < 150 && !d.settled(); ++k) d.integrate(Vector6d::Zero(), 1.0 / 30.0, false);
  EXPECT_TRUE(d.settled());
  EXPECT_FALSE(d.rising());
  // Held at its limit: not settled, and rising.
  d.set_axis(1, 50.0);
  for (int k = 0; k < 90; ++k) d.integrate(along(1, 0.1), 1.0 / 30.0, false);
  EXPECT_FALSE(d.settled());
  EXPECT_TRUE(d.rising());
}

}  // namespace
}  // namespace rovctl::control
