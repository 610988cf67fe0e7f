// pose_confirmation: an ok estimate is trusted only when the frame before had a sound pose it
// agrees with; a sure but wrong frame costs itself and the one after, and nothing is guessed.
#include "estimator/pose_confirmation.hpp"

#include <gtest/gtest.h>

#include "hal/model/pose.hpp"

namespace {

using namespace rovctl;
using namespace std::chrono_literals;
using estimator::ConfirmationParams;
using estimator::NotOkReason;
using estimator::PoseConfirmation;
using estimator::PoseEstimate;

constexpr std::chrono::nanoseconds kFrame = 33ms;

// An ok estimate as the estimator gives one at 1.35 m: 7 mm and 1.4 deg bounds (turbid water).
PoseEstimate ok_at(const Eigen::Vector3d& t_m, double yaw_deg) {
  PoseEstimate e;
  e.recognised = true;
  e.ok = true;
  e.T_cl_marker = hal::make_pose(
      t_m, Eigen::Quaterniond(Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY())));
  e.error_bound_m = 0.007;
  e.error_bound_deg = 1.4;
  return e;
}

const Eigen::Vector3d kAt(0.02, -0.01, 1.35);

TEST(PoseConfirmation, TheFirstFrameIsUnconfirmedAndTheSecondConfirmsIt) {
  PoseConfirmation c{ConfirmationParams{}};
  PoseEstimate first = ok_at(kAt, 0.0);
  c.judge(first, 1s);
  EXPECT_FALSE(first.ok);
  EXPECT_EQ(first.not_ok_reason, NotOkReason::unconfirmed);
  PoseEstimate second = ok_at(kAt + Eigen::Vector3d(0.0, 0.0, -0.005), 0.3);
  c.judge(second, 1s + kFrame);
  EXPECT_TRUE(second.ok);
  EXPECT_EQ(second.not_ok_reason, NotOkReason::none);
}

// The closed loop's turbid case: one frame 11 deg off with a 1.4 deg bound, between right ones.
TEST(PoseConfirmation, AFrameSureButWrongIsNotTrustedNorTheOneAfterIt) {
  PoseConfirmation c{ConfirmationParams{}};
  std::chrono::nanoseconds t = 1s;
  const auto judge = [&](PoseEstimate e) {
    c.judge(e, t);
    t += kFrame;
    return e;
  };
  judge(ok_at(kAt, 0.0));
  EXPECT_TRUE(judge(ok_at(kAt, 0.2)).ok);
  const PoseEstimate wrong = judge(ok_at(kAt, 11.0));
  EXPECT_FALSE(wrong.ok);
  EXPECT_EQ(wrong.not_ok_reason, NotOkReason::unconfirmed);
  // The frame after cannot tell which of the two was wrong: neither is trusted.
  EXPECT_FALSE(judge(ok_at(kAt, 0.4)).ok);
  EXPECT_TRUE(judge(ok_at(kAt, 0.5)).ok);
}

// The vehicle's own motion within its limits is not a disagreement: turning at 40 deg/s, the
// marker 1.35 m out sweeps 31 mm across the image's frame in one period.
TEST(PoseConfirmation, AVehicleTurningWithinItsRateIsConfirmed) {
  PoseConfirmation c{ConfirmationParams{}};
  const double turn_deg = 40.0 * 0.033;
  const Eigen::AngleAxisd turn(turn_deg * M_PI / 180.0, Eigen::Vector3d::UnitY());
  PoseEstimate a = ok_at(kAt, 0.0);
  c.judge(a, 1s);
  PoseEstimate b = a;
  b.T_cl_marker = Eigen::Isometry3d(turn) * a.T_cl_marker;
  b.ok = true;
  b.not_ok_reason = NotOkReason::none;
  ASSERT_GT((b.T_cl_marker.translation() - a.T_cl_marker.translation()).norm(), 0.03);
  c.judge(b, 1s + kFrame);
  EXPECT_TRUE(b.ok);
  // Four times as fast (160 deg/s): past the limit (60 deg/s) and both bounds, not confirmed.
  PoseEstimate fast = b;
  fast.T_cl_marker = Eigen::Isometry3d(Eigen::AngleAxisd(4.0 * turn_deg * M_PI / 180.0,
                                                         Eigen::Vector3d::UnitY())) *
                     b.T_cl_marker;
  c.judge(fast, 1s + 2 * kFrame);
  EXPECT_FALSE(fast.ok);
}

TEST(PoseConfirmation, OnlyARecentSoundPoseConfirms) {
  ConfirmationParams p;
  p.gap_ms = 100.0;
  PoseConfirmation c{p};
  PoseEstimate a = ok_at(kAt, 0.0);
  c.judge(a, 1s);
  PoseEstimate late = ok_at(kAt, 0.0);
  c.judge(late, 1s + 101ms);  // three frames lost in between
  EXPECT_FALSE(late.ok);
  // A pose over its bound is not a reference (its loose bound would confirm anything), and stays
  // as the estimator judged it.
  PoseEstimate loose = ok_at(kAt, 0.0);
  loose.ok = false;
  loose.not_ok_reason = NotOkReason::bound_over_limit;
  loose.error_bound_m = 0.03;
  c.judge(loose, 1s + 101ms + kFrame);
  EXPECT_EQ(loose.not_ok_reason, NotOkReason::bound_over_limit);
  PoseEstimate after = ok_at(kAt, 0.0);
  c.judge(after, 1s + 101ms + 2 * kFrame);
  EXPECT_FALSE(after.ok);
  EXPECT_EQ(after.not_ok_reason, NotOkReason::unconfirmed);
}

TEST(PoseConfirmation, ARateOfZeroTurnsItOff) {
  ConfirmationParams p;
  p.rate_dps = 0.0;
  PoseConfirmation c{p};
  PoseEstimate first = ok_at(kAt, 0.0);
  c.judge(first, 1s);
  EXPECT_TRUE(first.ok);
  PoseEstimate jump = ok_at(kAt, 30.0);
  c.judge(jump, 1s + kFrame);
  EXPECT_TRUE(jump.ok);
}

}  // namespace
