// Hardware in the loop without a vehicle: a docking trial of deploy/config/sim-ardusub.yaml (wrench
// mode) and sim-ardusub-thrusters.yaml (thrusters mode) flies rovctl's ArduSub driver and sensors
// against the mock ArduSub over loopback UDP, and docks.
#include <gtest/gtest.h>

#include <cmath>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/docking_trial.hpp"
#include "hal/mock/mock_ardusub.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

AppConfig ardusub_config() {
  return load_app_config(std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/sim-ardusub.yaml");
}

// The driver's map from newtons to axes must be the mock ArduSub's mixer read backwards, or the
// servo's gains would be off by their ratio.
TEST(DockingTrialArdusub, TheConfiguredScaleIsTheMockMixersFullStick) {
  const AppConfig config = ardusub_config();
  hal::mock::SimulatedWorld world(config.sim, config.vehicle, config.station);
  const hal::mock::MockArdusub ardusub(world, config.sim.ardusub);
  const drivers::ArdusubAxisScale& s = config.thruster_bus.ardusub.scale;
  const Eigen::Vector4d& full = ardusub.full_stick();
  EXPECT_NEAR(s.surge_full_n, full(0), 0.01 * full(0));
  EXPECT_NEAR(s.sway_full_n, full(1), 0.01 * full(1));
  EXPECT_NEAR(s.heave_full_n, full(2), 0.01 * full(2));
  EXPECT_NEAR(s.yaw_full_nm, full(3), 0.01 * full(3));
  EXPECT_DOUBLE_EQ(config.sim.ardusub.pilot_gain, config.thruster_bus.ardusub.pilot_gain);
}

TEST(DockingTrialArdusub, ATrialOverMavlinkDocks) {
  const AppConfig config = ardusub_config();
  const hal::StereoRig rig = load_rig(config);
  // The backends are the driver and the mock ArduSub, not the mock bus and sensors.
  const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);
  {
    VehicleBackends b = make_trial_backends(config, rig, generator.make(0, 1), false);
    ASSERT_NE(b.ardusub_peer, nullptr);
    EXPECT_EQ(b.bus, b.sim_bus.get());
    EXPECT_EQ(b.sensors, b.real_sensors.get());
  }
  const TrialResult r = run_docking_trial(config, rig, generator.make(0, 1), TrialOptions{});
  EXPECT_TRUE(trial_docked(r)) << r.final_state << " " << r.failsafe;
  EXPECT_TRUE(r.failsafe.empty()) << r.failsafe;
  EXPECT_LE(r.lateral_error_mm, kSuccessLateralMm);
}

// Thrusters mode: rovctl's allocation reaches the mock's ESCs as RC_CHANNELS_OVERRIDE passthrough,
// with no MANUAL_CONTROL at all, and the levelling is rovctl's own on the streamed attitude.
TEST(DockingTrialArdusub, ATrialInThrustersModeDocksOnRcOverrides) {
  const AppConfig config =
      load_app_config(std::string(ROVCTL_SOURCE_DIR) + "/deploy/config/sim-ardusub-thrusters.yaml");
  ASSERT_EQ(config.thruster_bus.ardusub.mode, "thrusters");
  const hal::StereoRig rig = load_rig(config);
  const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);
  {
    VehicleBackends b = make_trial_backends(config, rig, generator.make(1, 1), false);
    ASSERT_NE(b.ardusub_peer, nullptr);
    std::string error;
    ASSERT_TRUE(b.bus->open(error)) << error;
    ASSERT_EQ(b.bus->arm(true), hal::BusStatus::ok);
    hal::ThrusterCommand c;
    c.count = config.vehicle.thrusters.thrusters.size();
    c.thrust_fraction[0] = 0.5;
    EXPECT_EQ(b.bus->write(c), hal::BusStatus::ok);
    EXPECT_GE(b.ardusub_peer->counters().rc_override, 1U);
    EXPECT_EQ(b.ardusub_peer->counters().manual_control, 0U);
    b.bus->close();
  }
  const TrialResult r = run_docking_trial(config, rig, generator.make(1, 1), TrialOptions{});
  EXPECT_TRUE(trial_docked(r)) << r.final_state << " " << r.failsafe;
  EXPECT_TRUE(r.failsafe.empty()) << r.failsafe;
  EXPECT_LE(r.lateral_error_mm, kSuccessLateralMm);
}

}  // namespace
}  // namespace rovctl::app
