// The mock thruster bus: open, arming, neutral when disarmed, delivery, injected faults.
#include "hal/mock/mock_thruster_bus.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rovctl::hal::mock {
namespace {

using std::chrono::milliseconds;

ThrusterCommand all(double f) {
  ThrusterCommand c;
  c.count = 8;
  c.thrust_fraction.fill(f);
  return c;
}

struct BusFixture : ::testing::Test {
  SimParams params = [] {
    SimParams p;
    p.thrusters.time_constant_s = 0.0;
    return p;
  }();
  SimulatedWorld world{params, VehicleGeometry{}, DockingStation{}};
};

TEST_F(BusFixture, DisarmedBusDeliversNeutral) {
  MockThrusterBus bus(world, FaultInjection{});
  std::string error;
  ASSERT_TRUE(bus.open(error));
  EXPECT_EQ(bus.write(all(0.7)), BusStatus::ok);
  world.step_to(milliseconds(10));
  EXPECT_EQ(world.thrusters().thrust_n(0), 0.0);
  EXPECT_DOUBLE_EQ(bus.last_command().thrust_fraction[0], 0.7);  // recorded as asked
  EXPECT_EQ(bus.write_count(), 1u);
}

TEST_F(BusFixture, ArmedBusDrivesTheThrustersAndDisarmStopsThem) {
  MockThrusterBus bus(world, FaultInjection{});
  std::string error;
  ASSERT_TRUE(bus.open(error));
  ASSERT_EQ(bus.arm(true), BusStatus::ok);
  EXPECT_EQ(bus.write(all(0.7)), BusStatus::ok);
  world.step_to(milliseconds(10));
  EXPECT_GT(world.thrusters().thrust_n(0), 10.0);
  ThrusterTelemetry tel;
  EXPECT_EQ(bus.read(tel), BusStatus::ok);
  EXPECT_TRUE(tel.valid);
  EXPECT_GT(tel.speed_rpm[0], 1000.0);
  ASSERT_EQ(bus.arm(false), BusStatus::ok);
  world.step_to(milliseconds(20));
  EXPECT_EQ(world.thrusters().thrust_n(0), 0.0);
}

TEST_F(BusFixture, NonFiniteCommandIsDeliveredAsNeutralAndReported) {
  MockThrusterBus bus(world, FaultInjection{});
  std::string error;
  ASSERT_TRUE(bus.open(error));
  bus.arm(true);
  ThrusterCommand c = all(0.5);
  c.thrust_fraction[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(bus.write(c), BusStatus::degraded);
  world.step_to(milliseconds(10));
  EXPECT_EQ(world.thrusters().thrust_n(4), 0.0);
  EXPECT_GT(world.thrusters().thrust_n(0), 0.0);
  EXPECT_EQ(bus.non_finite_count(), 1u);
}

TEST_F(BusFixture, InjectedBusTimeoutFaultsAndTheEscsGoNeutral) {
  FaultInjection faults;
  faults.bus_timeout_at_s = 0.1;
  MockThrusterBus bus(world, faults);
  std::string error;
  ASSERT_TRUE(bus.open(error));
  bus.arm(true);
  EXPECT_EQ(bus.write(all(0.6)), BusStatus::ok);
  world.step_to(milliseconds(100));
  EXPECT_GT(world.thrusters().thrust_n(1), 0.0);
  EXPECT_EQ(bus.write(all(0.6)), BusStatus::fault);
  ThrusterTelemetry tel;
  EXPECT_EQ(bus.read(tel), BusStatus::fault);
  EXPECT_FALSE(tel.valid);
  // Without fresh commands the ESCs stop after their timeout.
  world.step_to(milliseconds(100 + 300));
  EXPECT_EQ(world.thrusters().thrust_n(1), 0.0);
}

TEST_F(BusFixture, InjectedOpenFailureNamesTheFault) {
  FaultInjection faults;
  faults.bus_open_fails = true;
  MockThrusterBus bus(world, faults);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("bus_open_fails"), std::string::npos);
  EXPECT_EQ(bus.write(all(0.2)), BusStatus::fault);
}

}  // namespace
}  // namespace rovctl::hal::mock
