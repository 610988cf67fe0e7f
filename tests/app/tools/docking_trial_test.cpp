// The trial runner flies the real application against the mock HAL: it docks on a fixed seed,
// levels from the IMU, and run-time faults put the vehicle in the safe state.
#include "app/tools/docking_trial.hpp"
#include "app/tools/validation_set.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/runtime/app_config.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/sim_report.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

struct Fixture {
  AppConfig config = load_app_config(default_config_path());
  hal::StereoRig rig = load_rig(config);
};

TEST(DockingTrial, CameraLossMakesTheVehicleSafe) {
  Fixture f;
  f.config.sim.faults.camera_lost_at_s = 2.0;
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  const TrialResult r = run_docking_trial(f.config, f.rig, generator.make(0, 1), TrialOptions{});
  EXPECT_FALSE(r.docked);
  EXPECT_EQ(r.failsafe, "camera lost");
  EXPECT_LT(r.sim_time_s, 4.0) << "the loop ends soon after the safe state";
  bool logged = false;
  for (const auto& e : r.events) logged = logged || e.find("FAILSAFE") != std::string::npos;
  EXPECT_TRUE(logged);
}

TEST(DockingTrial, BusTimeoutMakesTheVehicleSafe) {
  Fixture f;
  f.config.sim.faults.bus_timeout_at_s = 2.0;
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  const TrialResult r = run_docking_trial(f.config, f.rig, generator.make(0, 1), TrialOptions{});
  EXPECT_FALSE(r.docked);
  EXPECT_EQ(r.failsafe, "thruster bus fault");
}

// The case: the contact switch is relied on and never reads (sensors lost from the
// start). The simulator may capture the probe, but the mission never reaches DOCKED, and the
// report must not count the trial docked.
TEST(DockingTrial, ATrialIsNotDockedUnlessTheMissionReachedDocked) {
  Fixture f;
  f.config.mission.contact_switch = true;
  f.config.mission.contact_from_vision = false;
  f.config.sim.faults.sensor_lost_at_s = 0.0;
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  TrialOptions options;
  options.max_time_s = 60.0;
  const TrialResult r = run_docking_trial(f.config, f.rig, generator.make(2, 1), options);
  EXPECT_FALSE(r.mission_docked) << "final state " << r.final_state;
  EXPECT_NE(r.final_state, "docked");
  EXPECT_FALSE(trial_docked(r));
  const SimSummary s = summarise({r});
  EXPECT_EQ(s.docked, 0);
  EXPECT_EQ(s.captured, r.docked ? 1 : 0);
  EXPECT_NE(summary_text(s, {r}).find("docked 0 of 1"), std::string::npos);
  // Even a result whose cached flag says otherwise is judged by the mission's own state.
  TrialResult forged = r;
  forged.success = true;
  EXPECT_EQ(summarise({forged}).docked, 0);
}

// The closed loop on a fixed seed: the real estimator on rendered images, the real controller,
// the simulated vehicle in a current. It must dock within the tolerances.
TEST(DockingTrial, DocksOnAFixedSeed) {
  Fixture f;
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  TrialOptions options;
  options.keep_records = true;
  const TrialResult r = run_docking_trial(f.config, f.rig, generator.make(2, 1), options);
  ASSERT_TRUE(r.docked) << "final state " << r.final_state << " after " << r.sim_time_s << " s";
  EXPECT_TRUE(r.mission_docked);
  EXPECT_LE(r.lateral_error_mm, kSuccessLateralMm);
  EXPECT_LE(std::abs(r.yaw_error_deg), kSuccessYawDeg);
  EXPECT_EQ(r.overruns, 0u);
  EXPECT_FALSE(r.records.empty());
  EXPECT_LT(r.estimate_error_mm_median, 10.0);
  // Every ok estimate within the bench's "right" of the truth of its own image.
  EXPECT_GT(r.ok_ticks, r.records.size() / 2);
  EXPECT_EQ(r.ok_wrong_ticks, 0u) << "worst ok " << r.ok_error_mm_max << " mm";
  EXPECT_LT(r.ok_error_mm_max, kRightTranslationMm);
  EXPECT_LT(r.ok_error_deg_max, kRightRotationDeg);
  // The bound is a 99 % quantile: at most about 1 % of ok ticks outside it.
  EXPECT_LE(100 * r.ok_over_bound_ticks, r.ok_ticks) << r.ok_over_bound_ticks << " over";
}

// Turbid water, seed 1, trial 0, with estimator.rim_bound measured: the marker is found 1.35 m
// out, and on its first frames the third look's (denoised) rims fitted 10 deg off. Three sigma of
// their count said 2 deg and two ticks were ok and wrong; their measured misfit says 5-10 deg.
TEST(DockingTrial, AMeasuredBoundVouchesForNoDenoisedRimFitOffInTurbidWater) {
  Fixture f;
  f.config.estimator.rim_bound = "measured";
  f.config.sim.scenario = "turbid";
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  TrialOptions options;
  options.max_time_s = 2.0;
  const TrialResult r = run_docking_trial(f.config, f.rig, generator.make(0, 1), options);
  EXPECT_GT(r.ok_ticks, 20u);
  EXPECT_EQ(r.ok_wrong_ticks, 0u) << "worst ok " << r.ok_error_mm_max << " mm, "
                                  << r.ok_error_deg_max << " deg";
}

// Largest tilt of the camera off level over a trial: the angle between world down (the
// marker's y axis) and the camera's y axis, from the true T_cl_marker.
double max_tilt_deg(const TrialResult& r) {
  double worst = 0.0;
  for (const TelemetryRecord& rec : r.records) {
    if ((rec.flags & telemetry_flag::truth_valid) == 0) continue;
    const Eigen::Quaterniond q(rec.truth_q_wxyz[0], rec.truth_q_wxyz[1], rec.truth_q_wxyz[2],
                               rec.truth_q_wxyz[3]);
    const double c = std::clamp(q.normalized().toRotationMatrix()(1, 1), -1.0, 1.0);
    worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
  }
  return worst;
}

// Seed 7, trial 2: with roll and pitch left to passive stability the vehicle rolled 18 deg on
// the way in and lost the marker; the IMU levelling holds it within a few degrees.
TEST(DockingTrial, LevelsRollAndPitchFromTheImu) {
  Fixture f;
  const hal::mock::TrialGenerator generator(f.config.sim, f.config.vehicle, f.rig, f.config.marker);
  TrialOptions options;
  options.keep_records = true;
  options.max_time_s = 8.0;
  const TrialResult levelled = run_docking_trial(f.config, f.rig, generator.make(2, 7), options);
  f.config.control.attitude.enabled = false;
  const TrialResult passive = run_docking_trial(f.config, f.rig, generator.make(2, 7), options);
  const double levelled_deg = max_tilt_deg(levelled);
  const double passive_deg = max_tilt_deg(passive);
  std::printf("max tilt: levelled %.1f deg, passive %.1f deg\n", levelled_deg, passive_deg);
  EXPECT_LT(levelled_deg, 6.0);
  EXPECT_GT(passive_deg, 10.0) << "the trial no longer tips without levelling: pick another";
  EXPECT_EQ(levelled.aborts, 0);
}

}  // namespace
}  // namespace rovctl::app
