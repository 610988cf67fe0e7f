// The mock thruster bus: open, arming, neutral when disarmed, delivery, injected faults (a slow
// peer in virtual time, an ignored disarm).
#include "hal/mock/mock_thruster_bus.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

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

// A failure scheduled in sim.faults for thruster `index` at 0.1 s, the bus armed at +0.7.
struct FailingThruster : BusFixture {
  std::size_t channel(std::size_t index) const {
    return static_cast<std::size_t>(world.thrusters().channel(index));
  }
  ThrusterTelemetry fly(MockThrusterBus& bus, double fraction, int until_ms) {
    std::string error;
    if (!bus.is_open()) {
      EXPECT_TRUE(bus.open(error));
      EXPECT_EQ(bus.arm(true), BusStatus::ok);
    }
    EXPECT_EQ(bus.write(all(fraction)), BusStatus::ok);
    world.step_to(milliseconds(until_ms));
    ThrusterTelemetry tel;
    EXPECT_EQ(bus.read(tel), BusStatus::ok);
    return tel;
  }
};

TEST_F(FailingThruster, DeadThrusterGivesNoThrustZeroRpmAndAFaultFlag) {
  FaultInjection f;
  f.thruster_dead_index = 3;
  f.thruster_dead_at_s = 0.1;
  world.set_thruster_faults(f);
  MockThrusterBus bus(world, f);
  ThrusterTelemetry tel = fly(bus, 0.7, 50);
  EXPECT_GT(world.thrusters().thrust_n(3), 10.0);
  EXPECT_EQ(tel.fault_flags[channel(3)], 0);
  tel = fly(bus, 0.7, 150);
  EXPECT_EQ(world.thrusters().thrust_n(3), 0.0);
  EXPECT_EQ(tel.speed_rpm[channel(3)], 0.0);
  EXPECT_NE(tel.fault_flags[channel(3)], 0);
  EXPECT_GT(world.thrusters().thrust_n(2), 10.0);  // the others fly on
  EXPECT_EQ(tel.fault_flags[channel(2)], 0);
}

TEST_F(FailingThruster, WeakThrusterGivesAFractionOfItsThrustAndLowRpmWithoutAFlag) {
  FaultInjection f;
  f.thruster_weak_index = 5;
  f.thruster_weak_at_s = 0.1;
  f.thruster_weak_fraction = 0.3;
  world.set_thruster_faults(f);
  MockThrusterBus bus(world, f);
  const ThrusterTelemetry tel = fly(bus, 0.7, 150);
  EXPECT_NEAR(world.thrusters().thrust_n(5), 0.3 * world.thrusters().thrust_n(4), 1e-9);
  EXPECT_NEAR(tel.speed_rpm[channel(5)], std::sqrt(0.3) * tel.speed_rpm[channel(4)], 1e-6);
  EXPECT_EQ(tel.fault_flags[channel(5)], 0);
}

TEST_F(FailingThruster, StuckThrusterHoldsItsThrustWhateverIsCommanded) {
  FaultInjection f;
  f.thruster_stuck_index = 1;
  f.thruster_stuck_at_s = 0.1;
  world.set_thruster_faults(f);
  MockThrusterBus bus(world, f);
  fly(bus, 0.7, 100);
  const double held_n = world.thrusters().thrust_n(1);
  ASSERT_GT(held_n, 10.0);
  const ThrusterTelemetry tel = fly(bus, -0.5, 300);
  EXPECT_EQ(world.thrusters().thrust_n(1), held_n);
  EXPECT_GT(tel.speed_rpm[channel(1)], 1000.0);  // still forward
  EXPECT_LT(tel.speed_rpm[channel(0)], -1000.0);
}

TEST_F(FailingThruster, AFailureOnAThrusterTheLayoutLacksIsRejected) {
  FaultInjection f;
  f.thruster_dead_index = 8;
  f.thruster_dead_at_s = 1.0;
  EXPECT_THROW(world.set_thruster_faults(f), std::invalid_argument);
  f.thruster_dead_at_s = -1.0;  // never: the index does not matter
  EXPECT_NO_THROW(world.set_thruster_faults(f));
}

TEST_F(BusFixture, SlowPeerLandsOneRequestAtATimeAndNeverSendsASupersededCommand) {
  FaultInjection f;
  f.bus_slow_at_s = 0.0;
  f.bus_slow_for_s = 0.2;
  f.bus_latency_ms = 100.0;
  MockThrusterBus bus(world, f);
  std::string error;
  ASSERT_TRUE(bus.open(error));
  ASSERT_EQ(bus.arm(true), BusStatus::ok);
  ThrusterTelemetry tel;
  // 0 ms: sent, answered at 100 ms. The same tick it is not late yet.
  EXPECT_EQ(bus.write(all(0.5)), BusStatus::ok);
  world.step_to(milliseconds(33));
  EXPECT_EQ(world.thrusters().thrust_n(0), 0.0) << "not delivered before the peer answers";
  EXPECT_EQ(bus.read(tel), BusStatus::degraded) << "a request of an earlier tick unanswered";
  EXPECT_EQ(bus.write(all(0.6)), BusStatus::degraded);  // waits in the slot
  world.step_to(milliseconds(66));
  EXPECT_EQ(bus.write(all(0.0)), BusStatus::degraded);  // neutral replaces 0.6: never sent
  world.step_to(milliseconds(100));
  EXPECT_EQ(bus.read(tel), BusStatus::ok);  // 0.5 answered, the neutral sent just now
  world.step_to(milliseconds(133));
  EXPECT_GT(world.thrusters().thrust_n(0), 0.0);
  EXPECT_EQ(bus.landed_after_neutral(), 1u) << "0.5 was in flight when neutral was written";
  EXPECT_EQ(bus.read(tel), BusStatus::degraded);  // the neutral, sent at 100 ms, unanswered
  world.step_to(milliseconds(200));
  EXPECT_EQ(bus.read(tel), BusStatus::ok);  // the neutral answered at 200 ms
  world.step_to(milliseconds(233));
  EXPECT_EQ(world.thrusters().thrust_n(0), 0.0);
  EXPECT_EQ(bus.stale_sent(), 0u);
  // The peer is fast again: delivered at once.
  EXPECT_EQ(bus.write(all(0.5)), BusStatus::ok);
  world.step_to(milliseconds(266));
  EXPECT_GT(world.thrusters().thrust_n(0), 0.0);
}

TEST_F(BusFixture, IgnoredDisarmIsNotAcknowledgedAndTheEscsStayArmed) {
  FaultInjection f;
  f.disarm_ignored_at_s = 0.05;
  MockThrusterBus bus(world, f);
  std::string error;
  ASSERT_TRUE(bus.open(error));
  ASSERT_EQ(bus.arm(true), BusStatus::ok);
  world.step_to(milliseconds(60));
  EXPECT_EQ(bus.arm(false), BusStatus::fault);
  EXPECT_TRUE(bus.armed());
  EXPECT_EQ(bus.write(all(0.5)), BusStatus::ok);
  world.step_to(milliseconds(70));
  EXPECT_GT(world.thrusters().thrust_n(0), 0.0) << "still armed: commands still obeyed";
}

}  // namespace
}  // namespace rovctl::hal::mock
