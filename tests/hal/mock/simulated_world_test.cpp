// The simulated world: station placement, truth, fine stepping, pose history, contact and docking.
#include "hal/mock/simulated_world.hpp"

#include <gtest/gtest.h>

#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

using std::chrono::milliseconds;

VehicleState at(const Eigen::Isometry3d& T) {
  VehicleState s;
  s.position_world_m = T.translation();
  s.q_world_body = Eigen::Quaterniond(T.linear());
  return s;
}

TEST(SimulatedWorld, StationStandsWhereConfiguredFacingNorth) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  EXPECT_TRUE(world.T_world_marker().translation().isApprox(Eigen::Vector3d(5, 0, 2)));
  // Docking axis (marker +z) points north; docked, the vehicle heads north.
  EXPECT_TRUE(world.T_world_marker().linear().col(2).isApprox(Eigen::Vector3d::UnitX()));
  const Eigen::Isometry3d docked = world.docked_T_world_body();
  EXPECT_TRUE(docked.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_LT(docked.translation().x(), 5.0);
  // The default start is 1 m short of the docked pose, facing the station.
  EXPECT_NEAR(world.docking().axial_distance_m, 1.0, 1e-9);
  EXPECT_NEAR(world.docking().lateral_error_m, 0.0, 1e-9);
}

TEST(SimulatedWorld, DockingHeadingTurnsTheStation) {
  SimParams p;
  p.station.docking_heading_deg = 90.0;
  SimulatedWorld world(p, VehicleGeometry{}, DockingStation{});
  EXPECT_TRUE(world.T_world_marker().linear().col(2).isApprox(Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d x = world.docked_T_world_body().linear().col(0);
  EXPECT_TRUE(x.isApprox(Eigen::Vector3d::UnitY()));
}

TEST(SimulatedWorld, TruthAtTheDockedPoseMatchesDockedTclMarker) {
  const VehicleGeometry vehicle;
  const DockingStation station;
  SimulatedWorld world(SimParams{}, vehicle, station);
  world.reset(at(world.docked_T_world_body()), Eigen::Vector3d::Zero(), 0);
  const WorldTruth truth = world.truth();
  const Eigen::Isometry3d expected =
      docked_T_cl_marker(vehicle.T_body_cl(), vehicle.probe_tip_body_m, station);
  EXPECT_TRUE(truth.T_cl_marker.isApprox(expected, 1e-12));
  EXPECT_NEAR(truth.docking.axial_distance_m, 0.0, 1e-12);
  EXPECT_NEAR(truth.docking.yaw_error_rad, 0.0, 1e-12);
}

TEST(SimulatedWorld, StepsToTheRequestedTimeInFineSteps) {
  SimulatedWorld world(SimParams{}, VehicleGeometry{}, DockingStation{});
  world.step_to(milliseconds(33));
  EXPECT_EQ(world.time(), milliseconds(33));
  world.step_to(milliseconds(20));  // not ahead: nothing happens
  EXPECT_EQ(world.time(), milliseconds(33));
  // Buoyancy has started to lift it.
  EXPECT_LT(world.state().nu_body(2), 0.0);
}

TEST(SimulatedWorld, PoseHistoryInterpolatesThePast) {
  SimParams p = test::still_water_params();
  SimulatedWorld world(p, VehicleGeometry{}, DockingStation{});
  VehicleState s;
  s.position_world_m = {0, 0, 2};
  s.nu_body(0) = 0.4;
  s.nu_body(5) = 0.3;
  world.reset(s, Eigen::Vector3d::Zero(), 0);
  world.step_to(milliseconds(100));
  const Eigen::Isometry3d then = world.T_world_body_at(milliseconds(61));
  world.step_to(milliseconds(300));
  const Eigen::Isometry3d again = world.T_world_body_at(milliseconds(61));
  EXPECT_TRUE(then.isApprox(again, 1e-12));
  const Eigen::Isometry3d now = world.T_world_body_at(milliseconds(300));
  EXPECT_TRUE(now.isApprox(world.state().T_world_body(), 1e-12));
  EXPECT_GT((now.translation() - then.translation()).norm(), 0.05);
  // Between two samples it lies between them.
  const double x60 = world.T_world_body_at(milliseconds(60)).translation().x();
  const double x62 = world.T_world_body_at(milliseconds(62)).translation().x();
  EXPECT_GT(then.translation().x(), x60);
  EXPECT_LT(then.translation().x(), x62);
}

// Drives along the docking axis with a pure surge force, with a lateral offset of the start.
DockingTruth approach(double lateral_offset_m, double yaw_offset_rad,
                      double face_half_size_m = SimParams{}.contact.face_half_size_m) {
  SimParams p = test::still_water_params();
  p.contact.face_half_size_m = face_half_size_m;
  const VehicleGeometry vehicle;
  SimulatedWorld world(p, vehicle, DockingStation{});
  Eigen::Isometry3d start = world.docked_T_world_body();
  start.translation() += Eigen::Vector3d(-0.3, lateral_offset_m, 0.0);
  start.linear() = Eigen::AngleAxisd(yaw_offset_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                   start.linear();
  world.reset(at(start), Eigen::Vector3d::Zero(), 0);
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();
  wrench(0) = 15.0;
  const ThrusterCommand c = test::command_for_wrench(vehicle.thrusters, wrench);
  for (int k = 1; k <= 150 && !world.docking().docked; ++k) {
    world.command_thrusters(c);
    world.step_to(milliseconds(33 * k));
  }
  return world.docking();
}

TEST(SimulatedWorld, CentredAlignedApproachDocks) {
  const DockingTruth d = approach(0.0, 0.0);
  EXPECT_TRUE(d.docked);
  EXPECT_FALSE(d.collided);
  EXPECT_GT(d.docked_at.count(), 0);
  EXPECT_LT(d.lateral_error_m, 0.03);
}

TEST(SimulatedWorld, OffCentreApproachHitsTheFaceAndIsStopped) {
  // A face wide enough that the pressing probe does not slide off its edge in the 5 s push (it
  // slides 0.4 m down the frictionless face).
  const DockingTruth d = approach(0.08, 0.0, 10.0);
  EXPECT_FALSE(d.docked);
  EXPECT_TRUE(d.collided);
  EXPECT_TRUE(d.contact);  // still pressing
  EXPECT_GT(d.max_contact_force_n, 5.0);
  // The face holds it: only the small spring compression past the socket mouth.
  EXPECT_GT(d.axial_distance_m, -0.02);
}

// Beside the station face there is nothing to touch: the probe passes its plane.
TEST(SimulatedWorld, AnApproachBesideTheStationFaceTouchesNothing) {
  const double face = SimParams{}.contact.face_half_size_m;
  const DockingTruth beside = approach(face + 0.1, 0.0);
  EXPECT_FALSE(beside.contact);
  EXPECT_FALSE(beside.collided);
  EXPECT_LT(beside.axial_distance_m, -0.05) << "the probe did not pass the face's plane";
  const DockingTruth on_face = approach(face - 0.1, 0.0);
  EXPECT_TRUE(on_face.collided) << "a touch on the face, off the socket, is a collision";
}

TEST(SimulatedWorld, MisalignedApproachIsNotDocked) {
  const DockingTruth d = approach(0.0, 0.35);  // 20 degrees off
  EXPECT_FALSE(d.docked);
}

TEST(SimulatedWorld, LatchHoldsTheDockedVehicle) {
  SimParams p = test::still_water_params();
  p.dynamics.buoyancy_n = p.dynamics.weight_n + 5.0;
  SimulatedWorld world(p, VehicleGeometry{}, DockingStation{});
  Eigen::Isometry3d start = world.docked_T_world_body();
  start.translation().x() += 0.03;  // probe 3 cm deep: captured at once
  world.reset(at(start), Eigen::Vector3d::Zero(), 0);
  EXPECT_TRUE(world.docking().docked);
  world.step_to(milliseconds(2000));
  EXPECT_TRUE(world.state().position_world_m.isApprox(start.translation(), 1e-12));
}

}  // namespace
}  // namespace rovctl::hal::mock
