// The vehicle root against the mock HAL: the tick allocates nothing after start-up, an exception
// inside the loop still leaves the thrusters neutral and disarmed, and so does leaving the scope.
#include "app/runtime/vehicle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "app/runtime/allocation_counter.hpp"
#include "app/runtime/app_config.hpp"
#include "drivers/monotonic_clock.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

struct Fixture {
  AppConfig config = load_app_config(default_config_path());
  hal::StereoRig rig = load_rig(config);
  hal::mock::TrialConditions trial() const {
    return hal::mock::TrialGenerator(config.sim, config.vehicle, rig, config.marker).make(0, 1);
  }
  VehicleOptions sim_options() const {
    VehicleOptions o;
    o.helper_threads = false;
    return o;
  }
};

// A camera whose driver throws after a few good frames: the worst a backend can do to the tick.
class ThrowingCamera final : public hal::StereoCamera {
 public:
  ThrowingCamera(hal::StereoCamera& inner, int good_frames) : inner_(inner), left_(good_frames) {}
  bool open(std::string& error) override { return inner_.open(error); }
  hal::GrabStatus grab(hal::StereoFrame& frame) override {
    if (left_-- <= 0) throw std::runtime_error("camera driver threw");
    return inner_.grab(frame);
  }
  void close() override { inner_.close(); }
  std::string name() const override { return "throwing camera"; }

 private:
  hal::StereoCamera& inner_;
  int left_;
};

// What reached the bus, kept outside the vehicle so that it can be read after the vehicle is gone.
struct BusLog {
  bool armed = false;
  bool closed = false;
  hal::ThrusterCommand last{};
  std::uint64_t writes = 0;
};

class RecordingBus final : public hal::ThrusterBus {
 public:
  RecordingBus(hal::ThrusterBus& inner, BusLog& log) : inner_(inner), log_(log) {}
  bool open(std::string& error) override { return inner_.open(error); }
  hal::BusStatus arm(bool armed) override {
    log_.armed = armed;
    return inner_.arm(armed);
  }
  hal::BusStatus write(const hal::ThrusterCommand& command) override {
    log_.last = command;
    ++log_.writes;
    return inner_.write(command);
  }
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override { return inner_.read(telemetry); }
  void close() override {
    log_.closed = true;
    inner_.close();
  }
  std::string name() const override { return "recording bus"; }

 private:
  hal::ThrusterBus& inner_;
  BusLog& log_;
};

bool all_neutral(const hal::ThrusterCommand& c) {
  for (std::size_t i = 0; i < c.count; ++i) {
    if (c.thrust_fraction[i] != 0.0) return false;
  }
  return true;
}

TEST(Vehicle, TickAllocatesNothingAfterStartUp) {
  Fixture f;
  Vehicle vehicle(f.config, f.rig, make_trial_backends(f.config, f.rig, f.trial(), false),
                  f.sim_options());
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  VehicleLoop& loop = vehicle.loop();
  // Start-up: the first ticks size the images and warm every path.
  vehicle.scheduler().run([&](const TickInfo& info) { return loop.tick(info); }, 30);
  ASSERT_GT(loop.recognised_ticks(), 0u) << "the marker should be seen at the start of trial 0";
  std::uint64_t allocations = 0;
  vehicle.scheduler().run(
      [&](const TickInfo& info) {
        AllocationProbe probe;
        const bool more = loop.tick(info);
        allocations += probe.allocations();
        return more;
      },
      300);
  EXPECT_EQ(allocations, 0u) << "allocations in 300 ticks of the application loop";
  TelemetryRing& ring = vehicle.telemetry();
  EXPECT_EQ(ring.size(), std::min<std::size_t>(ring.capacity(), 330));
}

// On a real clock every stage of the tick shows its time, segmentation apart from estimation.
TEST(Vehicle, TimesEveryStageOnARealClock) {
  Fixture f;
  VehicleBackends backends = make_trial_backends(f.config, f.rig, f.trial(), false);
  backends.real_clock = std::make_unique<drivers::MonotonicClock>();
  backends.clock = backends.real_clock.get();
  Vehicle vehicle(f.config, f.rig, std::move(backends), f.sim_options());
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  vehicle.run(5);
  TelemetryRecord r;
  std::array<std::int64_t, kStageCount> most{};
  while (vehicle.telemetry().try_pop(r)) {
    for (std::size_t i = 0; i < kStageCount; ++i) most[i] = std::max(most[i], r.stage_ns[i]);
  }
  // The telemetry stage writes the record while it runs, so only the stages before it show.
  for (std::size_t i = 0; i < static_cast<std::size_t>(Stage::telemetry); ++i) {
    EXPECT_GT(most[i], 0) << stage_name(static_cast<Stage>(i)) << " was never timed";
  }
}

TEST(Vehicle, AnExceptionInTheLoopLeavesTheThrustersNeutralAndDisarmed) {
  Fixture f;
  VehicleBackends backends = make_trial_backends(f.config, f.rig, f.trial(), false);
  hal::mock::SimulatedHal& sim = *backends.sim;
  backends.real_camera = std::make_unique<ThrowingCamera>(sim.camera(), 60);
  backends.camera = backends.real_camera.get();
  Vehicle vehicle(f.config, f.rig, std::move(backends), f.sim_options());
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  ASSERT_TRUE(sim.bus().armed());
  std::uint64_t ticks = 0;
  bool thrust_before = false;
  EXPECT_THROW(vehicle.run(1000,
                           [&](const TickInfo&) {
                             ++ticks;
                             thrust_before =
                                 thrust_before || !all_neutral(sim.bus().last_command());
                           }),
               std::runtime_error);
  EXPECT_EQ(ticks, 60u);
  EXPECT_TRUE(thrust_before) << "the vehicle was under thrust when the camera threw";
  EXPECT_FALSE(sim.bus().armed());
  EXPECT_TRUE(all_neutral(sim.bus().last_command()));
}

TEST(Vehicle, LeavingScopeLeavesTheThrustersNeutralAndDisarmed) {
  Fixture f;
  BusLog log;
  {
    VehicleBackends backends = make_trial_backends(f.config, f.rig, f.trial(), false);
    auto bus = std::make_unique<RecordingBus>(backends.sim->bus(), log);
    backends.bus = bus.get();
    backends.real_bus = std::move(bus);
    Vehicle vehicle(f.config, f.rig, std::move(backends), f.sim_options());
    std::string error;
    ASSERT_TRUE(vehicle.open(error)) << error;
    ASSERT_TRUE(vehicle.arm(error)) << error;
    vehicle.run(40);
    ASSERT_TRUE(log.armed);
    ASSERT_FALSE(all_neutral(log.last)) << "the vehicle is under thrust when the scope ends";
  }
  EXPECT_FALSE(log.armed);
  EXPECT_TRUE(all_neutral(log.last));
  EXPECT_TRUE(log.closed);
}

TEST(Vehicle, ListsItsThreads) {
  Fixture f;
  VehicleOptions flight;
  Vehicle vehicle(f.config, f.rig, make_trial_backends(f.config, f.rig, f.trial(), false), flight);
  const std::vector<ThreadSpec> threads = vehicle.threads();
  ASSERT_GE(threads.size(), 2u);
  EXPECT_EQ(threads[0].name, "tick");
  EXPECT_EQ(threads[0].period, std::chrono::microseconds(33000));
}

}  // namespace
}  // namespace rovctl::app
