// Mission: the nominal SEARCH -> APPROACH -> ALIGN -> DOCK -> DOCKED sequence, loss of the marker
// mid-approach, the ALIGN hold, DOCK limits and the blind push, retries, the event queue.
#include "control/mission.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

class MissionTest : public ::testing::Test {
 protected:
  hal::VehicleGeometry geometry;
  Eigen::Isometry3d T_body_cl = geometry.T_body_cl();
  Eigen::Isometry3d docked =
      hal::docked_T_cl_marker(T_body_cl, geometry.probe_tip_body_m, hal::DockingStation{});
  MissionParams params;
  std::chrono::nanoseconds now{0};

  Mission make() { return Mission(params, T_body_cl, docked, geometry.probe_tip_body_m); }

  // The marker as seen when the docked body frame lies at `d` (body axes) from the vehicle:
  // d.x() > 0 means the vehicle is short of docked by that much.
  Eigen::Isometry3d seen_at(const Eigen::Vector3d& d, double yaw = 0.0) const {
    const Eigen::Isometry3d T =
        Eigen::Translation3d(d) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    return T_body_cl.inverse() * T * T_body_cl * docked;
  }
  MissionOutput tick(Mission& m, bool recognised, const Eigen::Isometry3d& T, bool contact = false,
                     double fitness = 0.9, bool full_view = true) {
    now += 33ms;
    MissionInput in;
    in.now = now;
    in.recognised = recognised;
    in.full_view = recognised && full_view;
    in.fitness = fitness;
    in.T_cl_marker = T;
    in.contact = contact;
    in.attitude_aided = attitude_aided;
    in.disturbance_settled = settled;
    in.disturbance_at_limit = at_limit;
    in.disturbance_rising = rising;
    in.current_beyond_hold = beyond_hold;
    return m.update(in);
  }
  // The servo's estimate of the current, as the next ticks report it.
  bool settled = true;
  bool at_limit = false;
  bool rising = false;
  bool beyond_hold = false;
  bool attitude_aided = false;  // the next ticks' partial views have the attitude sensor's rotation
  MissionOutput blind(Mission& m) { return tick(m, false, Eigen::Isometry3d::Identity()); }
  static std::vector<std::string> drain(Mission& m) {
    std::vector<std::string> out;
    MissionEvent e;
    while (m.pop_event(e)) {
      out.push_back(std::string(to_string(e.from)) + ">" + to_string(e.to) + ":" + e.reason);
    }
    return out;
  }
  // Drives a fresh mission to APPROACH.
  void to_approach(Mission& m) {
    for (int k = 0; k < params.acquire_frames; ++k) tick(m, true, seen_at({2.0, 0.2, 0.1}));
    ASSERT_EQ(m.state(), MissionState::approach);
  }
  void to_dock(Mission& m) {
    to_approach(m);
    tick(m, true, seen_at({params.standoff_m, 0, 0}));
    ASSERT_EQ(m.state(), MissionState::align);
    for (int k = 0; k < params.align_hold_frames; ++k)
      tick(m, true, seen_at({params.standoff_m, 0, 0}));
    ASSERT_EQ(m.state(), MissionState::dock);
  }
};

TEST_F(MissionTest, NominalSequenceToDocked) {
  Mission m = make();
  // SEARCH: nothing seen, slow yaw scan, servo off.
  MissionOutput out;
  for (int k = 0; k < 10; ++k) out = blind(m);
  EXPECT_EQ(out.state, MissionState::search);
  EXPECT_TRUE(out.use_override);
  EXPECT_FALSE(out.servo_active);
  EXPECT_DOUBLE_EQ(out.wrench_override_body[5], params.search_yaw_moment_nm);
  EXPECT_TRUE(out.thrusters_enabled);
  EXPECT_EQ(out.max_bearing_rad, 0.0);

  // Seen for acquire_frames frames: APPROACH, servo (re)started on the stand-off pose.
  for (int k = 0; k < params.acquire_frames; ++k) out = tick(m, true, seen_at({2.0, 0.2, 0.1}));
  EXPECT_EQ(out.state, MissionState::approach);
  EXPECT_TRUE(out.servo_active);
  EXPECT_TRUE(out.servo_restart);
  EXPECT_FALSE(out.use_override);
  EXPECT_TRUE(out.T_cl_marker_desired.isApprox(m.standoff_T_cl_marker()));
  // The servo turns to the axis's heading only as far as keeps the marker in view.
  EXPECT_GT(params.approach_view_bearing_rad, 0.0);
  EXPECT_EQ(out.max_bearing_rad, params.approach_view_bearing_rad);
  EXPECT_TRUE(out.errors_valid);
  EXPECT_NEAR(out.axial_error_m, -2.0, 1e-9);
  EXPECT_NEAR(out.lateral_error_m, std::hypot(0.2, 0.1), 1e-9);
  out = tick(m, true, seen_at({1.0, 0.0, 0.0}));
  EXPECT_FALSE(out.servo_restart);

  // At the stand-off: ALIGN, then DOCK after align_hold_frames frames within the thresholds.
  out = tick(m, true, seen_at({params.standoff_m + 0.01, 0.003, 0.0}));
  EXPECT_EQ(out.state, MissionState::align);
  EXPECT_FALSE(out.servo_restart);      // the servo keeps its integral through the hand-over
  EXPECT_EQ(out.max_bearing_rad, 0.0);  // at the stand-off, the axis's heading in full
  for (int k = 1; k < params.align_hold_frames; ++k) {
    out = tick(m, true, seen_at({params.standoff_m, 0.002, 0.0}, 0.01));
  }
  EXPECT_EQ(out.state, MissionState::align);
  out = tick(m, true, seen_at({params.standoff_m, 0.002, 0.0}, 0.01));
  EXPECT_EQ(out.state, MissionState::dock);

  // DOCK: the set-point advances along the docking axis at dock_speed_mps.
  const Eigen::Vector3d p0 = out.T_cl_marker_desired.translation();
  for (int k = 0; k < 30; ++k) out = tick(m, true, seen_at({0.4, 0, 0}));
  const double moved = (p0 - out.T_cl_marker_desired.translation()).norm();
  EXPECT_NEAR(moved, params.dock_speed_mps * 30 * 0.033, 1e-6);
  EXPECT_TRUE(out.servo_active);
  EXPECT_EQ(out.max_bearing_rad, 0.0);

  // Contact: DOCKED, thrusters neutral.
  for (int k = 0; k < params.contact_frames; ++k) out = tick(m, true, seen_at({0.0, 0, 0}), true);
  EXPECT_EQ(out.state, MissionState::docked);
  EXPECT_FALSE(out.thrusters_enabled);
  EXPECT_FALSE(out.servo_active);

  const std::vector<std::string> expected = {"search>approach:marker recognised",
                                             "approach>align:stand-off reached",
                                             "align>dock:aligned", "dock>docked:contact"};
  EXPECT_EQ(drain(m), expected);
  EXPECT_EQ(m.aborts(), 0);
}

// A partial view (a sphere hidden or out of one image) is enough to approach on, never to dock on.
TEST_F(MissionTest, ApproachesOnAPartialViewButNeverDocksOnOne) {
  Mission m = make();
  MissionOutput out;
  for (int k = 0; k < params.acquire_frames; ++k) {
    out = tick(m, true, seen_at({2.0, 0.2, 0.1}), false, 0.9, false);
  }
  EXPECT_EQ(out.state, MissionState::approach);
  EXPECT_TRUE(out.servo_active);
  out = tick(m, true, seen_at({params.standoff_m, 0, 0}), false, 0.9, false);
  EXPECT_EQ(out.state, MissionState::align);
  for (int k = 0; k < 3 * params.align_hold_frames; ++k) {
    out = tick(m, true, seen_at({params.standoff_m, 0, 0}), false, 0.9, false);
  }
  EXPECT_EQ(out.state, MissionState::align) << "aligned on a partial view only";
  for (int k = 0; k < params.align_hold_frames; ++k)
    tick(m, true, seen_at({params.standoff_m, 0, 0}));
  ASSERT_EQ(m.state(), MissionState::dock);
  // Docking, still short of the blind zone: on a partial view the push waits where it is, on the
  // hold rather than the servo (a two-sphere pose's yaw is not to be steered on), and aborts when
  // the view stays partial too long.
  out = tick(m, true, seen_at({params.standoff_m - 0.02, 0, 0}), false, 0.9, false);
  EXPECT_FALSE(out.servo_active) << "the servo steered on a partial view while docking";
  EXPECT_TRUE(out.use_override);
  EXPECT_TRUE(out.wrench_override_body.isZero()) << "the hold pushes nothing of its own";
  const Eigen::Vector3d held = out.T_cl_marker_desired.translation();
  const int waiting_ticks = static_cast<int>(params.dock_partial_timeout_s / 0.033);
  for (int k = 0; k < waiting_ticks - 2; ++k) {
    out = tick(m, true, seen_at({params.standoff_m - 0.02, 0, 0}), false, 0.9, false);
  }
  ASSERT_EQ(out.state, MissionState::dock) << "a partial view waits before it aborts";
  EXPECT_TRUE(out.T_cl_marker_desired.translation().isApprox(held, 1e-9))
      << "the push does not advance on a partial view";
  for (int k = 0; k < 5 && m.state() == MissionState::dock; ++k) {
    out = tick(m, true, seen_at({params.standoff_m - 0.02, 0, 0}), false, 0.9, false);
  }
  EXPECT_EQ(m.state(), MissionState::abort);
  const std::vector<std::string> events = drain(m);
  EXPECT_EQ(events.back(), "dock>abort:partial view while docking");
}

// A partial view whose rotation is the attitude sensor's is steered on while the push waits, and
// the dock still aborts if the view stays partial too long.
TEST_F(MissionTest, DockSteersOnAnAttitudeAidedPartialViewWithoutPushing) {
  Mission m = make();
  to_approach(m);
  for (int k = 0; k < params.align_hold_frames + 2; ++k)
    tick(m, true, seen_at({params.standoff_m, 0, 0}));
  ASSERT_EQ(m.state(), MissionState::dock);
  MissionOutput out = tick(m, true, seen_at({params.standoff_m - 0.01, 0, 0}));
  const Eigen::Vector3d held = out.T_cl_marker_desired.translation();
  attitude_aided = true;
  const int waiting_ticks = static_cast<int>(params.dock_partial_timeout_s / 0.033);
  for (int k = 0; k < waiting_ticks - 2; ++k) {
    out = tick(m, true, seen_at({params.standoff_m - 0.01, 0.005, 0}), false, 0.9, false);
    ASSERT_TRUE(out.servo_active) << "tick " << k;
    ASSERT_FALSE(out.use_override);
    ASSERT_TRUE(out.T_cl_marker_desired.translation().isApprox(held, 1e-9))
        << "the push advanced on a partial view";
  }
  for (int k = 0; k < 5 && m.state() == MissionState::dock; ++k)
    out = tick(m, true, seen_at({params.standoff_m - 0.01, 0.005, 0}), false, 0.9, false);
  EXPECT_EQ(m.state(), MissionState::abort);
  EXPECT_EQ(drain(m).back(), "dock>abort:partial view while docking");
}

// A bar passing in front of the marker mid-dock: the push pauses and then goes on to contact.
TEST_F(MissionTest, APassingOccluderPausesTheDockWithoutAborting) {
  Mission m = make();
  to_approach(m);
  tick(m, true, seen_at({params.standoff_m, 0, 0}));
  for (int k = 0; k < params.align_hold_frames + 1; ++k) {
    tick(m, true, seen_at({params.standoff_m, 0, 0}));
  }
  ASSERT_EQ(m.state(), MissionState::dock);
  MissionOutput out = tick(m, true, seen_at({params.standoff_m - 0.01, 0, 0}));
  const double before = out.T_cl_marker_desired.translation().norm();
  for (int k = 0; k < 30; ++k) {  // 1 s hidden
    out = tick(m, true, seen_at({params.standoff_m - 0.01, 0, 0}), false, 0.9, false);
  }
  EXPECT_EQ(out.state, MissionState::dock);
  EXPECT_NEAR(out.T_cl_marker_desired.translation().norm(), before, 1e-9);
  out = tick(m, true, seen_at({params.standoff_m - 0.01, 0, 0}));
  EXPECT_NE(out.T_cl_marker_desired.translation().norm(), before) << "the push goes on";
  tick(m, true, seen_at({0.0, 0, 0}), true);
  for (int k = 0; k < params.contact_frames + 1; ++k) tick(m, true, seen_at({0.0, 0, 0}), true);
  EXPECT_EQ(m.state(), MissionState::docked);
  EXPECT_EQ(m.aborts(), 0);
}

// A gust carries the probe off the axis near the socket: the set-point waits where it is (the
// servo brings the probe back) rather than pushing it in off the axis; back on it, the push goes
// on.
TEST_F(MissionTest, DockWaitsWhileTheProbeIsOffTheAxis) {
  Mission m = make();
  to_dock(m);
  const double off_m = 2.0 * params.dock_wait_lateral_m;  // under dock_abort_lateral_m
  ASSERT_LT(off_m, params.dock_abort_lateral_m);
  auto setpoint_m = [](const MissionOutput& out) {
    return out.T_cl_marker_desired.translation().norm();
  };
  MissionOutput out = tick(m, true, seen_at({0.3, 0, 0}));
  // Carried off the axis and held there (a gust): the low-passed error crosses the line within
  // a few frames, and from then on the set-point waits where it is.
  for (int k = 0; k < 10; ++k) out = tick(m, true, seen_at({0.3, 0, off_m}));
  const double waiting = setpoint_m(out);
  for (int k = 0; k < 20; ++k) out = tick(m, true, seen_at({0.3, 0, off_m}));
  EXPECT_EQ(out.state, MissionState::dock);
  EXPECT_NEAR(setpoint_m(out), waiting, 1e-9);
  // Back on the axis, the push goes on.
  for (int k = 0; k < 10; ++k) out = tick(m, true, seen_at({0.3, 0, 0}));
  EXPECT_LT(setpoint_m(out), waiting - 1e-4) << "the push goes on";
  // Swinging as fast as the frames from one side to the other (a vibrating mount): no drift to
  // wait for.
  const double swinging = setpoint_m(out);
  for (int k = 0; k < 20; ++k) out = tick(m, true, seen_at({0.3, 0, k % 2 == 0 ? off_m : -off_m}));
  EXPECT_LT(setpoint_m(out), swinging - 1e-4) << "a swing is no drift";
  EXPECT_EQ(m.aborts(), 0);
}

// The servo lags DOCK's ramp by centimetres: a wait that left the set-point where the ramp had
// put it would let the probe coast on into the face off the axis.
TEST_F(MissionTest, DockWaitHoldsTheSetPointBehindTheProbe) {
  Mission m = make();
  to_dock(m);
  // How far back from docked along the axis a pose seen_at() puts the marker.
  auto back_m = [this](const Eigen::Isometry3d& T_cl_marker) {
    return (T_body_cl * T_cl_marker * docked.inverse() * T_body_cl.inverse()).translation().x();
  };
  const double probe_back_m = 0.1;
  MissionOutput out;
  // The probe stays 10 cm out while the ramp runs on past it.
  const int ramp_ticks = static_cast<int>((params.standoff_m / params.dock_speed_mps) / 0.033);
  for (int k = 0; k < ramp_ticks; ++k) out = tick(m, true, seen_at({probe_back_m, 0, 0}));
  ASSERT_EQ(out.state, MissionState::dock);
  ASSERT_LT(back_m(out.T_cl_marker_desired), probe_back_m - 0.05) << "the ramp ran ahead";
  // A gust carries it off the axis: the set-point comes back behind the probe and stays there.
  const double off_m = 2.0 * params.dock_wait_lateral_m;
  for (int k = 0; k < 10; ++k) out = tick(m, true, seen_at({probe_back_m, 0, off_m}));
  EXPECT_NEAR(back_m(out.T_cl_marker_desired), probe_back_m + params.dock_wait_backoff_m, 1e-9);
  for (int k = 0; k < 20; ++k) out = tick(m, true, seen_at({probe_back_m, 0, off_m}));
  EXPECT_NEAR(back_m(out.T_cl_marker_desired), probe_back_m + params.dock_wait_backoff_m, 1e-9);
  // Back on the axis, the push goes on from there, not from where the ramp had been.
  for (int k = 0; k < 20; ++k) out = tick(m, true, seen_at({probe_back_m, 0, 0}));
  const double resumed_m = back_m(out.T_cl_marker_desired);
  EXPECT_LT(resumed_m, probe_back_m + params.dock_wait_backoff_m);
  EXPECT_GT(resumed_m, probe_back_m - 0.05);
  EXPECT_EQ(m.aborts(), 0);
}

TEST_F(MissionTest, MarkerLostMidApproachAbortsAndSearchesAtOnceWithoutBackingOff) {
  Mission m = make();
  to_approach(m);
  tick(m, true, seen_at({1.5, 0.1, 0.0}));
  // A brief loss holds (no servo, zero override) without aborting.
  MissionOutput out;
  for (int k = 0; k < params.lost_frames - 1; ++k) out = blind(m);
  EXPECT_EQ(out.state, MissionState::approach);
  EXPECT_FALSE(out.servo_active);
  EXPECT_TRUE(out.use_override);
  EXPECT_TRUE(out.wrench_override_body.isZero());
  out = blind(m);
  EXPECT_EQ(out.state, MissionState::abort);
  EXPECT_EQ(m.aborts(), 1);
  EXPECT_TRUE(out.use_override);
  EXPECT_TRUE(out.wrench_override_body.isZero()) << "no back-off short of the station";
  out = blind(m);
  EXPECT_EQ(out.state, MissionState::search);
  EXPECT_DOUBLE_EQ(out.wrench_override_body[5], params.search_yaw_moment_nm);
  EXPECT_DOUBLE_EQ(out.wrench_override_body[0], 0.0);
  const std::vector<std::string> expected = {"search>approach:marker recognised",
                                             "approach>abort:marker lost",
                                             "abort>search:searching from here"};
  EXPECT_EQ(drain(m), expected);
  // And a second acquisition restarts the servo.
  for (int k = 0; k < params.acquire_frames; ++k) out = tick(m, true, seen_at({1.0, 0, 0}));
  EXPECT_EQ(out.state, MissionState::approach);
  EXPECT_TRUE(out.servo_restart);
}

// While a marker found is confirmed the scan turns toward it, not past it; before it is found and
// after it is lost again, the configured way (the current that took it off the edge would stall a
// scan turning back against it).
TEST_F(MissionTest, SearchTurnsTowardAMarkerBeingConfirmedElseTheConfiguredWay) {
  for (const double configured_nm : {0.6, -0.6}) {
    params.search_yaw_moment_nm = configured_nm;
    for (const double side_m : {-0.3, 0.3}) {
      const double toward_nm = side_m > 0.0 ? 0.6 : -0.6;  // body +y starboard, z down
      Mission m = make();
      EXPECT_DOUBLE_EQ(blind(m).wrench_override_body[5], configured_nm) << "never seen";
      const MissionOutput confirming = tick(m, true, seen_at({2.0, side_m, 0.0}));
      ASSERT_EQ(confirming.state, MissionState::search);
      EXPECT_DOUBLE_EQ(confirming.wrench_override_body[5], toward_nm)
          << "configured " << configured_nm << " N m, marker at y " << side_m << " m";
      EXPECT_DOUBLE_EQ(blind(m).wrench_override_body[5], configured_nm) << "a glimpse, gone";
      to_approach(m);
      tick(m, true, seen_at({1.0, side_m, 0.0}));
      MissionOutput out;
      while (m.state() != MissionState::search) out = blind(m);
      EXPECT_DOUBLE_EQ(out.wrench_override_body[5], configured_nm) << "lost in APPROACH";
    }
  }
}

TEST_F(MissionTest, BriefLossDoesNotRestartTheServo) {
  Mission m = make();
  to_approach(m);
  blind(m);
  blind(m);
  const MissionOutput out = tick(m, true, seen_at({1.0, 0, 0}));
  EXPECT_TRUE(out.servo_active);
  EXPECT_FALSE(out.servo_restart);
}

TEST_F(MissionTest, LowFitnessCountsAsNotRecognised) {
  Mission m = make();
  for (int k = 0; k < 20; ++k)
    tick(m, true, seen_at({1.0, 0, 0}), false, params.min_fitness - 0.01);
  EXPECT_EQ(m.state(), MissionState::search);
}

// ALIGN's hold is judged on the averaged errors: one noisy frame does not restart it, a frame past
// the dock's abort limits does, and an offset that persists never passes.
TEST_F(MissionTest, AlignHoldsOnTheAveragedErrorsNotOnOneNoisyFrame) {
  const double stand = params.standoff_m;
  {
    Mission m = make();
    to_approach(m);
    tick(m, true, seen_at({stand, 0, 0}));
    ASSERT_EQ(m.state(), MissionState::align);
    for (int k = 0; k < params.align_hold_frames - 2; ++k) tick(m, true, seen_at({stand, 0, 0}));
    // Twice the threshold in one frame moves the average by a fifth of it.
    tick(m, true, seen_at({stand, 2.0 * params.align_lateral_m, 0}));
    EXPECT_EQ(m.state(), MissionState::align);
    tick(m, true, seen_at({stand, 0, 0}));
    EXPECT_EQ(m.state(), MissionState::dock) << "one noisy frame restarted the hold";
  }
  {
    Mission m = make();
    to_approach(m);
    tick(m, true, seen_at({stand, 0, 0}));
    for (int k = 0; k < params.align_hold_frames - 1; ++k) tick(m, true, seen_at({stand, 0, 0}));
    // Past the dock's abort limit: the count starts again.
    tick(m, true, seen_at({stand, 1.5 * params.dock_abort_lateral_m, 0}));
    for (int k = 0; k < params.align_hold_frames - 1; ++k) tick(m, true, seen_at({stand, 0, 0}));
    EXPECT_EQ(m.state(), MissionState::align);
    tick(m, true, seen_at({stand, 0, 0}));
    EXPECT_EQ(m.state(), MissionState::dock);
  }
  {
    Mission m = make();
    to_approach(m);
    for (int k = 0; k < 5 * params.align_hold_frames; ++k)
      tick(m, true, seen_at({stand, 1.5 * params.align_lateral_m, 0}));
    EXPECT_EQ(m.state(), MissionState::align) << "a steady offset over the threshold passed";
  }
}

TEST_F(MissionTest, DockAbortsOnLateralAndYawLimits) {
  {
    Mission m = make();
    to_dock(m);
    for (int k = 1; k < params.dock_abort_frames; ++k) {
      tick(m, true, seen_at({0.3, 0, 1.5 * params.dock_abort_lateral_m}));
      EXPECT_EQ(m.state(), MissionState::dock);
    }
    MissionOutput out = tick(m, true, seen_at({0.3, 0, 1.5 * params.dock_abort_lateral_m}));
    EXPECT_EQ(m.state(), MissionState::abort);
    // Near the station the abort backs off for abort_backoff_s, even with the marker in view.
    const auto t_abort = now;
    while (now - t_abort < std::chrono::duration<double>(params.abort_backoff_s) - 33ms) {
      EXPECT_DOUBLE_EQ(out.wrench_override_body[0], -params.abort_backoff_force_n);
      out = tick(m, true, seen_at({0.3, 0, 0}));
      ASSERT_EQ(out.state, MissionState::abort);
    }
    out = blind(m);
    EXPECT_EQ(out.state, MissionState::search);
    EXPECT_EQ(drain(m).back(), "abort>search:backed off");
  }
  {
    Mission m = make();
    to_dock(m);
    for (int k = 0; k < params.dock_abort_frames; ++k)
      tick(m, true, seen_at({0.3, 0, 0}, 1.5 * params.dock_abort_yaw_rad));
    EXPECT_EQ(m.state(), MissionState::abort);
    drain(m);
  }
}

TEST_F(MissionTest, OneOutlierEstimateDoesNotAbortTheDock) {
  params.dock_abort_frames = 3;
  Mission m = make();
  to_dock(m);
  for (int k = 0; k < 5; ++k) {
    tick(m, true, seen_at({0.3, 0, 0}, 1.5 * params.dock_abort_yaw_rad));
    tick(m, true, seen_at({0.3, 0, 0}));
    tick(m, true, seen_at({0.3, 0, 2.0 * params.dock_abort_lateral_m}));
    tick(m, true, seen_at({0.3, 0, 0}));
  }
  EXPECT_EQ(m.state(), MissionState::dock);
}

TEST_F(MissionTest, DockPushesBlindNearTheSocket) {
  Mission m = make();
  to_dock(m);
  tick(m, true, seen_at({0.5 * params.dock_blind_distance_m, 0, 0}));
  MissionOutput out;
  // Longer than a loss elsewhere would be allowed, shorter than the blind push's own limit.
  const int blind_ticks = std::min(3 * params.lost_frames,
                                   static_cast<int>((params.dock_blind_timeout_s - 0.5) / 0.033));
  ASSERT_GT(blind_ticks, params.lost_frames);
  for (int k = 0; k < blind_ticks; ++k) out = blind(m);
  EXPECT_EQ(out.state, MissionState::dock);  // no abort for the expected loss of view
  EXPECT_TRUE(out.use_override);
  EXPECT_NEAR(out.wrench_override_body[0], params.dock_blind_push_n, 1e-9);  // along the axis
  out = tick(m, false, Eigen::Isometry3d::Identity(), true);
  for (int k = 1; k < params.contact_frames; ++k) {
    out = tick(m, false, Eigen::Isometry3d::Identity(), true);
  }
  EXPECT_EQ(out.state, MissionState::docked);
}

// In the blind zone a partial view whose rotation is the estimator's own (no sphere in both views
// for the attitude aid) is pushed through blind, not steered on; an aided one is steered on.
TEST_F(MissionTest, InTheBlindZoneAnUnaidedPartialViewIsPushedBlind) {
  Mission m = make();
  to_dock(m);
  tick(m, true, seen_at({0.5 * params.dock_blind_distance_m, 0, 0}));
  // A two-sphere pose 30 deg off in yaw: steered on, it would turn the vehicle; judged, it
  // would abort on the yaw limit.
  MissionOutput out;
  for (int k = 0; k < 3 * params.dock_abort_frames; ++k) {
    out =
        tick(m, true, seen_at({0.4 * params.dock_blind_distance_m, 0, 0}, 0.52), false, 0.9, false);
    ASSERT_EQ(out.state, MissionState::dock) << "tick " << k;
    ASSERT_FALSE(out.servo_active) << "tick " << k;
    ASSERT_TRUE(out.use_override);
    ASSERT_NEAR(out.wrench_override_body[0], params.dock_blind_push_n, 1e-9);
  }
  attitude_aided = true;
  out = tick(m, true, seen_at({0.4 * params.dock_blind_distance_m, 0.002, 0}), false, 0.9, false);
  EXPECT_TRUE(out.servo_active) << "an aided partial view in the blind zone is steered on";
  EXPECT_FALSE(out.use_override);
  attitude_aided = false;
  // The blind push's own limit still ends it.
  const auto t0 = now;
  while (m.state() == MissionState::dock && now - t0 < 60s) {
    tick(m, true, seen_at({0.4 * params.dock_blind_distance_m, 0, 0}, 0.52), false, 0.9, false);
  }
  EXPECT_EQ(m.state(), MissionState::abort);
  EXPECT_NEAR(std::chrono::duration<double>(now - t0).count(), params.dock_blind_timeout_s, 0.1);
  EXPECT_EQ(drain(m).back(), "dock>abort:no contact after blind push");
}

TEST_F(MissionTest, BlindPushTimesOut) {
  Mission m = make();
  to_dock(m);
  tick(m, true, seen_at({0.05, 0, 0}));
  const auto t0 = now;
  while (m.state() == MissionState::dock && now - t0 < 60s) blind(m);
  EXPECT_EQ(m.state(), MissionState::abort);
  EXPECT_NEAR(std::chrono::duration<double>(now - t0).count(), params.dock_blind_timeout_s, 0.1);
}

TEST_F(MissionTest, LossFarFromTheSocketAbortsTheDock) {
  Mission m = make();
  to_dock(m);
  tick(m, true, seen_at({2.0 * params.dock_blind_distance_m, 0, 0}));
  for (int k = 0; k < params.lost_frames; ++k) blind(m);
  EXPECT_EQ(m.state(), MissionState::abort);
}

TEST_F(MissionTest, RetriesAreBounded) {
  params.max_retries = 2;
  params.abort_backoff_s = 0.1;
  Mission m = make();
  for (int attempt = 0; attempt <= params.max_retries; ++attempt) {
    to_approach(m);
    while (m.state() == MissionState::approach) blind(m);
    if (attempt < params.max_retries) {
      ASSERT_EQ(m.state(), MissionState::abort);
      while (m.state() == MissionState::abort) blind(m);
      ASSERT_EQ(m.state(), MissionState::search);
    }
  }
  EXPECT_EQ(m.state(), MissionState::failed);
  EXPECT_EQ(m.aborts(), 3);
  const MissionOutput out = tick(m, true, seen_at({1.0, 0, 0}));
  EXPECT_FALSE(out.thrusters_enabled);
  EXPECT_EQ(out.state, MissionState::failed);
  const std::vector<std::string> events = drain(m);
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back(), "abort>failed:retries exhausted");
  m.restart(now);
  EXPECT_EQ(m.state(), MissionState::search);
  EXPECT_EQ(m.aborts(), 0);
}

TEST_F(MissionTest, TimeoutsAbort) {
  params.approach_timeout_s = 2.0;
  Mission m = make();
  to_approach(m);
  for (int k = 0; k < 100; ++k) tick(m, true, seen_at({1.5, 0, 0}));
  EXPECT_EQ(m.state(), MissionState::abort);
  std::vector<std::string> ev = drain(m);
  EXPECT_EQ(ev.back(), "approach>abort:approach timed out");
}

TEST_F(MissionTest, EventQueueKeepsTheNewest) {
  params.abort_backoff_s = 0.0;
  params.max_retries = 100;
  Mission m = make();
  for (int i = 0; i < 20; ++i) {  // 3 events per cycle: 60 events
    to_approach(m);
    while (m.state() != MissionState::search) blind(m);
  }
  EXPECT_EQ(m.dropped_events(), 60 - Mission::kEventCapacity);
  const std::vector<std::string> ev = drain(m);
  EXPECT_EQ(ev.size(), Mission::kEventCapacity);
  EXPECT_EQ(ev.back(), "abort>search:searching from here");
}

TEST_F(MissionTest, StandOffLiesBackAlongTheDockingAxis) {
  Mission m = make();
  const MissionOutput out = tick(m, true, m.standoff_T_cl_marker());
  EXPECT_NEAR(out.axial_error_m, -params.standoff_m, 1e-9);
  EXPECT_NEAR(out.lateral_error_m, 0.0, 1e-9);
  // Docked pose: the marker's docking axis is the camera's optical axis.
  EXPECT_NEAR((m.standoff_T_cl_marker().translation() - docked.translation()).z(),
              params.standoff_m, 1e-9);
}

TEST_F(MissionTest, AlignCountsOnlyOnceTheCurrentsEstimateHasSettled) {
  const double stand = params.standoff_m;
  Mission m = make();
  to_approach(m);
  tick(m, true, seen_at({stand, 0, 0}));
  ASSERT_EQ(m.state(), MissionState::align);
  settled = false;
  for (int k = 0; k < 3 * params.align_hold_frames; ++k) tick(m, true, seen_at({stand, 0, 0}));
  EXPECT_EQ(m.state(), MissionState::align) << "aligned while the estimate was still learning";
  settled = true;
  for (int k = 0; k < params.align_hold_frames - 1; ++k) tick(m, true, seen_at({stand, 0, 0}));
  EXPECT_EQ(m.state(), MissionState::align);
  tick(m, true, seen_at({stand, 0, 0}));
  EXPECT_EQ(m.state(), MissionState::dock);
  // Never settled: the timeout says so.
  Mission n = make();
  to_approach(n);
  tick(n, true, seen_at({stand, 0, 0}));
  settled = false;
  const int timeout_ticks = static_cast<int>(params.align_timeout_s / 0.033) + 2;
  for (int k = 0; k < timeout_ticks && n.state() == MissionState::align; ++k)
    tick(n, true, seen_at({stand, 0, 0}));
  EXPECT_EQ(n.state(), MissionState::abort);
  EXPECT_EQ(drain(n).back(), "align>abort:align timed out: current not settled");
}

TEST_F(MissionTest, ACurrentBeyondHoldFailsTheMissionWithoutRetrying) {
  for (const MissionState where :
       {MissionState::approach, MissionState::align, MissionState::dock}) {
    Mission m = make();
    if (where == MissionState::dock) {
      to_dock(m);
    } else {
      to_approach(m);
      if (where == MissionState::align) tick(m, true, seen_at({params.standoff_m, 0, 0}));
    }
    ASSERT_EQ(m.state(), where);
    beyond_hold = true;
    const MissionOutput out = tick(m, true, seen_at({params.standoff_m, 0.02, 0}));
    beyond_hold = false;
    EXPECT_EQ(out.state, MissionState::failed) << to_string(where);
    EXPECT_FALSE(out.thrusters_enabled);
    EXPECT_TRUE(m.finished());
    EXPECT_EQ(m.aborts(), 0);
    EXPECT_EQ(drain(m).back(), std::string(to_string(where)) + ">failed:current beyond hold");
  }
  // The marker swept out of view while the estimate was at its limit: the same verdict, at once.
  Mission m = make();
  to_approach(m);
  at_limit = true;
  for (int k = 0; k < params.lost_frames; ++k) blind(m);
  at_limit = false;
  EXPECT_EQ(m.state(), MissionState::failed);
  EXPECT_EQ(drain(m).back(), "approach>failed:current beyond hold");
}

// A current that sweeps the marker from view before its estimate reaches the limit: the first
// loss while the estimate is still rising searches again; the mission.beyond_hold_losses-th ends
// the mission. Settling in view between the losses clears the count.
TEST_F(MissionTest, TheMarkerSweptAwayTwiceWhileTheEstimateRisesIsBeyondHold) {
  Mission m = make();
  to_approach(m);
  settled = false;
  rising = true;
  for (int k = 0; k < params.lost_frames; ++k) blind(m);
  blind(m);  // ABORT searches at once after a loss before the dock
  EXPECT_EQ(m.state(), MissionState::search);
  EXPECT_EQ(m.aborts(), 1);
  for (int k = 0; k < params.acquire_frames; ++k) tick(m, true, seen_at({2.0, 0.2, 0.1}));
  ASSERT_EQ(m.state(), MissionState::approach);
  for (int k = 0; k < params.lost_frames; ++k) blind(m);
  EXPECT_EQ(m.state(), MissionState::failed);
  EXPECT_EQ(drain(m).back(), "approach>failed:current beyond hold");

  // Settled in view after the first loss: the second is an ordinary abort.
  Mission n = make();
  to_approach(n);
  for (int k = 0; k < params.lost_frames + 1; ++k) blind(n);
  for (int k = 0; k < params.acquire_frames; ++k) tick(n, true, seen_at({2.0, 0.2, 0.1}));
  settled = true;
  rising = false;
  tick(n, true, seen_at({2.0, 0.2, 0.1}));
  settled = false;
  rising = true;
  for (int k = 0; k < params.lost_frames + 1; ++k) blind(n);
  EXPECT_EQ(n.state(), MissionState::search);
  EXPECT_EQ(n.aborts(), 2);
  settled = true;
  rising = false;
}

}  // namespace
}  // namespace rovctl::control
