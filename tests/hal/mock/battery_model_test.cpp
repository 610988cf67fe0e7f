// The battery and the station charger: constant current then the taper, the energy books, the
// thrusters' power draw; and the world's seat, charge and injected charger fault.
#include "hal/mock/battery_model.hpp"

#include <gtest/gtest.h>

#include "hal/mock/charger.hpp"
#include "hal/mock/simulated_world.hpp"
#include "hal/model/vehicle_geometry.hpp"
#include "sim_test_support.hpp"

namespace rovctl::hal::mock {
namespace {

TEST(BatteryModel, AcceptsTheChargerCurrentThenTapersToNothingWhenFull) {
  BatteryParams p;
  BatteryModel b(p);
  b.reset(0.5);
  EXPECT_DOUBLE_EQ(b.accepted_current_a(10.0), 10.0);
  EXPECT_DOUBLE_EQ(b.accepted_current_a(100.0), p.max_charge_current_a);
  b.reset(0.9);  // halfway through the taper
  EXPECT_NEAR(b.accepted_current_a(100.0), 0.5 * p.max_charge_current_a, 1e-9);
  b.reset(1.0);
  EXPECT_DOUBLE_EQ(b.accepted_current_a(100.0), 0.0);
}

TEST(BatteryModel, ChargeAndThrusterEnergyMoveTheStateOfCharge) {
  BatteryParams p;
  p.hotel_power_w = 0.0;
  BatteryModel b(p);
  b.reset(0.5);
  const double v = b.voltage_v();
  b.step(1800.0, 10.0, 0.0);  // half an hour at 10 A
  EXPECT_NEAR(b.charged_wh(), 5.0 * v, 1e-6);
  EXPECT_NEAR(b.soc_fraction(), 0.5 + 5.0 * v / p.capacity_wh, 1e-6);
  const double soc = b.soc_fraction();
  b.step(1800.0, 0.0, 50.0);  // half an hour of 50 W of thrusters
  EXPECT_NEAR(b.thruster_wh(), 25.0, 1e-9);
  EXPECT_NEAR(b.soc_fraction(), soc - 25.0 / p.capacity_wh, 1e-9);
}

// On the bus the charger feeds the hold: in the taper the battery still takes all it accepts, and
// only a load past the charger's limit comes out of the battery.
TEST(BatteryModel, TheChargerFeedsTheThrustersBesideTheBattery) {
  BatteryParams p;
  p.hotel_power_w = 0.0;
  BatteryModel b(p);
  b.reset(0.9);  // halfway through the taper: the battery accepts half the maximum
  const double v = b.voltage_v();
  b.step(1.0, 18.0, 80.0);
  EXPECT_NEAR(b.charge_current_a(), 0.5 * p.max_charge_current_a, 1e-9);
  EXPECT_NEAR(b.charger_current_a(), 0.5 * p.max_charge_current_a + 80.0 / v, 1e-9);
  EXPECT_GT(b.soc_fraction(), 0.9);
  b.reset(0.5);  // constant current: the charger at its limit, the load takes its share
  const double v_half = b.voltage_v();
  b.step(360.0, 18.0, 80.0);  // a tenth of an hour
  EXPECT_NEAR(b.charger_current_a(), 18.0, 1e-9);
  EXPECT_NEAR(b.charge_current_a(), 18.0 - 80.0 / v_half, 1e-9);
  EXPECT_NEAR(b.soc_fraction(), 0.5 + 0.1 * (18.0 * v_half - 80.0) / p.capacity_wh, 1e-9);
  EXPECT_NEAR(b.charged_wh(), 0.1 * 18.0 * v_half, 1e-9);
  b.reset(0.5);  // a load past the offer: the battery gives the rest, and reads no charge
  b.step(360.0, 2.0, 80.0);
  EXPECT_DOUBLE_EQ(b.charge_current_a(), 0.0);
  EXPECT_NEAR(b.soc_fraction(), 0.5 + 0.1 * (2.0 * v_half - 80.0) / p.capacity_wh, 1e-9);
}

TEST(BatteryModel, ThrusterPowerGrowsWithThrustToTheOneAndAHalf) {
  VehicleGeometry vehicle;
  ThrusterModelParams tp;
  tp.deadband = 0.0;
  ThrusterModel thrusters(vehicle.thrusters, tp);
  EXPECT_DOUBLE_EQ(thruster_power_w(thrusters, 0.95), 0.0);
  ThrusterCommand c;
  c.count = vehicle.thrusters.thrusters.size();
  c.thrust_fraction[0] = 0.2;
  thrusters.command(c, 0.0);
  // 0.2 s: inside the ESCs' command timeout, past most of the spin-up.
  for (int i = 0; i < 20; ++i) thrusters.step(0.01 * (i + 1), 0.01);
  const double f = std::abs(thrusters.thrust_n(0)) + std::abs(thrusters.thrust_n(1)) +
                   std::abs(thrusters.thrust_n(2)) + std::abs(thrusters.thrust_n(3));
  ASSERT_GT(f, 1.0);
  const double p1 = thruster_power_w(thrusters, 1.0);
  EXPECT_GT(p1, 0.0);
  EXPECT_NEAR(thruster_power_w(thrusters, 2.0), 2.0 * p1, 1e-9);
}

TEST(Charger, OffersCurrentOnlyWhileSeatedAndHealthy) {
  ChargerParams p;
  Charger c(p);
  EXPECT_DOUBLE_EQ(c.offer_a(true, false), p.max_current_a);
  EXPECT_DOUBLE_EQ(c.offer_a(false, false), 0.0);
  EXPECT_DOUBLE_EQ(c.offer_a(true, true), 0.0);
}

// The world, the vehicle placed seated with the latch open: the charger charges (in sped-up
// battery time), until the injected fault stops it.
TEST(SimulatedWorldCharge, SeatedVehicleChargesFasterThanThePhysicsUntilTheChargerFails) {
  SimParams p = test::still_water_params();
  p.contact.latch_on_dock = false;
  p.recharge.seated_time_scale = 50.0;
  p.recharge.initial_soc_min = p.recharge.initial_soc_max = 0.4;
  p.faults.charger_fails_at_s = 1.0;
  VehicleGeometry vehicle;
  DockingStation station;
  SimulatedWorld world(p, vehicle, station);
  VehicleState seated;
  const Eigen::Isometry3d docked = world.docked_T_world_body();
  seated.q_world_body = Eigen::Quaterniond(docked.linear());
  // The probe 2 mm short of the socket bottom: in, the pins touching, no contact force yet.
  const Eigen::Vector3d axis = world.T_world_marker().linear().col(2);
  seated.position_world_m = docked.translation() + (station.capture_depth_m - 0.002) * axis;
  world.reset(seated, Eigen::Vector3d::Zero(), 1);
  EXPECT_DOUBLE_EQ(world.charge().soc_fraction, 0.4);
  world.step_to(std::chrono::milliseconds(500));
  ASSERT_TRUE(world.docking().seated);
  // The charger's current less the electronics' share (no thrust: the vehicle is at rest).
  EXPECT_NEAR(world.charge().charge_current_a,
              p.recharge.charger.max_current_a -
                  p.recharge.battery.hotel_power_w / world.charge().battery_voltage_v,
              0.05);
  EXPECT_NEAR(world.charge().battery_time_s, 0.5 * 50.0, 1e-6);
  EXPECT_GT(world.charge().soc_fraction, 0.4);
  world.step_to(std::chrono::milliseconds(1200));
  EXPECT_DOUBLE_EQ(world.charge().charge_current_a, 0.0);
}

}  // namespace
}  // namespace rovctl::hal::mock
