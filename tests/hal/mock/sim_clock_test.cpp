// The simulation clock moves the world: at once in virtual time; in real time it steps the world
// to the deadline, then sleeps until the wall clock gets there.
#include "hal/mock/sim_clock.hpp"

#include <gtest/gtest.h>

namespace rovctl::hal::mock {
namespace {

using std::chrono::milliseconds;

TEST(SimClock, VirtualSleepStepsTheWorld) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  SimClock clock(world, SimClock::Mode::virtual_time);
  EXPECT_EQ(clock.now().count(), 0);
  const Eigen::Vector3d before = world.state().position_world_m;
  clock.sleep_until(milliseconds(500));
  EXPECT_EQ(clock.now(), milliseconds(500));
  EXPECT_EQ(world.time(), milliseconds(500));
  EXPECT_NE(world.state().position_world_m, before);  // it has risen a little
  clock.advance(milliseconds(7));
  EXPECT_EQ(world.time(), milliseconds(507));
  clock.sleep_until(milliseconds(100));  // in the past: no change
  EXPECT_EQ(clock.now(), milliseconds(507));
}

TEST(SimClock, RealtimeSleepStepsThenWaits) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  SimClock clock(world, SimClock::Mode::realtime);
  const auto start = clock.now();
  clock.sleep_until(start + milliseconds(20));
  EXPECT_GE(clock.now(), start + milliseconds(20));
  EXPECT_EQ(world.time(), start + milliseconds(20));
  clock.advance(milliseconds(50));  // real time passes by itself
  EXPECT_EQ(world.time(), start + milliseconds(20));
}

}  // namespace
}  // namespace rovctl::hal::mock
