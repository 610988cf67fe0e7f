// The vehicle root against the mock HAL: the tick allocates nothing after start-up, an exception
// inside the loop still leaves the thrusters neutral and disarmed, and so does leaving the scope.
#include "app/runtime/vehicle.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <stdexcept>
#include <thread>

#include "app/runtime/allocation_counter.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/operator_link.hpp"
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

// A real bus as the vehicle sees one (not the mock's): each request takes `latency`; hung, it
// answers nothing (fault) after its response timeout.
class RemoteBus final : public hal::ThrusterBus {
 public:
  bool open(std::string&) override { return true; }
  hal::BusStatus arm(bool armed) override {
    if (!answer()) return hal::BusStatus::fault;
    armed_ = armed;
    return hal::BusStatus::ok;
  }
  hal::BusStatus write(const hal::ThrusterCommand&) override {
    writes.fetch_add(1);
    return answer() ? hal::BusStatus::ok : hal::BusStatus::degraded;
  }
  hal::BusStatus read(hal::ThrusterTelemetry& t) override {
    t.valid = answer();
    return t.valid ? hal::BusStatus::ok : hal::BusStatus::degraded;
  }
  void close() override {}
  std::string name() const override { return "remote bus"; }

  std::atomic<bool> hung{false};
  std::atomic<std::uint64_t> writes{0};

 private:
  bool answer() {
    std::this_thread::sleep_for(hung.load() ? std::chrono::milliseconds(150)
                                            : std::chrono::milliseconds(10));
    return !hung.load();
  }
  bool armed_ = false;
};

// The mock world in real time with `bus` as the vehicle's real bus (so it gets the I/O thread).
VehicleBackends remote_bus_backends(const Fixture& f, std::unique_ptr<RemoteBus> bus) {
  VehicleBackends backends = make_trial_backends(f.config, f.rig, f.trial(), true);
  backends.bus = bus.get();
  backends.real_bus = std::move(bus);
  return backends;
}

// Heap allocations made by `ticks` ticks of the vehicle's loop (the tick's own thread only).
std::uint64_t count_tick_allocations(Vehicle& vehicle, std::uint64_t ticks) {
  std::uint64_t allocations = 0;
  vehicle.scheduler().run(
      [&](const TickInfo& info) {
        AllocationProbe probe;
        const bool more = vehicle.loop().tick(info);
        allocations += probe.allocations();
        return more;
      },
      ticks);
  return allocations;
}

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
  const std::uint64_t allocations = count_tick_allocations(vehicle, 300);
  EXPECT_EQ(allocations, 0u) << "allocations in 300 ticks of the application loop";
  TelemetryRing& ring = vehicle.telemetry();
  EXPECT_EQ(ring.size(), std::min<std::size_t>(ring.capacity(), 330));
}

// The operator view's link takes the record every tick and the images every few: still nothing
// allocated on the tick, and the view's side gets both.
TEST(Vehicle, TickWithTheOperatorLinkAllocatesNothing) {
  Fixture f;
  OperatorLink link(f.rig, std::chrono::milliseconds(100));
  VehicleOptions options = f.sim_options();
  options.operator_link = &link;
  Vehicle vehicle(f.config, f.rig, make_trial_backends(f.config, f.rig, f.trial(), false), options);
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  VehicleLoop& loop = vehicle.loop();
  vehicle.scheduler().run([&](const TickInfo& info) { return loop.tick(info); }, 30);
  const std::uint64_t allocations = count_tick_allocations(vehicle, 300);
  EXPECT_EQ(allocations, 0u) << "allocations in 300 ticks with the operator link attached";
  EXPECT_EQ(link.records().published(), 330u);
  // Every third or fourth tick at 33 ms and a 100 ms image period.
  EXPECT_GE(link.frames().published(), 330u / 4);
  EXPECT_LE(link.frames().published(), 330u / 3 + 1);
  const OperatorFrame* frame = link.frames().take();
  ASSERT_NE(frame, nullptr);
  EXPECT_EQ(frame->left_bgr.cols, f.rig.left.width_px);
  EXPECT_GT(cv::norm(frame->left_bgr, cv::NORM_L1), 0.0) << "the copied image is not blank";
  EXPECT_NE(frame->record.flags & telemetry_flag::estimate_valid, 0u);
}

// ABORT from the operator: neutral from the next tick, held (not ended) until START, which
// begins a new mission from SEARCH under thrust again.
TEST(Vehicle, OperatorAbortHoldsNeutralUntilStart) {
  Fixture f;
  OperatorLink link(f.rig, std::chrono::milliseconds(100));
  VehicleBackends backends = make_trial_backends(f.config, f.rig, f.trial(), false);
  hal::mock::SimulatedHal& sim = *backends.sim;
  VehicleOptions options = f.sim_options();
  options.operator_link = &link;
  Vehicle vehicle(f.config, f.rig, std::move(backends), options);
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  vehicle.run(60);
  ASSERT_FALSE(all_neutral(sim.bus().last_command())) << "under thrust before the abort";
  link.request_abort();
  int neutral_ticks = 0;
  bool held_every_tick = true;
  vehicle.run(90, [&](const TickInfo&) {
    neutral_ticks += all_neutral(sim.bus().last_command()) ? 1 : 0;
    held_every_tick = held_every_tick && vehicle.loop().operator_hold();
  });
  EXPECT_EQ(neutral_ticks, 90) << "every tick after the abort is neutral, the first included";
  EXPECT_TRUE(held_every_tick);
  EXPECT_TRUE(sim.bus().armed()) << "a hold is not a disarm: START resumes without re-arming";
  LoopEvent e;
  bool logged = false;
  while (vehicle.loop().pop_event(e)) {
    logged = logged || std::string(e.reason).find("operator ABORT") != std::string::npos;
  }
  EXPECT_TRUE(logged) << "the abort is logged";

  link.request_start();
  bool thrust_again = false;
  vehicle.run(60, [&](const TickInfo&) {
    thrust_again = thrust_again || !all_neutral(sim.bus().last_command());
  });
  EXPECT_FALSE(vehicle.loop().operator_hold());
  EXPECT_TRUE(thrust_again) << "START flies again";
  bool restarted = false;
  while (vehicle.loop().pop_event(e)) {
    restarted = restarted || (!e.failsafe && e.to == control::MissionState::search &&
                              std::string(e.reason) == "restart");
  }
  EXPECT_TRUE(restarted) << "START begins a new mission from SEARCH";
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

TEST(Vehicle, ARealBusRunsOnItsIoThreadAndTheTickStillAllocatesNothing) {
  Fixture f;
  auto owned = std::make_unique<RemoteBus>();
  RemoteBus& bus = *owned;
  Vehicle vehicle(f.config, f.rig, remote_bus_backends(f, std::move(owned)), f.sim_options());
  ASSERT_NE(vehicle.bus_io(), nullptr);
  EXPECT_EQ(vehicle.threads().back().name, "bus I/O");
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  vehicle.scheduler().run([&](const TickInfo& info) { return vehicle.loop().tick(info); }, 10);
  EXPECT_EQ(count_tick_allocations(vehicle, 30), 0u);
  EXPECT_GT(bus.writes.load(), 10u);  // the commands went out, from the I/O thread
  EXPECT_TRUE(vehicle.shutdown(error)) << error;
}

TEST(Vehicle, ShutdownSaysWhenTheFinalDisarmWasNotAcknowledged) {
  Fixture f;
  auto owned = std::make_unique<RemoteBus>();
  RemoteBus& bus = *owned;
  Vehicle vehicle(f.config, f.rig, remote_bus_backends(f, std::move(owned)), f.sim_options());
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  vehicle.run(5);
  bus.hung = true;  // the peer stops answering as the mission ends
  EXPECT_FALSE(vehicle.shutdown(error));
  EXPECT_NE(error.find("remote bus: the final neutral and disarm were not acknowledged"),
            std::string::npos)
      << error;
}

TEST(Vehicle, TheMockBusStaysOnTheTickThread) {
  Fixture f;
  Vehicle vehicle(f.config, f.rig, make_trial_backends(f.config, f.rig, f.trial(), false),
                  f.sim_options());
  EXPECT_EQ(vehicle.bus_io(), nullptr);  // stepped simulation: deterministic
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
