// The mock ArduSub's vehicle side: stabilise holds level on neutral input, arming gates the
// thrusters, a MANUAL_CONTROL x step is forward thrust, and lost pilot input disarms.
#include "hal/mock/mock_ardusub.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;

constexpr nanoseconds kTick = milliseconds(33);

struct ArdusubFixture : ::testing::Test {
  SimParams params = [] {
    SimParams p = test::still_water_params();
    p.thrusters.time_constant_s = 0.0;
    // No restoring moment: only the stabilise loop can bring the vehicle back to level.
    p.dynamics.centre_of_buoyancy_body_m.setZero();
    return p;
  }();
  SimulatedWorld world{params, VehicleGeometry{}, DockingStation{}};
  MockArdusub ardusub{world, params.ardusub};

  void start_rolled(double roll_rad) {
    VehicleState s;
    s.position_world_m = Eigen::Vector3d(0.0, 0.0, 2.0);
    s.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()));
    world.reset(s, Eigen::Vector3d::Zero(), 1);
  }
  // ArduSub's loop once per tick with the same pilot input, for `duration`.
  void fly(const PilotAxes& axes, nanoseconds duration) {
    const nanoseconds end = world.time() + duration;
    while (world.time() < end) {
      ardusub.pilot_input(axes, world.time());
      ardusub.update(world.time());
      world.step_to(world.time() + kTick);
    }
  }
  double roll_rad() const {
    const Eigen::Vector3d down = world.state().q_world_body.conjugate() * Eigen::Vector3d::UnitZ();
    return std::atan2(down.y(), down.z());
  }
};

TEST_F(ArdusubFixture, NeutralInputInStabilizeBringsTheVehicleLevel) {
  start_rolled(0.3);
  ardusub.set_mode(kArdusubModeStabilize);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  fly(PilotAxes{}, milliseconds(6000));
  EXPECT_LT(std::abs(roll_rad()), 0.02);
  EXPECT_LT(world.state().omega_body_radps().norm(), 0.02);
}

TEST_F(ArdusubFixture, ManualModeDoesNotLevel) {
  start_rolled(0.3);
  ardusub.set_mode(kArdusubModeManual);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  fly(PilotAxes{}, milliseconds(6000));
  EXPECT_GT(std::abs(roll_rad()), 0.25);
}

TEST_F(ArdusubFixture, DisarmedItDeliversNeutralWhateverThePilotAsks) {
  start_rolled(0.0);
  ardusub.set_mode(kArdusubModeStabilize);
  fly(PilotAxes{800, 0, 500, 0}, milliseconds(200));
  EXPECT_DOUBLE_EQ(world.truth().thrust_wrench_body.norm(), 0.0);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  fly(PilotAxes{800, 0, 500, 0}, milliseconds(200));
  EXPECT_GT(world.truth().thrust_wrench_body(0), 10.0);
  ASSERT_TRUE(ardusub.arm(false, world.time()));
  fly(PilotAxes{800, 0, 500, 0}, milliseconds(100));
  EXPECT_FALSE(ardusub.armed());
  EXPECT_DOUBLE_EQ(world.truth().thrust_wrench_body.norm(), 0.0);
}

TEST_F(ArdusubFixture, ForwardStepIsForwardThrustThroughThePilotGain) {
  start_rolled(0.0);
  ardusub.set_mode(kArdusubModeStabilize);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  fly(PilotAxes{500, 0, 500, 0}, milliseconds(100));
  const Eigen::Matrix<double, 6, 1> w = world.truth().thrust_wrench_body;
  const double expected_n = 0.5 * params.ardusub.pilot_gain * ardusub.full_stick()(0);
  EXPECT_NEAR(w(0), expected_n, 0.02 * expected_n);
  EXPECT_NEAR(w(1), 0.0, 0.5);
  EXPECT_NEAR(w(2), 0.0, 0.5);
  EXPECT_NEAR(w(5), 0.0, 0.1);
  // Full stick saturates a thruster exactly: the figure is the layout's, not a guess.
  fly(PilotAxes{1000, 0, 500, 0}, milliseconds(100));
  double largest = 0.0;
  for (std::size_t i = 0; i < ardusub.last_command().count; ++i) {
    largest = std::max(largest, std::abs(ardusub.last_command().thrust_fraction[i]));
  }
  EXPECT_NEAR(largest, params.ardusub.pilot_gain, 1e-6);
}

TEST_F(ArdusubFixture, HeaveAxisAbove500Climbs) {
  start_rolled(0.0);
  ardusub.set_mode(kArdusubModeStabilize);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  fly(PilotAxes{0, 0, 750, 0}, milliseconds(100));
  EXPECT_LT(world.truth().thrust_wrench_body(2), -5.0);  // body z is down
}

TEST_F(ArdusubFixture, LostPilotInputDisarmsAfterTheTimeout) {
  start_rolled(0.0);
  ardusub.set_mode(kArdusubModeStabilize);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  ardusub.pilot_input(PilotAxes{300, 0, 500, 0}, world.time());
  const nanoseconds timeout = std::chrono::duration_cast<nanoseconds>(
      std::chrono::duration<double, std::milli>(params.ardusub.pilot_timeout_ms));
  ardusub.update(world.time() + timeout - milliseconds(50));
  EXPECT_TRUE(ardusub.armed());
  ardusub.update(world.time() + timeout + milliseconds(50));
  EXPECT_FALSE(ardusub.armed());
  EXPECT_TRUE(ardusub.pilot_failsafe());
}

// Thrusters mode: each channel's PWM is its ESC's fraction, past the mixer, until the override is
// older than RC_OVERRIDE_TIME; then neutral.
TEST_F(ArdusubFixture, RcOverridePassesEachChannelThroughUntilItExpires) {
  start_rolled(0.0);
  ASSERT_TRUE(ardusub.arm(true, world.time()));
  std::array<std::uint16_t, 18> us{};
  us.fill(1500);
  us[0] = 1700;  // +0.5
  us[4] = 1400;  // -0.25
  us[8] = 0;     // released: neutral in the mock
  ardusub.rc_override(us, world.time());
  ardusub.update(world.time());
  EXPECT_NEAR(ardusub.last_command().thrust_fraction[0], 0.5, 1e-9);
  EXPECT_NEAR(ardusub.last_command().thrust_fraction[4], -0.25, 1e-9);
  EXPECT_NEAR(ardusub.last_command().thrust_fraction[1], 0.0, 1e-9);
  const nanoseconds hold = std::chrono::duration_cast<nanoseconds>(
      std::chrono::duration<double, std::milli>(params.ardusub.rc_override_time_ms));
  ardusub.update(world.time() + hold - milliseconds(10));
  EXPECT_NEAR(ardusub.last_command().thrust_fraction[0], 0.5, 1e-9);
  EXPECT_TRUE(ardusub.armed()) << "the override refreshes the pilot-input timer";
  ardusub.update(world.time() + hold + milliseconds(10));
  EXPECT_NEAR(ardusub.last_command().thrust_fraction[0], 0.0, 1e-9);
}

}  // namespace
}  // namespace rovctl::hal::mock
