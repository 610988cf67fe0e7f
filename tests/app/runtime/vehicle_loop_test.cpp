// VehicleLoop against the mock HAL with failing thrusters: a dead one is found from the bus's
// telemetry, removed from the allocation (logged, no allocation on the tick) and the mission goes
// on; losing x, y, z or yaw trips the failsafe as a thruster fault. And the faults of time and
// bus: a CPU stall, a slow bus and an unacknowledged disarm, each safe within 2 ticks.
#include "app/runtime/vehicle_loop.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/runtime/allocation_counter.hpp"
#include "app/runtime/vehicle.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

struct FailingThrusters : ::testing::Test {
  AppConfig config = load_app_config(default_config_path());
  hal::StereoRig rig = load_rig(config);

  std::unique_ptr<Vehicle> open_vehicle() {
    const hal::mock::TrialConditions trial =
        hal::mock::TrialGenerator(config.sim, config.vehicle, rig, config.marker).make(0, 1);
    VehicleOptions o;
    o.helper_threads = false;
    auto v =
        std::make_unique<Vehicle>(config, rig, make_trial_backends(config, rig, trial, false), o);
    std::string error;
    EXPECT_TRUE(v->open(error)) << error;
    EXPECT_TRUE(v->arm(error)) << error;
    return v;
  }
  // Runs `ticks` ticks; returns the heap allocations made by those after the first `warm_up`.
  std::uint64_t run(Vehicle& v, int ticks, int warm_up, std::vector<LoopEvent>& events) {
    std::uint64_t allocations = 0;
    int k = 0;
    v.scheduler().run(
        [&](const TickInfo& info) {
          AllocationProbe probe;
          const bool more = v.loop().tick(info);
          if (k++ >= warm_up) allocations += probe.allocations();
          LoopEvent e;
          while (v.loop().pop_event(e)) {
            if (e.thruster >= 0 || e.failsafe) events.push_back(e);
          }
          return more;
        },
        static_cast<std::uint64_t>(ticks));
    return allocations;
  }
};

TEST_F(FailingThrusters, ADeadThrusterIsRemovedWithinTwoTicksAndTheMissionGoesOn) {
  config.sim.faults.thruster_dead_index = 2;
  config.sim.faults.thruster_dead_at_s = 0.5;  // tick 16 on the 33 ms grid
  auto v = open_vehicle();
  std::vector<LoopEvent> events;
  const std::uint64_t allocations = run(*v, 90, 10, events);
  EXPECT_EQ(allocations, 0u) << "the failure and the re-allocation are on the tick";
  ASSERT_EQ(events.size(), 1u);
  const LoopEvent& e = events.front();
  EXPECT_EQ(e.thruster, 2);
  EXPECT_EQ(e.thruster_failure, control::ThrusterFailure::fault_flag);
  EXPECT_GE(e.tick, 16u);
  EXPECT_LE(e.tick, 18u);
  EXPECT_EQ(e.thrusters_left, 7u);
  EXPECT_TRUE(e.servo_axes_controllable);
  const std::string line = format_event(e);
  EXPECT_NE(line.find("THRUSTER 2"), std::string::npos) << line;
  EXPECT_NE(line.find("ESC fault flag"), std::string::npos) << line;
  EXPECT_FALSE(v->loop().failsafe().tripped());
  EXPECT_FALSE(v->loop().allocator().active(2));
  EXPECT_EQ(v->loop().last_command().thrust_fraction[2], 0.0);
  EXPECT_GT(v->loop().recognised_ticks(), 60u);
}

TEST_F(FailingThrusters, LosingTwoVectoredThrustersTripsAThrusterFault) {
  // One dead with its flag, one giving nothing without a flag (found by its rpm): the two front
  // horizontal thrusters, after which x, y and yaw cannot all be produced.
  config.sim.faults.thruster_dead_index = 0;
  config.sim.faults.thruster_dead_at_s = 0.4;
  config.sim.faults.thruster_weak_index = 1;
  config.sim.faults.thruster_weak_at_s = 0.4;
  config.sim.faults.thruster_weak_fraction = 0.0;
  auto v = open_vehicle();
  std::vector<LoopEvent> events;
  run(*v, 90, 0, events);
  ASSERT_TRUE(v->loop().failsafe().tripped());
  EXPECT_EQ(v->loop().failsafe().cause(), control::FailsafeCause::thruster_fault);
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events[0].thruster, 0);
  EXPECT_TRUE(events[0].servo_axes_controllable);
  EXPECT_EQ(events[1].thruster, 1);
  EXPECT_FALSE(events[1].servo_axes_controllable);
  EXPECT_TRUE(events[2].failsafe);
  EXPECT_EQ(events[2].cause, control::FailsafeCause::thruster_fault);
}

// The loop's faults of time and bus, from the tick they strike: `strike_s` is the injection.
struct LoopFailsafes : FailingThrusters {
  static constexpr double strike_s = 0.5;
  std::uint64_t first_struck_tick = 0;  // the loop's tick count at the first tick from strike_s
  std::vector<LoopEvent> failsafe_events;

  std::uint64_t run_ticks(Vehicle& v, int ticks) {
    std::uint64_t allocations = 0;
    int k = 0;
    v.scheduler().run(
        [&](const TickInfo& info) {
          AllocationProbe probe;
          const bool more = v.loop().tick(info);
          if (k++ >= 10) allocations += probe.allocations();
          if (first_struck_tick == 0 && info.time_s() >= strike_s) {
            first_struck_tick = v.loop().ticks();
          }
          LoopEvent e;
          while (v.loop().pop_event(e)) {
            if (e.failsafe) failsafe_events.push_back(e);
          }
          return more;
        },
        static_cast<std::uint64_t>(ticks));
    return allocations;
  }
};

TEST_F(LoopFailsafes, AStalledTickCountsItsOwnOverrunAndTheStreakTripsOnTheSecond) {
  config.sim.faults.cpu_stall_at_s = strike_s;
  config.sim.faults.cpu_stall_for_s = 1.0;
  config.sim.faults.cpu_stall_ms = 50.0;  // every tick from strike_s ends past the next release
  auto v = open_vehicle();
  run_ticks(*v, 40);
  ASSERT_FALSE(failsafe_events.empty());
  const LoopEvent& trip = failsafe_events.front();
  EXPECT_EQ(trip.cause, control::FailsafeCause::cpu_overrun);
  EXPECT_EQ(trip.failsafe_kind, control::FailsafeEventKind::trip);
  // overrun_ticks = 2: the first stalled tick and the next; not a third from skipped releases.
  EXPECT_EQ(trip.tick, first_struck_tick + 1);
}

TEST_F(LoopFailsafes, OneOverrunIsCountedOnceNotAgainByTheTickAfter) {
  config.sim.faults.cpu_stall_at_s = strike_s;
  config.sim.faults.cpu_stall_for_s = 0.033;  // one stalled grab: the tick at 0.528 s
  auto v = open_vehicle();
  run_ticks(*v, 40);
  EXPECT_TRUE(failsafe_events.empty()) << format_event(failsafe_events.front());
  EXPECT_GT(v->scheduler().stats().overrun_ticks, 0u);
}

TEST_F(LoopFailsafes, ASlowBusTripsAtTheFirstLateAnswerSendsNothingStaleAndRecovers) {
  config.sim.faults.bus_slow_at_s = strike_s;
  config.sim.faults.bus_slow_for_s = 0.5;
  config.sim.faults.bus_latency_ms = 100.0;
  config.control.failsafe.recover_ticks = 5;
  auto v = open_vehicle();
  const std::uint64_t allocations = run_ticks(*v, 60);
  EXPECT_EQ(allocations, 0u);
  ASSERT_GE(failsafe_events.size(), 2u);
  EXPECT_EQ(failsafe_events[0].cause, control::FailsafeCause::bus_slow);
  EXPECT_EQ(failsafe_events[0].failsafe_kind, control::FailsafeEventKind::trip);
  // Sent at the first struck tick, unanswered at the next: that tick reads it and goes neutral.
  EXPECT_EQ(failsafe_events[0].tick, first_struck_tick + 1);
  EXPECT_EQ(failsafe_events[1].failsafe_kind, control::FailsafeEventKind::recovered);
  EXPECT_EQ(v->backends().sim->bus().stale_sent(), 0u);
  EXPECT_FALSE(v->loop().failsafe().tripped());
}

TEST_F(LoopFailsafes, AnUnacknowledgedDisarmTripsHoldsNeutralAndIsRetriedUntilTaken) {
  config.sim.faults.sensor_lost_at_s = strike_s;  // a cause whose action is disarm
  config.sim.faults.disarm_ignored_at_s = strike_s;
  auto v = open_vehicle();
  run_ticks(*v, 30);
  ASSERT_GE(failsafe_events.size(), 2u);
  EXPECT_EQ(failsafe_events[0].cause, control::FailsafeCause::sensor_lost);
  EXPECT_EQ(failsafe_events[0].action, control::SafeAction::disarm);
  EXPECT_EQ(failsafe_events[1].cause, control::FailsafeCause::disarm_unacked);
  EXPECT_EQ(failsafe_events[1].tick, failsafe_events[0].tick + 1);
  EXPECT_EQ(v->loop().failsafe().cause(), control::FailsafeCause::disarm_unacked);
  hal::mock::MockThrusterBus& bus = v->backends().sim->bus();
  EXPECT_TRUE(bus.armed());
  for (std::size_t i = 0; i < bus.last_command().count; ++i) {
    EXPECT_EQ(bus.last_command().thrust_fraction[i], 0.0) << "thruster " << i;
  }
  bus.faults().disarm_ignored_at_s = -1.0;  // the bus takes the next retry
  run_ticks(*v, 2);
  EXPECT_FALSE(bus.armed());
}

// With the tracker on, the camera gives no frame for 50 ms while the marker is tracked: the
// tracker carries the pose through the gap with a bound that grows every tick, the truth of the
// moment within it, and nothing on the tick allocates.
TEST_F(FailingThrusters, TheTrackerCarriesThePoseThroughDroppedFramesWithAGrowingBound) {
  config.control.tracker.enabled = true;
  config.sim.faults.camera_drop_at_s = 2.0;
  config.sim.faults.camera_drop_for_s = 0.05;
  auto v = open_vehicle();
  int carried = 0;
  double last_bound_m = 0.0;
  std::uint64_t allocations = 0;
  int k = 0;
  v->scheduler().run(
      [&](const TickInfo& info) {
        AllocationProbe probe;
        const bool more = v->loop().tick(info);
        if (k++ >= 10) allocations += probe.allocations();
        const control::TrackedPose& p = v->loop().tracked_pose();
        if (p.source == control::TrackSource::coasting && p.ok) {
          ++carried;
          EXPECT_GT(p.bound_m, last_bound_m) << "tick " << v->loop().ticks();
          const Eigen::Isometry3d truth = v->backends().sim->world().truth().T_cl_marker;
          EXPECT_LE((p.T_cl_marker.translation() - truth.translation()).norm(), p.bound_m)
              << "tick " << v->loop().ticks();
        }
        last_bound_m = p.bound_m;
        LoopEvent e;
        while (v->loop().pop_event(e)) {
        }
        return more;
      },
      90);
  EXPECT_GE(carried, 1);
  EXPECT_EQ(allocations, 0u) << "the tracker and the attitude filter are on the tick";
  EXPECT_EQ(v->loop().tracked_pose().source, control::TrackSource::fused);
}

}  // namespace
}  // namespace rovctl::app
