// The per-tick calls allocate nothing, counted per thread by the tests' malloc counter (glibc, no
// sanitizer: that also catches Eigen's aligned mallocs).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "control/control_allocation_pseudo_inverse.hpp"
#include "control/failsafe.hpp"
#include "control/mission.hpp"
#include "control/pd_visual_servo.hpp"
#include "control/pose_tracker.hpp"
#include "control/thruster_health.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"
#include "malloc_counter.hpp"

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;
using rovctl::testing::t_allocations;

TEST(Realtime, CounterCounts) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "malloc belongs to the sanitizer runtime";
  }
  const std::uint64_t before = t_allocations;
  // Through a volatile pointer, so that the compiler cannot elide the new/delete pair.
  std::vector<int>* volatile v = new std::vector<int>(100);
  delete v;
  EXPECT_GE(t_allocations - before, 2u);
}

TEST(Realtime, TickCallsDoNotAllocate) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "malloc belongs to the sanitizer runtime";
  }
  const hal::VehicleGeometry geometry;
  const Eigen::Isometry3d T_body_cl = geometry.T_body_cl();
  const Eigen::Isometry3d docked =
      hal::docked_T_cl_marker(T_body_cl, geometry.probe_tip_body_m, hal::DockingStation{});
  ControlParams control;
  control.allocation.thruster_weights = {{"t5_vert_front_right", 2.0}};
  const ControlAllocator allocator(geometry.thrusters, control.allocation);
  PdVisualServo servo(control.servo, T_body_cl);
  MissionParams mp;
  Mission mission(mp, T_body_cl, docked, geometry.probe_tip_body_m);
  Failsafe failsafe(control.failsafe);
  hal::ThrusterCommand command;

  const std::uint64_t before = t_allocations;
  std::chrono::nanoseconds now{0};
  MissionEvent me;
  FailsafeEvent fe;
  for (int k = 0; k < 2000; ++k) {
    now += 33ms;
    MissionInput in;
    in.now = now;
    in.recognised = (k / 50) % 4 != 3;  // drop-outs drive the mission through its states
    in.full_view = in.recognised;
    in.fitness = 0.8;
    in.T_cl_marker = offset_along_docking_axis(docked, 1.0 - 0.0005 * k);
    const MissionOutput out = mission.update(in);
    Wrench w = servo.feedforward_body();
    if (out.servo_active) {
      if (out.servo_restart) servo.reset();
      w = servo.update(in.T_cl_marker, out.T_cl_marker_desired, 33ms);
    } else if (out.use_override) {
      w += out.wrench_override_body;
    }
    servo.set_allocation_fraction(allocator.allocate(w * (k % 7 == 0 ? 50.0 : 1.0), command));
    FailsafeInput fi;
    fi.now = now;
    fi.T_cl_marker = in.T_cl_marker;
    fi.fitness = in.fitness;
    fi.wrench_body = w;
    fi.mission = out.state;
    fi.grab = k == 1500 ? hal::GrabStatus::device_lost : hal::GrabStatus::ok;
    failsafe.update(fi);
    while (mission.pop_event(me)) {
    }
    while (failsafe.pop_event(fe)) {
    }
  }
  EXPECT_EQ(t_allocations - before, 0u);
  EXPECT_TRUE(failsafe.tripped());
  EXPECT_GT(mission.aborts(), 0);
}

TEST(Realtime, PoseTrackerUpdatesDoNotAllocate) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "malloc belongs to the sanitizer runtime";
  }
  PoseTracker tracker(PoseTrackerParams{}, hal::VehicleGeometry{}.T_body_cl(), 0.01, 5.0);
  PoseMeasurement sound;
  sound.sound = true;
  sound.T_cl_marker.translation() = Eigen::Vector3d(0.05, 0.0, 0.8);
  sound.bound_m = 0.004;
  sound.bound_deg = 1.0;
  PoseMeasurement partial = sound;
  partial.sound = false;
  partial.points = 2;
  partial.points_marker_m[0] = Eigen::Vector3d(-0.06, 0.0, 0.0);
  partial.points_marker_m[1] = Eigen::Vector3d(0.06, 0.0, 0.0);
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  tracker.update(std::chrono::milliseconds(0), q, true, sound);  // a candidate, before counting
  const std::uint64_t before = t_allocations;
  for (int f = 1; f < 60; ++f) {  // start, fuse, aid, coast
    const PoseMeasurement& m = f < 20 ? sound : (f < 40 ? partial : PoseMeasurement{});
    tracker.update(std::chrono::milliseconds(33 * f), q, true, m);
  }
  EXPECT_EQ(t_allocations - before, 0u);
  EXPECT_EQ(tracker.last().source, TrackSource::coasting);
}

TEST(Realtime, ThrusterFailureAndReallocationDoNotAllocate) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "malloc belongs to the sanitizer runtime";
  }
  const hal::VehicleGeometry geometry;
  ControlParams control;
  ControlAllocator allocator(geometry.thrusters, control.allocation);
  ThrusterHealth health(allocator.effectiveness(), control.thruster_health);
  hal::ThrusterCommand command;
  Wrench w;
  w << 20.0, -10.0, 15.0, 0.0, 0.0, 1.5;
  allocator.allocate(w, command);
  hal::ThrusterTelemetry tel;
  tel.valid = true;
  tel.count = command.count;
  tel.fault_flags[3] = 1;

  const std::uint64_t before = t_allocations;
  std::size_t failed = 0;
  for (int k = 0; k < 5; ++k) failed += health.update(tel, command, 0.033);
  const bool controllable = allocator.remove_thruster(3) && allocator.remove_thruster(6);
  allocator.allocate(w, command);
  EXPECT_EQ(t_allocations - before, 0u);
  EXPECT_EQ(failed, 1u);
  EXPECT_TRUE(controllable);
}

}  // namespace
}  // namespace rovctl::control
