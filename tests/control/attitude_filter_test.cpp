// AttitudeFilter: the body rates carry the attitude between reads, the sensor pulls it back
// slowly, so the sensor's read-to-read noise shrinks and a turn is followed without lag.
#include "control/attitude_filter.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

constexpr double kDeg = M_PI / 180.0;

double angle_deg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.inverse() * b).angle() / kDeg;
}

Eigen::Quaterniond yawed(double yaw_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()));
}

// Half a degree of white noise per axis on each read, the vehicle turning at 10 deg/s about z:
// from one frame to the next the filtered attitude moves by the turn, within a tenth of the noise.
TEST(AttitudeFilter, TheRatesCarryTheTurnAndTheSensorsNoiseShrinks) {
  AttitudeFilter filter(2.0, 250ms);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.5 * kDeg);
  const double rate_radps = 10.0 * kDeg;
  const std::chrono::nanoseconds tick = 33ms;
  double raw_step_max_deg = 0.0, filtered_step_max_deg = 0.0;
  Eigen::Quaterniond last_raw, last_filtered;
  for (int i = 0; i < 300; ++i) {
    const std::chrono::nanoseconds now = i * tick;
    const Eigen::Quaterniond truth = yawed(rate_radps * std::chrono::duration<double>(now).count());
    const Eigen::Vector3d tilt(noise(rng), noise(rng), noise(rng));
    const Eigen::Quaterniond raw =
        truth * Eigen::Quaterniond(Eigen::AngleAxisd(tilt.norm(), tilt.normalized()));
    ASSERT_TRUE(filter.update(now, true, raw, Eigen::Vector3d(0.0, 0.0, rate_radps)));
    const Eigen::Quaterniond filtered = filter.q_world_body_at(now);
    if (i > 150) {  // settled: 2.5 time constants
      const Eigen::Quaterniond step_truth = yawed(rate_radps * 0.033);
      raw_step_max_deg = std::max(raw_step_max_deg, angle_deg(last_raw * step_truth, raw));
      filtered_step_max_deg =
          std::max(filtered_step_max_deg, angle_deg(last_filtered * step_truth, filtered));
      EXPECT_LT(angle_deg(truth, filtered), 0.3) << "tick " << i;
    }
    last_raw = raw;
    last_filtered = filtered;
  }
  EXPECT_GT(raw_step_max_deg, 1.0);
  EXPECT_LT(filtered_step_max_deg, 0.1 * raw_step_max_deg);
}

// A frame captured 50 ms before the read: the attitude carried back by the rates is the one at
// the capture.
TEST(AttitudeFilter, CarriesTheAttitudeBackToTheCapture) {
  AttitudeFilter filter(2.0, 250ms);
  const double rate_radps = 20.0 * kDeg;
  ASSERT_TRUE(filter.update(1s, true, yawed(0.5), Eigen::Vector3d(0.0, 0.0, rate_radps)));
  EXPECT_LT(angle_deg(filter.q_world_body_at(950ms), yawed(0.5 - 0.05 * rate_radps)), 1e-9);
}

// No attitude: the filter forgets, and the next valid read starts from the sensor; so does a
// read after a gap longer than the rates may carry.
TEST(AttitudeFilter, ForgetsWithoutAnAttitudeAndAfterAGap) {
  AttitudeFilter filter(2.0, 250ms);
  ASSERT_TRUE(filter.update(0ms, true, yawed(0.0), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(filter.update(33ms, false, yawed(0.0), Eigen::Vector3d::Zero()));
  EXPECT_FALSE(filter.valid());
  const double nan = std::nan("");
  EXPECT_FALSE(
      filter.update(66ms, true, Eigen::Quaterniond(nan, nan, nan, nan), Eigen::Vector3d::Zero()));
  ASSERT_TRUE(filter.update(99ms, true, yawed(0.3), Eigen::Vector3d::Zero()));
  EXPECT_LT(angle_deg(filter.q_world_body_at(99ms), yawed(0.3)), 1e-9);
  ASSERT_TRUE(filter.update(1s, true, yawed(-0.4), Eigen::Vector3d::Zero()));
  EXPECT_LT(angle_deg(filter.q_world_body_at(1s), yawed(-0.4)), 1e-9);
}

}  // namespace
}  // namespace rovctl::control
