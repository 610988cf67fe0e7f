// The recharging mission flown end to end on the mock HAL (a short charge: the battery starts at
// 70 %): dock, hold seated, charge, undock clear with the marker in view; and the injected
// charger fault ends in UNDOCK -> DEPARTED with its cause logged.
#include <gtest/gtest.h>

#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/docking_trial.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

struct RechargeFixture {
  AppConfig config = [] {
    AppConfig c = load_app_config(default_config_path());
    c.mission.kind = "recharge";
    hal::mock::apply_recharge_sea(c.sim);
    c.sim.recharge.initial_soc_min = c.sim.recharge.initial_soc_max = 0.7;
    return c;
  }();
  hal::StereoRig rig = load_rig(config);

  TrialResult run(int index) const {
    const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);
    TrialOptions options;
    options.max_time_s = 120.0;
    return run_docking_trial(config, rig, generator.make(index, 1), options);
  }
};

bool has_event(const TrialResult& r, const std::string& text) {
  for (const auto& e : r.events)
    if (e.find(text) != std::string::npos) return true;
  return false;
}

TEST(RechargeTrial, DocksChargesHoldsSeatedAndDepartsClear) {
  const RechargeFixture f;
  const TrialResult r = f.run(0);
  ASSERT_TRUE(r.recharge);
  EXPECT_TRUE(trial_docked(r)) << r.final_state;
  EXPECT_TRUE(r.charge.charged) << r.charge.end_reason;
  EXPECT_TRUE(r.charge.departed);
  EXPECT_TRUE(trial_recharged(r));
  EXPECT_EQ(r.final_state, "departed");
  EXPECT_GE(r.charge.contact_fraction, 0.99);
  EXPECT_GT(r.charge.charged_wh, 0.0);
  EXPECT_GT(r.charge.hold_wh, 0.0);
  EXPECT_LT(r.charge.hold_fraction, 0.10);
  EXPECT_GT(r.charge.soc_end, r.charge.soc_start);
  EXPECT_TRUE(r.charge.undock_marker_in_view);
  EXPECT_GT(r.charge.undock_clearance_m, 0.3);
  EXPECT_TRUE(has_event(r, "charging -> undock (charge complete"));
}

TEST(RechargeTrial, ChargerWithNoCurrentUndocksAndDepartsWithTheCauseLogged) {
  RechargeFixture f;
  f.config.sim.faults.charger_fails_at_s = 0.0;
  const TrialResult r = f.run(0);
  EXPECT_TRUE(r.charge.charging_reached);
  EXPECT_FALSE(r.charge.charged);
  EXPECT_EQ(r.charge.end_reason, "charger reports no current");
  EXPECT_TRUE(has_event(r, "charging -> undock (charger reports no current"));
  EXPECT_EQ(r.final_state, "departed");
  EXPECT_DOUBLE_EQ(r.charge.charged_wh, 0.0);
}

}  // namespace
}  // namespace rovctl::app
