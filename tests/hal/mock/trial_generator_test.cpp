// Randomised trial starts: ranges, visibility classes, reproducibility, and the assembled HAL.
#include "hal/mock/trial_generator.hpp"

#include <gtest/gtest.h>

#include "hal/mock/simulated_hal.hpp"

namespace rovctl::hal::mock {
namespace {

struct TrialFixture : ::testing::Test {
  SimParams params;
  VehicleGeometry vehicle;
  StereoRig rig = make_parallel_rig(CameraModel{}, 0.178);
  MarkerModel marker = MarkerModel::standard();
};

TEST_F(TrialFixture, DrawsWithinTheRangesAndWithTheMarkerInView) {
  const TrialGenerator gen(params, vehicle, rig, marker);
  const Eigen::Isometry3d T_world_marker = station_T_world_marker(params.station);
  for (int i = 0; i < 200; ++i) {
    const TrialConditions t = gen.make(i, 1234);
    const Eigen::Isometry3d T_world_cl = t.initial.T_world_body() * vehicle.T_body_cl();
    const double d = (T_world_cl.translation() - T_world_marker.translation()).norm();
    EXPECT_NEAR(d, t.distance_m, 1e-9);
    EXPECT_GE(d, 0.6);
    EXPECT_LE(d, 1.5);
    EXPECT_TRUE(t.as_requested);
    EXPECT_TRUE(t.marker_in_left_view || t.marker_in_right_view) << "trial " << i;
    EXPECT_LE(t.current_mean_world_mps.norm(), 0.1 + 1e-12);
    EXPECT_EQ(t.current_mean_world_mps.z(), 0.0);
    EXPECT_GE(t.image_noise_sigma, params.trials.noise_sigma_min);
    EXPECT_LE(t.image_noise_sigma, params.trials.noise_sigma_max);
    EXPECT_EQ(t.initial.nu_body, Vector6d::Zero());
    // In front of the station (negative marker z).
    EXPECT_LT((T_world_marker.inverse() * T_world_cl.translation()).z(), 0.0);
  }
}

TEST_F(TrialFixture, OutOfViewTrialsHaveTheMarkerInNeitherImage) {
  params.trials.out_of_view_fraction = 1.0;
  const TrialGenerator gen(params, vehicle, rig, marker);
  for (int i = 0; i < 50; ++i) {
    const TrialConditions t = gen.make(i, 99);
    ASSERT_TRUE(t.as_requested);
    int left = -1, right = -1;
    gen.spheres_in_view(t.initial.T_world_body(), left, right);
    EXPECT_EQ(left, 0);
    EXPECT_EQ(right, 0);
  }
}

TEST_F(TrialFixture, SameIndexAndSeedSameTrial) {
  const TrialGenerator gen(params, vehicle, rig, marker);
  const TrialConditions a = gen.make(5, 77), b = gen.make(5, 77), c = gen.make(6, 77),
                        d = gen.make(5, 78);
  EXPECT_EQ(a.initial.position_world_m, b.initial.position_world_m);
  EXPECT_EQ(a.world_seed, b.world_seed);
  EXPECT_NE(a.initial.position_world_m, c.initial.position_world_m);
  EXPECT_NE(a.initial.position_world_m, d.initial.position_world_m);
}

TEST_F(TrialFixture, InvertedRangeIsRejectedByName) {
  params.trials.distance_min_m = 2.0;
  params.trials.distance_max_m = 1.0;
  try {
    TrialGenerator gen(params, vehicle, rig, marker);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sim.trials.distance_min_m"), std::string::npos);
  }
}

TEST_F(TrialFixture, SimulatedHalStartsWhereTheTrialSays) {
  const TrialGenerator gen(params, vehicle, rig, marker);
  const TrialConditions t = gen.make(3, 5);
  SimulatedHal hal(params, vehicle, DockingStation{}, rig, marker, t);
  EXPECT_EQ(hal.world().state().position_world_m, t.initial.position_world_m);
  EXPECT_EQ(hal.world().current().mean_world_mps(), t.current_mean_world_mps);
  EXPECT_EQ(hal.clock().now().count(), 0);
  std::string error;
  ASSERT_TRUE(hal.camera().open(error));
  ASSERT_TRUE(hal.bus().open(error));
  StereoFrame frame;
  hal.clock().sleep_until(std::chrono::milliseconds(66));
  EXPECT_EQ(hal.camera().grab(frame), GrabStatus::ok);
  SensorReadings r;
  EXPECT_TRUE(hal.sensors().read(r));
  EXPECT_EQ(r.stamp, std::chrono::milliseconds(66));
}

}  // namespace
}  // namespace rovctl::hal::mock
