// ControlAllocator: exact solutions on a known matrix, weights, saturation that keeps heave and the
// moments and scales surge and sway, asymmetric limits, non-finite input.
#include "control/control_allocation_pseudo_inverse.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

// Six thrusters, one along each body axis at the origin for forces, and three pairs for moments:
// the effectiveness matrix is known by construction.
hal::ThrusterLayout planar_layout() {
  hal::ThrusterLayout l;
  auto add = [&l](const char* name, Eigen::Vector3d r, Eigen::Vector3d d) {
    hal::Thruster t;
    t.name = name;
    t.position_body_m = r;
    t.direction_body = d;
    t.max_forward_n = 10.0;
    t.max_reverse_n = 5.0;
    t.channel = static_cast<int>(l.thrusters.size());
    l.thrusters.push_back(t);
  };
  // Two surge thrusters at y = -+0.5: surge and yaw.
  add("left", {0, -0.5, 0}, {1, 0, 0});
  add("right", {0, 0.5, 0}, {1, 0, 0});
  return l;
}

// The ESC deadband off, so commands are thrust over maximum.
AllocationParams linear() {
  AllocationParams p;
  p.deadband = 0.0;
  return p;
}

double cos_angle(const Wrench& a, const Wrench& b) { return a.dot(b) / (a.norm() * b.norm()); }

TEST(ControlAllocator, KnownMatrixTwoThrusters) {
  const ControlAllocator alloc(planar_layout(), linear());
  // B = [1 1; 0 0; ...; Mz: -y*dx => left: +0.5, right: -0.5].
  EXPECT_NEAR(alloc.effectiveness().matrix()(5, 0), 0.5, 1e-12);
  EXPECT_NEAR(alloc.effectiveness().matrix()(5, 1), -0.5, 1e-12);
  Wrench w = Wrench::Zero();
  w[0] = 4.0;  // 2 N each
  w[5] = 0.5;  // left - right = 1 N
  hal::ThrusterCommand cmd;
  EXPECT_DOUBLE_EQ(alloc.allocate(w, cmd), 1.0);
  ASSERT_EQ(cmd.count, 2u);
  EXPECT_NEAR(cmd.thrust_fraction[0], 2.5 / 10.0, 1e-12);
  EXPECT_NEAR(cmd.thrust_fraction[1], 1.5 / 10.0, 1e-12);
  // Reverse thrust scales by the reverse maximum: -4 N on a 5 N reverse thruster is -0.8.
  w.setZero();
  w[0] = -8.0;
  alloc.allocate(w, cmd);
  EXPECT_NEAR(cmd.thrust_fraction[0], -0.8, 1e-12);
  EXPECT_NEAR(cmd.thrust_fraction[1], -0.8, 1e-12);
}

TEST(ControlAllocator, BlueRov2ReproducesTheWrench) {
  const ControlAllocator alloc(hal::ThrusterLayout::bluerov2_heavy(), AllocationParams{});
  Wrench w;
  w << 20.0, -10.0, 15.0, 0.0, 0.0, 3.0;
  hal::ThrusterCommand cmd;
  EXPECT_DOUBLE_EQ(alloc.allocate(w, cmd), 1.0);
  EXPECT_EQ(cmd.count, 8u);
  const Wrench achieved = alloc.effectiveness().wrench_for_command(cmd);
  EXPECT_LT((achieved - w).norm(), 1e-9) << achieved.transpose();
  // Pure surge uses the four horizontal thrusters equally (by magnitude); they sit below the
  // origin, so the vertical ones cancel their pitch moment without any net heave.
  w << 40.0, 0, 0, 0, 0, 0;
  const ThrustVector f = alloc.thrust_for(w);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(std::abs(f[i]), std::abs(f[0]), 1e-9);
  EXPECT_NEAR(f.tail<4>().sum(), 0.0, 1e-9);
  EXPECT_GT(std::abs(f[4]), 0.1);
}

// Holding against a current that takes the horizontal thrusters: heave and yaw are given whole and
// surge and sway scaled by what the thrusters leave, not the whole wrench by one factor (which
// would cut the heave that holds the stand-off's depth: the vehicle bobs while it holds).
TEST(ControlAllocator, SaturationKeepsHeaveAndYawAndScalesSurgeAndSway) {
  const ControlAllocator alloc(hal::ThrusterLayout::bluerov2_heavy(), AllocationParams{});
  Wrench w;
  w << 150.0, 90.0, -30.0, 0.0, 0.0, 6.0;  // surge and sway beyond the T200s
  hal::ThrusterCommand cmd;
  const double fraction = alloc.allocate(w, cmd);
  EXPECT_GT(fraction, 0.2);
  EXPECT_LT(fraction, 1.0);
  double largest = 0.0;
  for (std::size_t i = 0; i < cmd.count; ++i) {
    EXPECT_LE(std::abs(cmd.thrust_fraction[i]), 1.0);
    largest = std::max(largest, std::abs(cmd.thrust_fraction[i]));
  }
  EXPECT_NEAR(largest, 1.0, 1e-9);  // the busiest thruster is at its limit, no further
  const Wrench achieved = alloc.effectiveness().wrench_for_command(cmd);
  for (int axis = 2; axis < 6; ++axis) EXPECT_NEAR(achieved[axis], w[axis], 1e-6) << axis;
  // Surge and sway keep their direction, scaled by the fraction returned.
  EXPECT_NEAR(achieved[0], fraction * w[0], 1e-6);
  EXPECT_NEAR(achieved[1], fraction * w[1], 1e-6);
  // One factor for the whole wrench would have given less heave than asked.
  const ThrustVector f = alloc.thrust_for(w);
  double worst = 0.0;
  for (std::size_t i = 0; i < alloc.effectiveness().count(); ++i) {
    worst = std::max(worst, std::abs(f[static_cast<Eigen::Index>(i)]) /
                                alloc.effectiveness().limit_n(i, f[static_cast<Eigen::Index>(i)]));
  }
  EXPECT_GT(worst, 1.1);
}

// Heave and the moments alone beyond the thrusters: they are scaled by one factor, keeping their
// direction, and surge and sway get nothing.
TEST(ControlAllocator, SaturatedHeaveAndMomentsKeepTheirDirection) {
  const ControlAllocator alloc(hal::ThrusterLayout::bluerov2_heavy(), AllocationParams{});
  Wrench w;
  w << 40.0, 0.0, -400.0, 0.0, 0.0, 40.0;  // far beyond the vertical T200s
  hal::ThrusterCommand cmd;
  EXPECT_EQ(alloc.allocate(w, cmd), 0.0);  // surge asked for, none given
  const Wrench achieved = alloc.effectiveness().wrench_for_command(cmd);
  EXPECT_NEAR(achieved[0], 0.0, 1e-6);
  Wrench held = w;
  held[0] = 0.0;
  EXPECT_NEAR(cos_angle(achieved, held), 1.0, 1e-9);
  double largest = 0.0;
  for (std::size_t i = 0; i < cmd.count; ++i) {
    largest = std::max(largest, std::abs(cmd.thrust_fraction[i]));
  }
  EXPECT_NEAR(largest, 1.0, 1e-9);
  // Without surge or sway, the fraction is that common factor.
  const double fraction = alloc.allocate(held, cmd);
  EXPECT_GT(fraction, 0.0);
  EXPECT_NEAR(alloc.effectiveness().wrench_for_command(cmd).norm() / held.norm(), fraction, 1e-9);
}

TEST(ControlAllocator, SaturationUsesTheReverseLimit) {
  const ControlAllocator alloc(planar_layout(), linear());
  Wrench w = Wrench::Zero();
  w[0] = -20.0;  // -10 N each, reverse maximum 5 N: half achievable
  hal::ThrusterCommand cmd;
  EXPECT_NEAR(alloc.allocate(w, cmd), 0.5, 1e-12);
  EXPECT_NEAR(cmd.thrust_fraction[0], -1.0, 1e-12);
  w[0] = 20.0;  // forward maximum 10 N: all of it
  EXPECT_NEAR(alloc.allocate(w, cmd), 1.0, 1e-12);
  EXPECT_NEAR(cmd.thrust_fraction[0], 1.0, 1e-12);
}

TEST(ControlAllocator, ThrusterWeightsShiftTheEffort) {
  AllocationParams params;
  params.thruster_weights = {{"t1_front_right", 4.0}};
  const ControlAllocator plain(hal::ThrusterLayout::bluerov2_heavy(), AllocationParams{});
  const ControlAllocator weighted(hal::ThrusterLayout::bluerov2_heavy(), params);
  Wrench w;
  w << 30.0, 10.0, 0.0, 0.0, 0.0, 2.0;
  const ThrustVector fp = plain.thrust_for(w);
  const ThrustVector fw = weighted.thrust_for(w);
  EXPECT_LT(std::abs(fw[0]), std::abs(fp[0]));
  // Still exact: the weights pick among the solutions, they do not change the wrench.
  EXPECT_LT((weighted.effectiveness().matrix() * fw - w).norm(), 1e-9);

  params.thruster_weights = {{"no_such_thruster", 2.0}};
  EXPECT_THROW(ControlAllocator(hal::ThrusterLayout::bluerov2_heavy(), params),
               std::invalid_argument);
}

TEST(ControlAllocator, AxisWeightsRankConflictingAxes) {
  // One surge thruster off the centre line gives Fx = f and Mz = 0.5 f; asking for Fx = 1 and
  // Mz = -0.5 cannot be met, and the axis weights decide which one wins.
  hal::ThrusterLayout one = planar_layout();
  one.thrusters.resize(1);
  Wrench w = Wrench::Zero();
  w[0] = 1.0;
  w[5] = -0.5;
  AllocationParams surge_first;
  surge_first.axis_weights_force = {10000.0, 1.0, 1.0};
  AllocationParams yaw_first;
  yaw_first.axis_weights_moment = {1.0, 1.0, 10000.0};
  EXPECT_NEAR(ControlAllocator(one, surge_first).thrust_for(w)[0], 1.0, 0.01);
  EXPECT_NEAR(ControlAllocator(one, yaw_first).thrust_for(w)[0], -1.0, 0.01);
}

TEST(ControlAllocator, CommandsSkipTheDeadband) {
  AllocationParams p;
  p.deadband = 0.1;
  const ControlAllocator alloc(planar_layout(), p);
  Wrench w = Wrench::Zero();
  w[0] = 2.0;  // 1 N each on 10 N thrusters: 0.1 past a 0.1 deadband over the remaining 0.9
  hal::ThrusterCommand cmd;
  EXPECT_DOUBLE_EQ(alloc.allocate(w, cmd), 1.0);
  EXPECT_NEAR(cmd.thrust_fraction[0], 0.1 + 0.9 * 0.1, 1e-12);
  EXPECT_LT((alloc.effectiveness().wrench_for_command(cmd) - w).norm(), 1e-12);
  w[0] = -2.0;  // reverse: 1 N of 5 N
  alloc.allocate(w, cmd);
  EXPECT_NEAR(cmd.thrust_fraction[1], -(0.1 + 0.9 * 0.2), 1e-12);
  w.setZero();
  alloc.allocate(w, cmd);
  EXPECT_EQ(cmd.thrust_fraction[0], 0.0);  // no thrust wanted: neutral, not the deadband edge
  w[0] = 1000.0;
  EXPECT_NEAR(alloc.allocate(w, cmd), 20.0 / 1000.0, 1e-12);
  EXPECT_NEAR(cmd.thrust_fraction[0], 1.0, 1e-12);
}

TEST(ControlAllocator, NonFiniteWrenchGivesNeutral) {
  const ControlAllocator alloc(hal::ThrusterLayout::bluerov2_heavy(), AllocationParams{});
  Wrench w = Wrench::Constant(5.0);
  w[3] = std::numeric_limits<double>::quiet_NaN();
  hal::ThrusterCommand cmd;
  cmd.thrust_fraction.fill(0.7);
  EXPECT_EQ(alloc.allocate(w, cmd), 0.0);
  EXPECT_EQ(cmd.count, 8u);
  for (double c : cmd.thrust_fraction) EXPECT_EQ(c, 0.0);
}

// The BlueROV2-heavy layout (deploy/config flies the default) without any one of its eight
// thrusters still produces a requested x, y, z and yaw wrench: exactly while nothing saturates,
// and the removed thruster is never commanded.
TEST(AllocatorWithoutAThruster, AnyOneOfEightRemovedStillGivesTheRequestedWrench) {
  const hal::ThrusterLayout layout = hal::VehicleGeometry{}.thrusters;
  Wrench request;
  request << 12.0, -8.0, 10.0, 0.0, 0.0, 1.2;
  for (std::size_t removed = 0; removed < 8; ++removed) {
    ControlAllocator allocator(layout, AllocationParams{});
    ASSERT_TRUE(allocator.servo_axes_controllable());
    EXPECT_TRUE(allocator.remove_thruster(removed)) << removed;
    EXPECT_FALSE(allocator.active(removed));
    EXPECT_EQ(allocator.active_count(), 7u);
    hal::ThrusterCommand command;
    const double achieved = allocator.allocate(request, command);
    EXPECT_DOUBLE_EQ(achieved, 1.0) << removed;
    EXPECT_EQ(command.thrust_fraction[static_cast<std::size_t>(layout.thrusters[removed].channel)],
              0.0);
    const Wrench produced = allocator.effectiveness().wrench_for_command(command);
    for (int axis : {0, 1, 2, 5}) {
      EXPECT_NEAR(produced[axis], request[axis], 0.02 * request.norm())
          << "thruster " << removed << " removed, axis " << axis;
    }
  }
}

TEST(AllocatorWithoutAThruster, TwoHorizontalThrustersLostLeaveTheServoAxesUncontrollable) {
  ControlAllocator allocator(hal::VehicleGeometry{}.thrusters, AllocationParams{});
  EXPECT_TRUE(allocator.remove_thruster(0));  // three vectored thrusters: x, y, yaw still
  EXPECT_FALSE(allocator.remove_thruster(1));
  EXPECT_FALSE(allocator.servo_axes_controllable());
}

TEST(ControlAllocator, AxisCapacityIsTheWeakerDirectionsLimit) {
  ControlAllocator alloc(planar_layout(), linear());
  const Wrench capacity = alloc.axis_capacity();
  // Surge: 5 N a side each way, the reverse limit the weaker: 10 N. Yaw: one thruster forward,
  // one in reverse at 0.5 m: the reverse one at 5 N makes 2 x 5 x 0.5 = 5 N m.
  EXPECT_NEAR(capacity[0], 10.0, 1e-9);
  EXPECT_NEAR(capacity[5], 5.0, 1e-9);
  // Sway: no thruster acts along it.
  EXPECT_EQ(capacity[1], 0.0);
  // What allocate() gives at that capacity is exactly the limit, no more.
  Wrench w = Wrench::Zero();
  w[0] = -capacity[0];
  hal::ThrusterCommand cmd;
  EXPECT_NEAR(alloc.allocate(w, cmd), 1.0, 1e-9);
  w[0] *= 1.1;
  EXPECT_LT(alloc.allocate(w, cmd), 1.0);
  // One thruster lost: less is left.
  alloc.remove_thruster(0);
  EXPECT_GT(alloc.axis_capacity()[0], 0.0);
  EXPECT_LT(alloc.axis_capacity()[0], 10.0 - 1e-6);
}

}  // namespace
}  // namespace rovctl::control
