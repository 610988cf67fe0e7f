// The Fossen model: buoyancy, terminal speed, dissipation, symmetry and the restoring moment.
#include "hal/mock/vehicle_dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "hal/mock/simulated_world.hpp"
#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

const Eigen::Vector3d kNoCurrent = Eigen::Vector3d::Zero();

TEST(VehicleDynamics, DefaultsAreTheBlueRov2HeavyWithDissipativeDamping) {
  const VehicleDynamicsParams p;
  EXPECT_DOUBLE_EQ(p.mass_kg, 13.5);
  EXPECT_DOUBLE_EQ(p.added_mass_linear.z(), -18.68);
  EXPECT_DOUBLE_EQ(p.damping_quadratic_linear.x(), -141.0);
  EXPECT_GT(p.buoyancy_n, p.weight_n);
  // Wu's M_q = +0.8 would be negative damping; it must not be there.
  EXPECT_LE(p.damping_angular.maxCoeff(), 0.0);
  EXPECT_LE(p.damping_linear.maxCoeff(), 0.0);
}

TEST(VehicleDynamics, PositiveBuoyancyMakesItRiseSlowly) {
  const VehicleDynamics dyn{VehicleDynamicsParams{}};
  VehicleState s;
  s.position_world_m = {0, 0, 2};
  for (int i = 0; i < 15000; ++i) dyn.step(s, Vector6d::Zero(), kNoCurrent, kNoCurrent, 0.002);
  // Terminal heave speed from B - W = Z_w w + Z_w|w| w|w|: 190 w^2 + 33 w = 2.
  const double expected = (-33.0 + std::sqrt(33.0 * 33.0 + 4.0 * 190.0 * 2.0)) / (2.0 * 190.0);
  EXPECT_NEAR(s.nu_body(2), -expected, 1e-3);  // z down: rising is negative w
  EXPECT_LT(s.position_world_m.z(), 2.0 - 0.5 * 30.0 * expected);
  EXPECT_GT(s.position_world_m.z(), 2.0 - 30.0 * expected - 0.01);
  // Upright and not turning.
  EXPECT_NEAR(s.q_world_body.angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-6);
}

TEST(VehicleDynamics, LeftToItselfItFloatsAtTheSurface) {
  const VehicleDynamicsParams p;
  const VehicleDynamics dyn{p};
  VehicleState s;
  s.position_world_m = {0, 0, 1};
  for (int i = 0; i < 100000; ++i) dyn.step(s, Vector6d::Zero(), kNoCurrent, kNoCurrent, 0.002);
  // Equilibrium: submerged fraction W / B of the hull.
  const double z = (p.weight_n / p.buoyancy_n - 0.5) * p.hull_height_m;
  EXPECT_NEAR(s.position_world_m.z(), z, 1e-3);
  EXPECT_NEAR(s.nu_body(2), 0.0, 1e-4);
}

TEST(VehicleDynamics, ConstantSurgeForceReachesTheTerminalSpeedTheDampingPredicts) {
  VehicleDynamicsParams p;
  p.buoyancy_n = p.weight_n;
  const VehicleDynamics dyn{p};
  VehicleState s;
  s.position_world_m.z() = 5.0;  // well submerged
  Vector6d tau = Vector6d::Zero();
  tau(0) = 40.0;
  for (int i = 0; i < 10000; ++i) dyn.step(s, tau, kNoCurrent, kNoCurrent, 0.002);
  // 141 u^2 + 13.7 u = 40
  const double u = (-13.7 + std::sqrt(13.7 * 13.7 + 4.0 * 141.0 * 40.0)) / (2.0 * 141.0);
  EXPECT_NEAR(s.nu_body(0), u, 1e-4);
  EXPECT_NEAR(s.nu_body.tail<5>().norm(), 0.0, 1e-9);
}

TEST(VehicleDynamics, KineticEnergyDecaysWithoutThrust) {
  VehicleDynamicsParams p;
  p.buoyancy_n = p.weight_n;
  p.centre_of_buoyancy_body_m.setZero();  // no potential energy to exchange with
  const VehicleDynamics dyn{p};
  VehicleState s;
  s.position_world_m.z() = 5.0;
  s.nu_body << 0.5, -0.3, 0.2, 0.4, -0.3, 0.6;
  double energy = dyn.kinetic_energy_j(s);
  const double start = energy;
  for (int i = 0; i < 5000; ++i) {
    dyn.step(s, Vector6d::Zero(), kNoCurrent, kNoCurrent, 0.002);
    const double e = dyn.kinetic_energy_j(s);
    ASSERT_LE(e, energy * (1.0 + 1e-9)) << "step " << i;
    energy = e;
  }
  EXPECT_LT(energy, 0.1 * start);
}

TEST(VehicleDynamics, RestoringMomentRightsATiltedVehicle) {
  VehicleDynamicsParams p;
  p.buoyancy_n = p.weight_n;
  const VehicleDynamics dyn{p};
  VehicleState s;
  s.position_world_m.z() = 5.0;
  s.q_world_body = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());
  const Vector6d w = dyn.restoring_wrench(s.q_world_body);
  EXPECT_LT(w(3), 0.0);  // rolled to starboard, pushed back to port
  for (int i = 0; i < 30000; ++i) dyn.step(s, Vector6d::Zero(), kNoCurrent, kNoCurrent, 0.002);
  EXPECT_LT(s.q_world_body.angularDistance(Eigen::Quaterniond::Identity()), 0.1);
}

TEST(VehicleDynamics, DriftsWithTheCurrent) {
  VehicleDynamicsParams p;
  p.buoyancy_n = p.weight_n;
  const VehicleDynamics dyn{p};
  VehicleState s;
  s.position_world_m.z() = 5.0;
  const Eigen::Vector3d current(0.05, -0.08, 0.0);
  for (int i = 0; i < 30000; ++i) dyn.step(s, Vector6d::Zero(), current, kNoCurrent, 0.002);
  EXPECT_NEAR((s.q_world_body * s.velocity_body_mps() - current).norm(), 0.0, 2e-3);
}

TEST(VehicleDynamics, SymmetricHorizontalThrustGivesNoYaw) {
  SimParams p = test::still_water_params();
  SimulatedWorld world(p, VehicleGeometry{}, DockingStation{});
  VehicleState start;
  start.position_world_m = {-10, 0, 2};
  world.reset(start, Eigen::Vector3d::Zero(), 1);
  ThrusterCommand c;
  c.count = 8;
  for (int i = 0; i < 4; ++i) c.thrust_fraction[static_cast<std::size_t>(i)] = 0.6;
  for (int k = 1; k <= 100; ++k) {
    world.command_thrusters(c);
    world.step_to(std::chrono::milliseconds(33 * k));
  }
  const VehicleState& s = world.state();
  EXPECT_GT(s.nu_body(0), 0.3);
  EXPECT_NEAR(s.nu_body(5), 0.0, 1e-9);  // r
  EXPECT_NEAR(s.nu_body(1), 0.0, 1e-9);  // v
  const Eigen::Vector3d x = s.q_world_body * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(std::atan2(x.y(), x.x()), 0.0, 1e-9);
}

}  // namespace
}  // namespace rovctl::hal::mock
