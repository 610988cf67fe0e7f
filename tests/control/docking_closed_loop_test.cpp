// The control stack alone in the closed loop: mission + servo + allocation driving the mock HAL's
// 6-DOF BlueROV2 dynamics and thruster model in a current, with the pose "estimate" taken from the
// truth plus noise and a field-of-view check (no images, no RM-GA). Checks that control can meet
// the docking targets when the estimate is good; the full loop is `rovctl sim`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "control/attitude_stabilizer.hpp"
#include "control/control_allocation_pseudo_inverse.hpp"
#include "control/mission.hpp"
#include "control/pd_visual_servo.hpp"
#include "hal/mock/thruster_model.hpp"
#include "hal/mock/vehicle_dynamics.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

struct TrialResult {
  bool docked = false;
  double lateral_m = 1.0;  // probe tip off the socket axis at contact
  double yaw_deg = 180.0;
  double time_s = 0.0;
  int aborts = 0;
  MissionState final_state = MissionState::search;
  std::string final_reason;  // of the last transition
  double end_s = 0.0;        // when the mission finished (docked or failed)
  bool thrust_after_end = false;
  // In APPROACH: the marker's largest true bearing off the camera's axis (about the vertical),
  // and the ticks it was out of the image.
  double approach_bearing_max_rad = 0.0;
  int approach_unseen_ticks = 0;
};

// Where a trial starts, relative to the docked pose: back along the docking axis, off it to
// starboard (seen from the vehicle), and the heading turned to starboard of the docked one.
struct TrialStart {
  double back_m = 0.0;
  double starboard_m = 0.0;
  double heading_rad = 0.0;
};

// Beyond this range the marker counts as not found (a current that carries the vehicle off must
// take it out of sight, as in the water).
constexpr double kVisibleRangeM = 3.5;

TrialResult run_trial(std::uint64_t seed, double current_mps, const TrialStart* start = nullptr,
                      double view_bearing_rad = MissionParams{}.approach_view_bearing_rad,
                      const Eigen::Vector3d* current_world_mps = nullptr) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);

  // The geometry and gains this control-only loop was tuned with (probe 0.35 m ahead of the body
  // origin, socket 50 mm proud of the marker, stiff yaw): without camera latency or an estimator
  // it needs no more. With the shipped geometry (probe 0.55 m, chosen so the marker stays in view
  // at contact) this plant's heave/pitch coupling limit-cycles in ALIGN; the full loop with the
  // shipped config is measured by rovctl sim and VehicleLoop.DocksOnAFixedSeed instead.
  hal::VehicleGeometry geometry;
  geometry.probe_tip_body_m = Eigen::Vector3d(0.35, 0.0, 0.05);
  hal::DockingStation station;
  station.socket_marker_m = Eigen::Vector3d(0.0, 0.10, 0.05);
  const Eigen::Isometry3d T_body_cl = geometry.T_body_cl();
  const Eigen::Isometry3d docked =
      hal::docked_T_cl_marker(T_body_cl, geometry.probe_tip_body_m, station);
  ControlParams control;
  control.servo.kp_angular.z() = 8.0;
  control.servo.kd_angular.z() = 3.0;
  control.servo.ki_angular.z() = 1.0;
  MissionParams mission_params;
  mission_params.align_yaw_rad = 0.03;
  mission_params.approach_view_bearing_rad = view_bearing_rad;
  const ControlAllocator allocator(geometry.thrusters, control.allocation);
  PdVisualServo servo(control.servo, T_body_cl);
  const AttitudeStabilizer stabilizer(control.attitude);
  servo.set_capacity(allocator.axis_capacity());
  Mission mission(mission_params, T_body_cl, docked, geometry.probe_tip_body_m);

  // Station: marker 2 m deep, its docking axis pointing north.
  Eigen::Isometry3d T_world_marker = Eigen::Isometry3d::Identity();
  T_world_marker.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // marker x = east, y = down, z = north
  T_world_marker.translation() = Eigen::Vector3d(0, 0, 2.0);
  const Eigen::Isometry3d T_world_body_docked = T_world_marker * (T_body_cl * docked).inverse();

  const hal::mock::VehicleDynamics dynamics{hal::mock::VehicleDynamicsParams{}};
  hal::mock::ThrusterModel thrusters(geometry.thrusters, hal::mock::ThrusterModelParams{});
  hal::mock::VehicleState s;
  s.position_world_m = T_world_body_docked.translation() +
                       Eigen::Vector3d(-2.5 + 0.5 * uni(rng), 0.4 * uni(rng), 0.2 * uni(rng));
  s.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * uni(rng), Eigen::Vector3d::UnitZ()));
  if (start != nullptr) {
    // World z is down here: the docked body's x and y axes are the docking axis and starboard.
    const Eigen::Matrix3d R = T_world_body_docked.linear();
    s.position_world_m = T_world_body_docked.translation() - start->back_m * R.col(0) +
                         start->starboard_m * R.col(1);
    s.q_world_body = Eigen::Quaterniond(
        R * Eigen::AngleAxisd(start->heading_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  }
  const double heading = M_PI * uni(rng);
  const Eigen::Vector3d current =
      current_world_mps != nullptr
          ? *current_world_mps
          : Eigen::Vector3d(current_mps * std::cos(heading), current_mps * std::sin(heading), 0.0);

  const Eigen::Vector3d socket = station.socket_marker_m;
  const double dt_control = 0.033;
  const int substeps = 6;
  TrialResult r;
  const bool trace = std::getenv("ROVCTL_TRACE") != nullptr;
  std::chrono::nanoseconds now{0};
  for (int tick = 0; tick < static_cast<int>(180.0 / dt_control); ++tick) {
    now += 33ms;
    const double t = tick * dt_control;
    const Eigen::Isometry3d T_world_body = s.T_world_body();
    // Contact: the probe tip past the socket mouth by the capture depth.
    const Eigen::Vector3d tip =
        T_world_marker.inverse() * (T_world_body * geometry.probe_tip_body_m);
    const bool contact = tip.z() >= socket.z() + station.capture_depth_m;
    if (contact && r.time_s == 0.0) {
      r.time_s = t;
      r.lateral_m = (tip - socket).head<2>().norm();
      const Eigen::Matrix3d R_err =
          T_world_body.linear().transpose() * T_world_body_docked.linear();
      const Eigen::Vector3d x = R_err.col(0);
      r.yaw_deg = std::abs(std::atan2(x.y(), x.x())) * 180.0 / M_PI;
    }

    // The estimate: truth plus noise growing with range, seen when the marker is in the image and
    // within the range the estimator finds it at.
    Eigen::Isometry3d T_cl_marker = (T_world_body * T_body_cl).inverse() * T_world_marker;
    const double range = T_cl_marker.translation().norm();
    const Eigen::Vector3d p = T_cl_marker.translation();
    const bool in_view = p.z() > 0.15 && std::abs(p.x() / p.z()) < 0.55 &&
                         std::abs(p.y() / p.z()) < 0.42 && range < kVisibleRangeM;
    const double true_bearing_rad = std::abs(marker_bearing_rad(T_body_cl, T_cl_marker));
    T_cl_marker.translation() +=
        (0.001 + 0.004 * range) * Eigen::Vector3d(gauss(rng), gauss(rng), 2.0 * gauss(rng));
    const Eigen::Vector3d rot_noise =
        (0.3 * M_PI / 180.0) * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    T_cl_marker.linear() =
        T_cl_marker.linear() *
        Eigen::AngleAxisd(rot_noise.norm(), rot_noise.normalized()).toRotationMatrix();

    MissionInput in;
    in.now = now;
    in.recognised = in_view;
    in.full_view = in_view;
    in.fitness = in_view ? 0.9 : 0.1;
    in.T_cl_marker = T_cl_marker;
    in.contact = contact;
    in.disturbance_settled = servo.disturbance().settled();
    in.disturbance_at_limit = servo.disturbance().at_limit();
    in.disturbance_rising = servo.disturbance().rising();
    in.current_beyond_hold = servo.disturbance().beyond_hold();
    const MissionOutput out = mission.update(in);
    if (out.state == MissionState::approach) {
      r.approach_bearing_max_rad = std::max(r.approach_bearing_max_rad, true_bearing_rad);
      r.approach_unseen_ticks += in_view ? 0 : 1;
    }
    MissionEvent e;
    while (mission.pop_event(e)) {
      r.final_reason = e.reason;
      if (trace) {
        std::printf("  %6.2f s %s -> %s (%s) lat %.3f ax %.3f yaw %.3f tip %.3f %.3f %.3f\n", t,
                    to_string(e.from), to_string(e.to), e.reason, out.lateral_error_m,
                    out.axial_error_m, out.yaw_error_rad, tip.x(), tip.y(), tip.z());
      }
    }
    if (trace) {
      if (tick % 5 == 0) {
        const Eigen::Vector3d rpy = s.q_world_body.toRotationMatrix().eulerAngles(2, 1, 0);
        std::printf(
            "  %6.2f s %-8s seen %d lat %.3f ax %.3f yaw %.3f p_cl %.2f %.2f %.2f "
            "depth %.2f ypr %.2f %.2f %.2f\n",
            t, to_string(out.state), in_view, out.lateral_error_m, out.axial_error_m,
            out.yaw_error_rad, p.x(), p.y(), p.z(), s.position_world_m.z(), rpy[0], rpy[1], rpy[2]);
      }
    }
    if (out.state == MissionState::docked || out.state == MissionState::failed) {
      r.end_s = t;
      r.thrust_after_end = out.thrusters_enabled;
      break;
    }

    Wrench w = servo.hold_wrench_body();
    if (out.servo_active) {
      if (out.servo_restart) servo.restart();
      servo.keep_in_view(out.max_bearing_rad);
      w = servo.update(T_cl_marker, out.T_cl_marker_desired, 33ms);
    } else if (out.use_override) {
      w += out.wrench_override_body;
    }
    {
      // Roll and pitch held level from the attitude, as the vehicle loop does: left to the
      // servo's damping alone, this plant pitched 25-40 deg nose up in a long approach, the
      // heave trim then learnt the approach's error tipped into body z, and the vehicle climbed
      // out of view.
      hal::SensorReadings readings;
      readings.attitude_valid = true;
      readings.q_world_body = s.q_world_body;
      readings.omega_body_radps = s.omega_body_radps();
      Eigen::Vector2d level_nm;
      if (stabilizer.update(readings, level_nm)) w.segment<2>(3) = level_nm;
    }
    hal::ThrusterCommand cmd;
    if (out.thrusters_enabled) {
      const double fraction = allocator.allocate(w, cmd);
      if (trace && tick % 15 == 0)
        std::printf("  dist %.1f %.1f ratio %.2f lim %d sat %.2f w %.1f %.1f\n",
                    servo.disturbance().wrench_body()[0], servo.disturbance().wrench_body()[1],
                    servo.disturbance().hold_ratio(), servo.disturbance().at_limit(), fraction,
                    w[0], w[1]);
      servo.set_allocation_fraction(fraction);
    } else {
      allocator.neutral(cmd);
    }
    thrusters.command(cmd, t);
    for (int k = 0; k < substeps; ++k) {
      const double ts = t + k * dt_control / substeps;
      thrusters.step(ts, dt_control / substeps);
      dynamics.step(s, thrusters.wrench_body(), current, Eigen::Vector3d::Zero(),
                    dt_control / substeps);
    }
  }
  r.docked = mission.state() == MissionState::docked;
  r.aborts = mission.aborts();
  r.final_state = mission.state();
  return r;
}

TEST(DockingClosedLoop, DocksWithinTolerancesInCurrent) {
  // 100 trials: the bar is 90 %, and over 20 one trial drifting in the blind push is 5 % of it.
  const int trials = std::getenv("ROVCTL_TRIALS") ? std::atoi(std::getenv("ROVCTL_TRIALS")) : 100;
  int success = 0;
  double worst_lateral = 0.0, worst_yaw = 0.0;
  for (int i = 0; i < trials; ++i) {
    const TrialResult r = run_trial(1000 + static_cast<std::uint64_t>(i), 0.1);
    const bool ok = r.docked && r.lateral_m <= 0.010 && r.yaw_deg <= 3.0;
    success += ok ? 1 : 0;
    if (r.docked) {
      worst_lateral = std::max(worst_lateral, r.lateral_m);
      worst_yaw = std::max(worst_yaw, r.yaw_deg);
    }
    std::printf("trial %2d: %s lateral %.1f mm yaw %.2f deg t %.1f s aborts %d\n", i,
                ok ? "ok  " : "FAIL", r.lateral_m * 1e3, r.yaw_deg, r.time_s, r.aborts);
  }
  std::printf("success %d/%d, worst lateral %.1f mm, worst yaw %.2f deg\n", success, trials,
              worst_lateral * 1e3, worst_yaw);
  // The full target (>= 95 % over 100 trials) is measured with the estimator by `rovctl sim`;
  // here the control stack alone must not be the reason it is missed.
  EXPECT_GE(success, trials * 9 / 10);
}

// Found far off the docking axis, looking at the marker: the axis's heading is 49 deg away. A
// pose-based servo turns there while it sways toward the axis, and the marker leaves the image
// (the sim's recharge trial 33 lost it four times that way). Turning only as far as keeps the
// marker within mission.approach_view_bearing_rad (15 deg) holds it there, within a degree and a
// half, through the whole approach and docks without an abort. The free turn (no bound) swings it
// to about 27 deg, 2 deg inside the image's edge (atan 0.55: 29 deg); this noise-free plant keeps
// it just inside, but a frame's latency or a gust more would lose it.
TEST(DockingClosedLoop, KeepsTheMarkerInViewFromFarOffTheAxis) {
  TrialStart start;
  start.back_m = 1.2;
  start.starboard_m = 1.4;
  start.heading_rad = std::atan2(-start.starboard_m, start.back_m);  // toward the marker
  const double bound_rad = MissionParams{}.approach_view_bearing_rad;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const TrialResult kept = run_trial(seed, 0.0, &start);
    const TrialResult turned = run_trial(seed, 0.0, &start, 0.0);
    std::printf(
        "seed %d: kept in view: docked %d aborts %d t %.1f s bearing max %.1f deg unseen %d; "
        "free turn: docked %d aborts %d bearing max %.1f deg unseen %d\n",
        static_cast<int>(seed), kept.docked, kept.aborts, kept.time_s,
        kept.approach_bearing_max_rad * 180.0 / M_PI, kept.approach_unseen_ticks, turned.docked,
        turned.aborts, turned.approach_bearing_max_rad * 180.0 / M_PI,
        turned.approach_unseen_ticks);
    EXPECT_TRUE(kept.docked) << "seed " << seed;
    EXPECT_EQ(kept.aborts, 0) << "seed " << seed;
    EXPECT_EQ(kept.approach_unseen_ticks, 0) << "seed " << seed;
    EXPECT_LE(kept.approach_bearing_max_rad, bound_rad + 1.5 * M_PI / 180.0) << "seed " << seed;
    EXPECT_GT(turned.approach_bearing_max_rad, 1.5 * bound_rad) << "seed " << seed;
  }
}

// A current the thrusters cannot hold (0.8 m/s across the docking axis; the BlueROV2 Heavy holds
// about 0.6 m/s sideways): the mission ends FAILED "current beyond hold" in bounded time, not in
// retries until the mission timer, and leaves the thrusters neutral. Levelled, the vehicle gives
// way slowly (19-41 s to be carried out of kVisibleRangeM) with the estimate at its limit, so the
// first loss ends it; a marker swept from view while the estimate still rises ends it at the
// second (mission.beyond_hold_losses).
TEST(DockingClosedLoop, ACurrentBeyondTheThrustersEndsTheMissionAsBeyondHold) {
  const Eigen::Vector3d across(0.0, 0.8, 0.0);  // the marker's axis points north: this is east
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const TrialResult r =
        run_trial(seed, 0.0, nullptr, MissionParams{}.approach_view_bearing_rad, &across);
    EXPECT_EQ(r.final_state, MissionState::failed) << "seed " << seed;
    EXPECT_EQ(r.final_reason, "current beyond hold") << "seed " << seed;
    EXPECT_LT(r.end_s, 60.0) << "seed " << seed;
    EXPECT_FALSE(r.thrust_after_end) << "seed " << seed;
    EXPECT_LE(r.aborts, 1) << "seed " << seed;
  }
}

}  // namespace
}  // namespace rovctl::control
