// PdVisualServo: sign conventions per axis, the 4-DOF default, filtered derivative, integral with
// anti-windup, error clipping, the turn limited to keep the marker in view, feed-forward,
// non-finite input.
#include "control/pd_visual_servo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

struct Fixture : ::testing::Test {
  hal::VehicleGeometry geometry;
  Eigen::Isometry3d T_body_cl = geometry.T_body_cl();
  Eigen::Isometry3d desired =
      hal::docked_T_cl_marker(T_body_cl, geometry.probe_tip_body_m, hal::DockingStation{});

  // The measured T_cl_marker when the marker sits at `T_bodynow_bodydesired` * (desired pose):
  // i.e. the desired body frame is at that pose in the current body frame.
  Eigen::Isometry3d measured(const Eigen::Isometry3d& T_now_desired) const {
    return T_body_cl.inverse() * T_now_desired * T_body_cl * desired;
  }
  static Eigen::Isometry3d moved(const Eigen::Vector3d& t) {
    return Eigen::Isometry3d(Eigen::Translation3d(t));
  }
  static Eigen::Isometry3d turned(double angle, const Eigen::Vector3d& axis) {
    return Eigen::Isometry3d(Eigen::AngleAxisd(angle, axis));
  }
  static ServoParams params() {
    ServoParams p;
    p.net_buoyancy_n = 0.0;
    p.ki_linear.setZero();
    p.ki_angular.setZero();
    p.kp_angular = {5.0, 6.0, 7.0};
    return p;
  }
};

using PdVisualServoTest = Fixture;

TEST_F(PdVisualServoTest, ZeroErrorZeroWrench) {
  PdVisualServo servo(params(), T_body_cl);
  EXPECT_LT(servo.update(desired, desired, 33ms).norm(), 1e-9);
}

TEST_F(PdVisualServoTest, SignConventionPerTranslationAxis) {
  const ServoParams p = params();
  for (int axis = 0; axis < 3; ++axis) {
    // The docked pose lies 0.1 m along +axis of the body: forward, starboard, down.
    PdVisualServo servo(p, T_body_cl);
    const Eigen::Vector3d d = 0.1 * Eigen::Vector3d::Unit(axis);
    const Wrench w = servo.update(measured(moved(d)), desired, 33ms);
    EXPECT_NEAR(w[axis], p.kp_linear[axis] * 0.1, 1e-9) << "axis " << axis;
    for (int j = 0; j < 6; ++j) {
      if (j != axis) {
        EXPECT_NEAR(w[j], 0.0, 1e-9) << "axis " << axis << " leaks into " << j;
      }
    }
  }
}

TEST_F(PdVisualServoTest, SignConventionYaw) {
  // The docked heading is 0.1 rad to starboard: turn right, positive Mz about body z (down).
  const ServoParams p = params();
  PdVisualServo servo(p, T_body_cl);
  const Wrench w = servo.update(measured(turned(0.1, Eigen::Vector3d::UnitZ())), desired, 33ms);
  EXPECT_NEAR(w[5], p.kp_angular[2] * 0.1, 1e-9);
  EXPECT_NEAR(w.head<3>().norm(), 0.0, 1e-9);  // turning about the body origin: no translation
  // Seen in the camera, the marker's docking axis then points to the right of the optical axis.
  const Eigen::Vector3d axis_cl = measured(turned(0.1, Eigen::Vector3d::UnitZ())).linear().col(2);
  EXPECT_GT(axis_cl.x(), 0.0);
}

TEST_F(PdVisualServoTest, RollAndPitchOnlyInSixDof) {
  ServoParams p = params();
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::Isometry3d m = measured(turned(0.05, Eigen::Vector3d::Unit(axis)));
    p.six_dof = false;
    PdVisualServo four(p, T_body_cl);
    const Wrench w4 = four.update(m, desired, 33ms);
    EXPECT_NEAR(w4[3 + axis], 0.0, 1e-12);
    p.six_dof = true;
    PdVisualServo six(p, T_body_cl);
    const Wrench w6 = six.update(m, desired, 33ms);
    EXPECT_NEAR(w6[3 + axis], p.kp_angular[axis] * 0.05, 1e-9) << "axis " << axis;
    EXPECT_NEAR(w6.head<3>().norm(), 0.0, 1e-9);
  }
}

TEST_F(PdVisualServoTest, FourDofYawIgnoresRollAndPitch) {
  // Pitched and yawed: the 4-DOF yaw is the docking axis's heading in the body x-y plane.
  const double yaw = 0.08;
  const Eigen::Isometry3d m =
      measured(turned(yaw, Eigen::Vector3d::UnitZ()) * turned(0.2, Eigen::Vector3d::UnitY()));
  const PoseError e = pose_error_body(T_body_cl, m, desired, false);
  EXPECT_NEAR(e[5], yaw, 1e-9);
}

TEST_F(PdVisualServoTest, DerivativeOpposesTheApproach) {
  // The vehicle closes a 1 m surge error at 0.3 m/s: the filtered rate is about -0.3 m/s and the
  // D term brakes.
  ServoParams p = params();
  PdVisualServo servo(p, T_body_cl);
  Wrench w = Wrench::Zero();
  double e = 1.0;
  for (int k = 0; k < 60; ++k, e -= 0.3 * 0.033) {
    w = servo.update(measured(moved({e, 0, 0})), desired, 33ms);
  }
  e += 0.3 * 0.033;
  EXPECT_NEAR(servo.error_rate()[0], -0.3, 0.01);
  EXPECT_NEAR(w[0], p.kp_linear[0] * std::min(e, p.max_position_error_m) - p.kd_linear[0] * 0.3,
              p.kd_linear[0] * 0.01);
}

TEST_F(PdVisualServoTest, DerivativeIsFilteredNotARawDifference) {
  // Hovering at the goal with 5 mm of estimate noise: the D term's jitter is far below what
  // kd times a raw difference would give.
  ServoParams p = params();
  p.kp_linear.setZero();
  PdVisualServo servo(p, T_body_cl);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.005);
  double sq = 0.0;
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    const Wrench w = servo.update(measured(moved({noise(rng), 0, 0})), desired, 33ms);
    sq += w[0] * w[0];
  }
  const double rms = std::sqrt(sq / n);
  const double raw_rms = p.kd_linear[0] * std::sqrt(2.0) * 0.005 / 0.033;
  EXPECT_LT(rms, 0.4 * raw_rms) << "D jitter " << rms << " N, raw " << raw_rms << " N";
}

TEST_F(PdVisualServoTest, GapRestartsTheDerivative) {
  PdVisualServo servo(params(), T_body_cl);
  servo.update(measured(moved({0.3, 0, 0})), desired, 33ms);
  servo.update(measured(moved({0.1, 0, 0})), desired, 2s);  // long gap: no kick
  EXPECT_TRUE(servo.error_rate().isZero());
}

TEST_F(PdVisualServoTest, IntegralAccumulatesAndIsClamped) {
  ServoParams p = params();
  p.kp_linear.setZero();
  p.kd_linear.setZero();
  p.ki_linear = {10.0, 10.0, 10.0};
  p.integral_limit_linear_n = {2.0, 2.0, 2.0};
  PdVisualServo servo(p, T_body_cl);
  const Eigen::Isometry3d m = measured(moved({0.0, 0.05, 0.0}));
  Wrench w = servo.update(m, desired, 33ms);
  for (int k = 0; k < 30; ++k) w = servo.update(m, desired, 100ms);  // 3 s
  EXPECT_NEAR(w[1], 10.0 * 0.05 * 3.0 + 10.0 * 0.05 * 0.033, 1e-6);
  for (int k = 0; k < 100; ++k) w = servo.update(m, desired, 100ms);
  EXPECT_NEAR(w[1], 2.0, 1e-9);  // anti-windup limit
  // The other sign unwinds at once from the limit, not from a wound-up state.
  const Eigen::Isometry3d back = measured(moved({0.0, -0.05, 0.0}));
  w = servo.update(back, desired, 100ms);
  EXPECT_NEAR(w[1], 2.0 - 10.0 * 0.05 * 0.1, 1e-9);
}

TEST_F(PdVisualServoTest, IntegralFreezesWhileSaturated) {
  ServoParams p = params();
  p.kp_linear.setZero();
  p.kd_linear.setZero();
  p.ki_linear = {10.0, 10.0, 10.0};
  PdVisualServo servo(p, T_body_cl);
  const Eigen::Isometry3d m = measured(moved({0.1, 0.0, 0.0}));
  servo.update(m, desired, 33ms);
  const double before = servo.update(m, desired, 100ms)[0];
  servo.set_allocation_fraction(0.6);
  EXPECT_NEAR(servo.update(m, desired, 100ms)[0], before, 1e-12);
  servo.set_allocation_fraction(1.0);
  EXPECT_GT(servo.update(m, desired, 100ms)[0], before);
  // Holding trim while blind: the integral is what pushes against the current.
  EXPECT_NEAR(servo.hold_wrench_body()[0], servo.integral_term()[0], 1e-12);
  EXPECT_GT(servo.hold_wrench_body()[0], 0.0);
  servo.reset();
  EXPECT_TRUE(servo.integral_term().isZero());
}

TEST_F(PdVisualServoTest, OneIntegralAxisCanBeSetAndHeld) {
  ServoParams p = params();
  p.kp_linear.setZero();
  p.kd_linear.setZero();
  p.ki_linear = {10.0, 10.0, 10.0};
  p.integral_limit_linear_n = {8.0, 8.0, 8.0};
  PdVisualServo servo(p, T_body_cl);
  servo.set_integral_term(0, 3.5);
  EXPECT_NEAR(servo.integral_term()[0], 3.5, 1e-12);
  servo.set_integral_term(0, 50.0);  // clamped to the anti-windup limit
  EXPECT_NEAR(servo.integral_term()[0], 8.0, 1e-12);
  servo.set_integral_term(0, 2.0);
  servo.hold_integral(0, true);
  const Eigen::Isometry3d m = measured(moved({0.1, 0.1, 0.0}));
  servo.update(m, desired, 33ms);
  servo.update(m, desired, 100ms);
  EXPECT_NEAR(servo.integral_term()[0], 2.0, 1e-12);  // held
  EXPECT_GT(servo.integral_term()[1], 0.0);           // the other axes integrate
  servo.hold_integral(0, false);
  servo.update(m, desired, 100ms);
  EXPECT_GT(servo.integral_term()[0], 2.0);
  servo.hold_integral(0, true);
  servo.reset();  // releases the hold
  servo.update(m, desired, 33ms);
  servo.update(m, desired, 100ms);
  EXPECT_GT(servo.integral_term()[0], 0.0);
}

TEST_F(PdVisualServoTest, LargeErrorsAreClipped) {
  ServoParams p = params();
  PdVisualServo servo(p, T_body_cl);
  const Wrench w = servo.update(measured(moved({5.0, 0, 0})), desired, 33ms);
  EXPECT_NEAR(w[0], p.kp_linear[0] * p.max_position_error_m, 1e-9);
}

TEST_F(PdVisualServoTest, BuoyancyFeedForwardPushesDown) {
  ServoParams p = params();
  p.net_buoyancy_n = 3.0;
  PdVisualServo servo(p, T_body_cl);
  const Wrench w = servo.update(desired, desired, 33ms);
  EXPECT_NEAR(w[2], 3.0, 1e-12);
  EXPECT_NEAR(servo.feedforward_body()[2], 3.0, 1e-12);
}

TEST_F(PdVisualServoTest, MarkerBearingIsTheTurnThatCentresIt) {
  // A forward camera: its x to starboard, y down, z forward.
  Eigen::Matrix3d R_body_cl;
  R_body_cl << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  Eigen::Isometry3d T_body_cam = Eigen::Isometry3d::Identity();
  T_body_cam.linear() = R_body_cl;
  T_body_cam.translation() = Eigen::Vector3d(0.2, -0.1, 0.05);
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  T_cl_marker.translation() = Eigen::Vector3d(0.0, 0.1, 0.7);
  EXPECT_NEAR(marker_bearing_rad(T_body_cam, T_cl_marker), 0.0, 1e-12);
  T_cl_marker.translation() = Eigen::Vector3d(0.4, -0.2, 0.4);  // 45 deg to starboard
  EXPECT_NEAR(marker_bearing_rad(T_body_cam, T_cl_marker), M_PI / 4, 1e-12);
  T_cl_marker.translation() = Eigen::Vector3d(-0.3, 0.0, 0.3 * std::sqrt(3.0));  // 30 to port
  EXPECT_NEAR(marker_bearing_rad(T_body_cam, T_cl_marker), -M_PI / 6, 1e-12);
}

TEST_F(PdVisualServoTest, KeepInViewLimitsTheTurnToWhatKeepsTheMarkerInSight) {
  // The station 1 m ahead and 0.1 m to one side, its docking axis 1 rad round the same way:
  // turning the whole radian would put the marker past the camera's edge.
  const double limit = 0.26;
  for (const double side : {1.0, -1.0}) {
    const Eigen::Isometry3d m =
        measured(moved({1.0, side * 0.1, 0.0}) * turned(side * 1.0, Eigen::Vector3d::UnitZ()));
    const double b = marker_bearing_rad(T_body_cl, m);
    ASSERT_GT(side * b, 0.2) << "side " << side;
    ASSERT_LT(side * (b + side * limit), 1.0) << "side " << side;
    PdVisualServo free_turn(params(), T_body_cl);
    free_turn.update(m, desired, 33ms);
    EXPECT_NEAR(free_turn.error()[5], side * 1.0, 1e-9);
    PdVisualServo servo(params(), T_body_cl);
    servo.keep_in_view(limit);
    servo.update(m, desired, 33ms);
    // Turned by the error, the marker stays `limit` inside; the translation is not touched.
    EXPECT_NEAR(servo.error()[5], b + side * limit, 1e-9) << "side " << side;
    EXPECT_NEAR(std::abs(b - servo.error()[5]), limit, 1e-9);
    EXPECT_TRUE(servo.error().head<3>().isApprox(free_turn.error().head<3>()));
    // A turn that keeps the marker in sight is left as it is, and 0 lifts the limit.
    const Eigen::Isometry3d small =
        measured(moved({0.8, side * 0.05, 0.0}) * turned(side * 0.1, Eigen::Vector3d::UnitZ()));
    servo.update(small, desired, 33ms);
    EXPECT_NEAR(servo.error()[5], side * 0.1, 1e-9);
    servo.keep_in_view(0.0);
    servo.update(m, desired, 33ms);
    EXPECT_NEAR(servo.error()[5], side * 1.0, 1e-9);
  }
}

TEST_F(PdVisualServoTest, NonFiniteInputGivesNaNAndKeepsState) {
  PdVisualServo servo(params(), T_body_cl);
  servo.update(measured(moved({0.2, 0, 0})), desired, 33ms);
  const PoseError before = servo.error();
  Eigen::Isometry3d bad = desired;
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(servo.update(bad, desired, 33ms).allFinite());
  EXPECT_TRUE(servo.error().isApprox(before));
  EXPECT_TRUE(servo.update(measured(moved({0.2, 0, 0})), desired, 33ms).allFinite());
}

TEST_F(PdVisualServoTest, TheIntegralTurnsWithTheStationAsTheBodyTurns) {
  ServoParams p = params();
  p.kp_linear.setZero();
  p.kd_linear.setZero();
  p.ki_linear = {10.0, 10.0, 10.0};
  PdVisualServo servo(p, T_body_cl);
  const Eigen::Isometry3d m = measured(moved({0.0, 0.1, 0.0}));
  servo.update(m, desired, 33ms);
  for (int k = 0; k < 10; ++k) servo.update(m, desired, 100ms);
  const double learnt = servo.integral_term()[1];
  ASSERT_GT(learnt, 1.0);
  // Seen again 2 s later (too late to integrate) with the body turned 0.5 rad about z: the push
  // is fixed to the station, so in body axes it has turned by as much.
  const double a = 0.5;
  servo.update(measured(turned(a, Eigen::Vector3d::UnitZ())), desired, 2s);
  EXPECT_NEAR(servo.integral_term()[0], -learnt * std::sin(a), 1e-9);
  EXPECT_NEAR(servo.integral_term()[1], learnt * std::cos(a), 1e-9);
  EXPECT_NEAR(servo.integral_term()[2], 0.0, 1e-9);
}

TEST_F(PdVisualServoTest, ALongApproachDoesNotWindTheIntegralUp) {
  ServoParams p = params();
  p.ki_linear = {20.0, 30.0, 30.0};
  PdVisualServo servo(p, T_body_cl);
  // Closing a clipped error at the speed the gains set (kp x clip / kd): what a calm approach does.
  const double speed = p.kp_linear[0] * p.max_position_error_m / p.kd_linear[0];
  double x = 1.2;
  for (int k = 0; k < 75; ++k, x -= speed * 0.033) {  // 2.5 s
    servo.update(measured(moved({x, 0.0, 0.0})), desired, 33ms);
  }
  ASSERT_GT(x, p.max_position_error_m);
  // A plain integral of the clipped error would hold 20 x 0.2 x 2.5 = 10 N by now.
  EXPECT_LT(std::abs(servo.integral_term()[0]), 1.5);
  // At a standstill off the set-point (once the rate has died away) it integrates the error as a
  // plain integral does: 20 x 0.05 = 1 N/s.
  for (int k = 0; k < 30; ++k) servo.update(measured(moved({0.05, 0.0, 0.0})), desired, 33ms);
  const double before = servo.integral_term()[0];
  for (int k = 0; k < 60; ++k) servo.update(measured(moved({0.05, 0.0, 0.0})), desired, 33ms);
  EXPECT_NEAR(servo.integral_term()[0] - before, 20.0 * 0.05 * 60 * 0.033, 0.2);
}

TEST_F(PdVisualServoTest, ARestartKeepsTheCurrentsEstimateAResetClearsIt) {
  ServoParams p = params();
  p.kp_linear.setZero();
  p.kd_linear.setZero();
  p.ki_linear = {10.0, 10.0, 10.0};
  PdVisualServo servo(p, T_body_cl);
  const Eigen::Isometry3d m = measured(moved({0.0, 0.1, 0.0}));
  servo.update(m, desired, 33ms);
  for (int k = 0; k < 10; ++k) servo.update(m, desired, 100ms);
  const double learnt = servo.integral_term()[1];
  ASSERT_GT(learnt, 1.0);
  servo.hold_integral(1, true);
  servo.restart();
  EXPECT_NEAR(servo.integral_term()[1], learnt, 1e-12);
  servo.update(m, desired, 100ms);
  EXPECT_GT(servo.integral_term()[1], learnt);  // released by the restart
  servo.reset();
  EXPECT_TRUE(servo.integral_term().isZero());
}

}  // namespace
}  // namespace rovctl::control
