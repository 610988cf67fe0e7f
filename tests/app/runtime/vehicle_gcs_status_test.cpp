// The vehicle on ArduSub's bus (the fake ArduSub on loopback UDP) tells the ground station what
// it does: rovctl's HEARTBEAT, the mission's NAMED_VALUE_FLOATs and a STATUSTEXT per mission
// transition, all from the bus's I/O thread, while the tick still allocates nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "app/runtime/allocation_counter.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle.hpp"
#include "drivers/mavlink/ardusub_thruster_bus.hpp"
#include "drivers/mavlink/fake_ardusub.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

using namespace std::chrono_literals;
using drivers::testing::FakeArduSub;
using drivers::testing::Received;

std::size_t count(const std::vector<Received>& r, std::uint32_t id, int component) {
  std::size_t n = 0;
  for (const Received& m : r) n += m.header.message_id == id && m.header.component_id == component;
  return n;
}

TEST(VehicleGcsStatus, StatusReachesTheLinkFromTheIoThreadAndTheTickAllocatesNothing) {
  FakeArduSub peer;
  AppConfig config = load_app_config(default_config_path());
  config.telemetry.enabled = false;
  config.thruster_bus.ardusub.link = "udpout:127.0.0.1:" + std::to_string(peer.port());
  config.thruster_bus.ardusub.ack_timeout_ms = 1000;  // generous under load
  config.thruster_bus.timing.close_timeout_ms = 3000;
  const hal::StereoRig rig = load_rig(config);
  const hal::mock::TrialConditions trial =
      hal::mock::TrialGenerator(config.sim, config.vehicle, rig, config.marker).make(0, 1);
  VehicleBackends backends = make_trial_backends(config, rig, trial, true);
  auto bus = std::make_unique<drivers::ArdusubThrusterBus>(config.thruster_bus.ardusub,
                                                           config.vehicle.thrusters);
  backends.bus = bus.get();
  backends.real_bus = std::move(bus);
  VehicleOptions options;
  options.helper_threads = true;  // the event logger posts the texts
  options.log_prefix = "vehicle_gcs_status_test: ";
  Vehicle vehicle(config, rig, std::move(backends), options);
  ASSERT_NE(vehicle.gcs_status(), nullptr);
  ASSERT_NE(vehicle.bus_io(), nullptr);
  std::string error;
  ASSERT_TRUE(vehicle.open(error)) << error;
  ASSERT_TRUE(vehicle.arm(error)) << error;
  vehicle.scheduler().run([&](const TickInfo& info) { return vehicle.loop().tick(info); }, 20);
  std::uint64_t allocations = 0;
  vehicle.scheduler().run(
      [&](const TickInfo& info) {
        AllocationProbe probe;
        const bool more = vehicle.loop().tick(info);
        allocations += probe.allocations();
        return more;
      },
      40);
  EXPECT_EQ(allocations, 0U) << "the tick posts the status values without allocating";
  // 60 ticks: at least one transition (trial 0 starts with the marker in view) and its text.
  ASSERT_TRUE(peer.wait_for([](const auto& r) {
    return count(r, 253, 191) >= 1 && count(r, 251, 191) >= 4 && count(r, 0, 191) >= 1;
  })) << "STATUSTEXT "
      << count(peer.received(), 253, 191) << ", NAMED_VALUE_FLOAT "
      << count(peer.received(), 251, 191) << ", HEARTBEAT " << count(peer.received(), 0, 191);
  for (const Received& m : peer.received()) {
    if (m.header.component_id == 191) {
      EXPECT_EQ(m.header.system_id, 1);
    }
  }
  EXPECT_TRUE(vehicle.shutdown(error)) << error;
}

}  // namespace
}  // namespace rovctl::app
