// AttitudeStabilizer: levelling moments oppose roll and pitch and their rates, saturate, and
// give way (false, zero) to the servo's damping when the IMU reading is missing or not finite.
#include "control/attitude_stabilizer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace rovctl::control {
namespace {

hal::SensorReadings level_reading() {
  hal::SensorReadings r;
  r.attitude_valid = true;
  return r;
}

Eigen::Quaterniond rpy(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

TEST(AttitudeStabilizer, RollPitchOfZyxAngles) {
  const Eigen::Vector2d a = AttitudeStabilizer::roll_pitch(rpy(0.2, -0.1, 2.5));
  EXPECT_NEAR(a.x(), 0.2, 1e-12);
  EXPECT_NEAR(a.y(), -0.1, 1e-12);
}

TEST(AttitudeStabilizer, LevelAndStillNeedsNoMoment) {
  const AttitudeStabilizer s{AttitudeParams{}};
  hal::SensorReadings r = level_reading();
  r.q_world_body = rpy(0.0, 0.0, 1.3);  // heading does not matter
  Eigen::Vector2d m;
  ASSERT_TRUE(s.update(r, m));
  EXPECT_NEAR(m.norm(), 0.0, 1e-12);
}

TEST(AttitudeStabilizer, OpposesRollAndPitch) {
  AttitudeParams p;
  p.roll_kp_nm_per_rad = 6.0;
  p.pitch_kp_nm_per_rad = 4.0;
  const AttitudeStabilizer s{p};
  hal::SensorReadings r = level_reading();
  // Starboard down (positive roll) needs a port-down moment (negative Mx); nose up (positive
  // pitch) a nose-down one (negative My).
  r.q_world_body = rpy(0.1, 0.05, 0.0);
  Eigen::Vector2d m;
  ASSERT_TRUE(s.update(r, m));
  EXPECT_NEAR(m.x(), -0.6, 1e-9);
  EXPECT_NEAR(m.y(), -0.2, 1e-9);
}

TEST(AttitudeStabilizer, DampsTheGyroRates) {
  AttitudeParams p;
  p.roll_kd_nms_per_rad = 2.0;
  p.pitch_kd_nms_per_rad = 3.0;
  const AttitudeStabilizer s{p};
  hal::SensorReadings r = level_reading();
  r.omega_body_radps = {0.5, -0.2, 4.0};  // yaw rate is the servo's business
  Eigen::Vector2d m;
  ASSERT_TRUE(s.update(r, m));
  EXPECT_NEAR(m.x(), -1.0, 1e-9);
  EXPECT_NEAR(m.y(), 0.6, 1e-9);
}

TEST(AttitudeStabilizer, SaturatesPerAxis) {
  AttitudeParams p;
  p.max_moment_nm = 2.5;
  const AttitudeStabilizer s{p};
  hal::SensorReadings r = level_reading();
  r.q_world_body = rpy(-1.0, 1.0, 0.0);
  Eigen::Vector2d m;
  ASSERT_TRUE(s.update(r, m));
  EXPECT_DOUBLE_EQ(m.x(), 2.5);
  EXPECT_DOUBLE_EQ(m.y(), -2.5);
}

TEST(AttitudeStabilizer, GivesWayWithoutAValidAttitude) {
  const AttitudeStabilizer s{AttitudeParams{}};
  Eigen::Vector2d m = Eigen::Vector2d::Ones();
  hal::SensorReadings invalid;  // attitude_valid false
  invalid.q_world_body = rpy(0.3, 0.0, 0.0);
  EXPECT_FALSE(s.update(invalid, m));
  EXPECT_TRUE(m.isZero());

  hal::SensorReadings nan = level_reading();
  nan.omega_body_radps.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(s.update(nan, m));
  EXPECT_TRUE(m.isZero());

  AttitudeParams off;
  off.enabled = false;
  hal::SensorReadings tilted = level_reading();
  tilted.q_world_body = rpy(0.3, 0.0, 0.0);
  EXPECT_FALSE(AttitudeStabilizer{off}.update(tilted, m));
  EXPECT_TRUE(m.isZero());
}

}  // namespace
}  // namespace rovctl::control
