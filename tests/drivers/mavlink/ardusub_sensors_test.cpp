// ArduSub's telemetry as hal::SensorReadings: attitude and rates, depth from the external
// pressure sensor, battery, leak, and each part invalid once stale, on a hand-set clock.
#include "drivers/mavlink/ardusub_sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/mavlink/mavlink_messages.hpp"
#define ROVCTL_MALLOC_HOOKS_ELSEWHERE 1  // the hooks live in mavlink_codec_test.cpp
#include "malloc_counter.hpp"

namespace rovctl::drivers {
namespace {

using namespace std::chrono_literals;
namespace mav = mavlink;

class HandClock final : public hal::Clock {
 public:
  std::chrono::nanoseconds now() const override { return now_; }
  void sleep_until(std::chrono::nanoseconds deadline) override { now_ = deadline; }
  std::chrono::nanoseconds now_{1s};
};

template <typename M>
mav::Frame frame_of(const M& m) {
  mav::FrameWriter writer(1, 1);
  std::array<std::uint8_t, mav::kMaxFrameBytes> buf{};
  const std::size_t n = mav::write_message(writer, m, buf);
  mav::FrameParser parser;
  parser.feed(std::span<const std::uint8_t>(buf.data(), n));
  mav::Frame f;
  EXPECT_TRUE(parser.next(f));
  return f;
}

TEST(ArdusubSensors, NothingBeforeArduSubSpeaks) {
  HandClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  hal::SensorReadings r;
  EXPECT_FALSE(sensors.read(r));
  sensors.accept(frame_of(mav::Heartbeat{}));  // not a reading
  EXPECT_FALSE(sensors.read(r));
}

TEST(ArdusubSensors, AttitudeAndRatesFromAttitudeQuaternion) {
  HandClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
  mav::AttitudeQuaternion a;
  a.q_ned_body = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
                  static_cast<float>(q.z())};
  a.rollspeed_rad_s = 0.01F;
  a.pitchspeed_rad_s = -0.02F;
  a.yawspeed_rad_s = 0.03F;
  sensors.accept(frame_of(a));
  hal::SensorReadings r;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.attitude_valid);
  EXPECT_LT(r.q_world_body.angularDistance(q), 1e-6);
  EXPECT_NEAR(r.omega_body_radps.x(), 0.01, 1e-7);
  EXPECT_NEAR(r.omega_body_radps.y(), -0.02, 1e-7);
  EXPECT_NEAR(r.omega_body_radps.z(), 0.03, 1e-7);
  EXPECT_FALSE(r.depth_valid);
  EXPECT_EQ(r.stamp, 1s);
}

TEST(ArdusubSensors, DepthFromAbsolutePressure) {
  HandClock clock;
  ArdusubSensorParams p;
  ArdusubSensors sensors(p, clock);
  mav::ScaledPressure2 s;
  // 2.5 m of sea water: rho g h = 1025 * 9.80665 * 2.5 Pa.
  s.press_abs_hpa = static_cast<float>(1013.25 + 1025.0 * 9.80665 * 2.5 / 100.0);
  sensors.accept(frame_of(s));
  hal::SensorReadings r;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.depth_valid);
  EXPECT_NEAR(r.depth_m, 2.5, 1e-3);
}

TEST(ArdusubSensors, BatteryFromSysStatusUnknownIsInvalid) {
  HandClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  mav::SysStatus s;
  s.voltage_battery_mv = 15800;
  s.battery_remaining_pct = 64;
  sensors.accept(frame_of(s));
  hal::SensorReadings r;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.battery_valid);
  EXPECT_DOUBLE_EQ(r.soc_fraction, 0.64);
  EXPECT_DOUBLE_EQ(r.battery_voltage_v, 15.8);
  s.battery_remaining_pct = -1;
  sensors.accept(frame_of(s));
  ASSERT_TRUE(sensors.read(r));
  EXPECT_FALSE(r.battery_valid);
}

TEST(ArdusubSensors, LeakFromStatusTextLatches) {
  HandClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  mav::StatusText t;
  t.severity = 2;  // CRITICAL
  mav::set_text(t.text, "Lost manual control");
  sensors.accept(frame_of(t));
  hal::SensorReadings r;
  EXPECT_FALSE(sensors.read(r));  // not a reading
  mav::set_text(t.text, "Leak Detected");
  sensors.accept(frame_of(t));
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.leak_valid);
  EXPECT_TRUE(r.leak);
  sensors.accept(frame_of(mav::ScaledPressure2{}));
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.leak);
}

TEST(ArdusubSensors, EachPartGoesStaleOnItsOwn) {
  HandClock clock;
  ArdusubSensorParams p;
  p.stale_ms = 300;
  ArdusubSensors sensors(p, clock);
  sensors.accept(frame_of(mav::AttitudeQuaternion{{}, {1, 0, 0, 0}}));
  clock.now_ += 200ms;
  sensors.accept(frame_of(mav::ScaledPressure2{}));
  clock.now_ += 200ms;  // attitude 400 ms old, depth 200 ms
  hal::SensorReadings r;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_FALSE(r.attitude_valid);
  EXPECT_TRUE(r.depth_valid);
  EXPECT_EQ(r.attitude_age, 400ms);  // each reading says how old it is
  EXPECT_EQ(r.depth_age, 200ms);
  clock.now_ += 200ms;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_FALSE(r.depth_valid);
  EXPECT_EQ(r.depth_age, 400ms);
}

TEST(ArdusubSensors, AcceptAndReadAllocateNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) GTEST_SKIP() << "no malloc hooks under ASan";
  HandClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  const mav::Frame att = frame_of(mav::AttitudeQuaternion{{}, {1, 0, 0, 0}});
  const mav::Frame press = frame_of(mav::ScaledPressure2{});
  hal::SensorReadings r;
  const std::uint64_t before = rovctl::testing::t_allocations;
  for (int i = 0; i < 100; ++i) {
    sensors.accept(att);
    sensors.accept(press);
    (void)sensors.read(r);
  }
  EXPECT_EQ(rovctl::testing::t_allocations - before, 0U);
}

}  // namespace
}  // namespace rovctl::drivers
