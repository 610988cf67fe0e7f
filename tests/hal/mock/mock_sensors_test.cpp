// Mock depth and attitude: noisy truth, NaN and loss by fault injection.
#include "hal/mock/mock_sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rovctl::hal::mock {
namespace {

TEST(MockSensors, ReportsNoisyTruth) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  SensorSimParams p;
  MockSensors sensors(world, p, FaultInjection{}, 3);
  double sum = 0.0;
  double max_dev = 0.0;
  SensorReadings r;
  for (int i = 0; i < 200; ++i) {
    ASSERT_TRUE(sensors.read(r));
    ASSERT_TRUE(r.depth_valid);
    sum += r.depth_m;
    max_dev = std::max(max_dev, std::abs(r.depth_m - world.state().position_world_m.z()));
    EXPECT_LT(r.q_world_body.angularDistance(world.state().q_world_body),
              5.0 * 0.5 * M_PI / 180 * 1.8);
  }
  EXPECT_NEAR(sum / 200, world.state().position_world_m.z(), 0.002);
  EXPECT_GT(max_dev, 0.0);  // there is noise
  EXPECT_LT(max_dev, 6.0 * p.depth_noise_m);
}

TEST(MockSensors, InjectedNanAndLoss) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  FaultInjection f;
  f.sensor_nan_at_s = 0.1;
  f.sensor_lost_at_s = 0.2;
  MockSensors sensors(world, SensorSimParams{}, f, 3);
  SensorReadings r;
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(std::isfinite(r.depth_m));
  world.step_to(std::chrono::milliseconds(150));
  ASSERT_TRUE(sensors.read(r));
  EXPECT_TRUE(r.depth_valid);
  EXPECT_TRUE(std::isnan(r.depth_m));
  EXPECT_TRUE(std::isnan(r.q_world_body.w()));
  world.step_to(std::chrono::milliseconds(250));
  EXPECT_FALSE(sensors.read(r));
  EXPECT_FALSE(r.depth_valid);
  EXPECT_FALSE(r.attitude_valid);
}

}  // namespace
}  // namespace rovctl::hal::mock
