// The recharging mission flown end to end on the mock HAL (a short charge: the battery starts at
// 70 %): dock, hold seated, charge, undock clear with the marker in view; and each charging fault
// `rovctl sim --charge-fault` injects, mid-charge in the closed loop, ends in its stated state
// with its cause logged.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/charge_fault.hpp"
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

  TrialResult run(int index, const char* fault = "none") const {
    AppConfig c = config;
    TrialOptions options;
    options.max_time_s = 120.0;
    const ChargeFault* f = find_charge_fault(fault);
    if (f == nullptr) throw std::invalid_argument(fault);
    apply_charge_fault(*f, c, options);
    const hal::mock::TrialGenerator generator(c.sim, c.vehicle, rig, c.marker);
    return run_docking_trial(c, rig, generator.make(index, 1), options);
  }
};

std::string events_text(const TrialResult& r) {
  std::string text;
  for (const auto& e : r.events) text += e + "\n";
  return text;
}

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
  const RechargeFixture f;
  const TrialResult r = f.run(0, "charger");
  EXPECT_TRUE(r.charge.charging_reached);
  EXPECT_FALSE(r.charge.charged);
  EXPECT_EQ(r.charge.end_reason, "charger reports no current");
  EXPECT_TRUE(has_event(r, "charging -> undock (charger reports no current"));
  EXPECT_EQ(r.final_state, "departed");
  EXPECT_DOUBLE_EQ(r.charge.charged_wh, 0.0);
  EXPECT_STREQ(find_charge_fault("charger")->cause, "charger reports no current");
}

TEST(RechargeTrial, FaultTableNamesEveryFaultOnce) {
  EXPECT_EQ(charge_fault_names_text(), "none, knock, knocks, surge, charger, operator, camera");
  EXPECT_EQ(find_charge_fault("nonsense"), nullptr);
  ASSERT_NE(find_charge_fault("charger"), nullptr);
  EXPECT_STREQ(find_charge_fault("charger")->cause, "charger reports no current");
}

TEST(RechargeTrial, AKnockOutOfTheSocketIsReseatedAndTheChargeGoesOn) {
  const RechargeFixture f;
  const TrialResult r = f.run(0, "knock");
  EXPECT_TRUE(has_event(r, "charging -> dock (probe unseated: re-seat")) << events_text(r);
  EXPECT_TRUE(has_event(r, "docked -> charging (re-seated")) << events_text(r);
  EXPECT_EQ(r.charge.reseats, 1);
  EXPECT_TRUE(r.charge.charged) << r.charge.end_reason;
  EXPECT_EQ(r.final_state, "departed");
  // Noticed: the probe was never out for long while the mission thought it seated.
  EXPECT_LE(r.charge.unseated_unnoticed_max_s, 0.5);
}

TEST(RechargeTrial, AKnockAtEverySeatUndocksAndAbortsWhenTheReseatsRunOut) {
  const RechargeFixture f;
  const TrialResult r = f.run(0, "knocks");
  EXPECT_EQ(r.charge.reseats, f.config.mission.recharge.max_reseats) << events_text(r);
  EXPECT_TRUE(has_event(r, "charging -> undock (probe unseated: re-seats exhausted"))
      << events_text(r);
  EXPECT_TRUE(has_event(r, "undock -> abort (undocked after the re-seats ran out"));
  EXPECT_EQ(r.final_state, "abort");
  EXPECT_FALSE(r.charge.charged);
  EXPECT_TRUE(r.failsafe.empty()) << r.failsafe;
}

TEST(RechargeTrial, ACrossCurrentBeyondTheHoldUndocksBeforeItDragsTheProbeOut) {
  const RechargeFixture f;
  const TrialResult r = f.run(0, "surge");
  EXPECT_EQ(r.charge.end_reason, "current beyond what the hold resists") << events_text(r);
  EXPECT_TRUE(has_event(r, "charging -> undock (current beyond what the hold resists"));
  EXPECT_EQ(r.charge.reseats, 0) << events_text(r);  // undocked, not dragged off the seat
  EXPECT_FALSE(r.charge.charged);
  EXPECT_EQ(r.final_state, "departed");
  EXPECT_GT(r.charge.end_clearance_m, 0.3);
}

TEST(RechargeTrial, TheOperatorEndsTheChargeAndTheVehicleDeparts) {
  const RechargeFixture f;
  const TrialResult r = f.run(0, "operator");
  EXPECT_EQ(r.charge.end_reason, "operator command") << events_text(r);
  EXPECT_TRUE(has_event(r, "charging -> undock (operator command"));
  EXPECT_FALSE(r.charge.charged);
  EXPECT_TRUE(r.charge.departed);
  EXPECT_TRUE(r.charge.undock_marker_in_view);
  EXPECT_EQ(r.final_state, "departed");
}

TEST(RechargeTrial, AFailsafeWhileChargingBacksOutOfTheSocketBeforeGoingSafe) {
  const RechargeFixture f;
  const TrialResult r = f.run(0, "camera");
  EXPECT_EQ(r.failsafe, "camera lost");
  EXPECT_TRUE(has_event(r, "FAILSAFE camera lost -> back out")) << events_text(r);
  EXPECT_TRUE(has_event(r, "charging -> undock (failsafe: backing out of the socket"));
  EXPECT_TRUE(has_event(r, "FAILSAFE camera lost -> disarm"));
  EXPECT_EQ(r.final_state, "undock");
  // Out of the socket, not hanging on the probe: clear by more than the probe's seat.
  EXPECT_GT(r.charge.end_clearance_m, 0.2);
}

}  // namespace
}  // namespace rovctl::app
