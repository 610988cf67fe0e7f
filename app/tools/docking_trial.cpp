// The trial runner: builds the mock HAL for the trial, arms, runs the cyclic scheduler over the
// VehicleLoop, and reads the outcome from the simulator's truth (never shown to the loop).
#include "app/tools/docking_trial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>

#include "app/runtime/vehicle.hpp"
#include "app/tools/validation_set.hpp"
#include "hal/mock/battery_model.hpp"
#include "hal/primitives/percentile.hpp"

namespace rovctl::app {
namespace {

double ms(std::chrono::nanoseconds d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

void put_pose(const Eigen::Isometry3d& T, std::array<double, 3>& t, std::array<double, 4>& q) {
  const Eigen::Quaterniond r(T.linear());
  t = {T.translation().x(), T.translation().y(), T.translation().z()};
  q = {r.w(), r.x(), r.y(), r.z()};
}

// The simulator's truth beside the estimate in one record; the loop itself never sees it.
void score_against_truth(const Eigen::Isometry3d& truth, TelemetryRecord& r) {
  put_pose(truth, r.truth_t_m, r.truth_q_wxyz);
  r.flags |= telemetry_flag::truth_valid;
  if ((r.flags & telemetry_flag::estimate_valid) == 0) return;
  const Eigen::Vector3d t(r.est_t_m[0], r.est_t_m[1], r.est_t_m[2]);
  const Eigen::Quaterniond q(r.est_q_wxyz[0], r.est_q_wxyz[1], r.est_q_wxyz[2], r.est_q_wxyz[3]);
  r.est_error_m = (truth.translation() - t).norm();
  r.est_error_rad = Eigen::AngleAxisd(truth.linear().transpose() * q.toRotationMatrix()).angle();
}

}  // namespace

bool trial_docked(const TrialResult& r) {
  return r.docked && r.mission_docked && r.lateral_error_mm <= kSuccessLateralMm &&
         std::abs(r.yaw_error_deg) <= kSuccessYawDeg;
}

bool trial_recharged(const TrialResult& r) {
  return trial_docked(r) && r.charge.charged && r.charge.departed && r.charge.undock_marker_in_view;
}

TrialResult run_docking_trial(const AppConfig& config, const hal::StereoRig& rig,
                              const hal::mock::TrialConditions& conditions,
                              const TrialOptions& options) {
  TrialResult result;
  result.conditions = conditions;

  VehicleOptions vehicle_options;
  vehicle_options.seed = conditions.seed * 7919u + static_cast<std::uint64_t>(conditions.index);
  vehicle_options.helper_threads = false;  // this thread drains between ticks
  vehicle_options.min_ring_capacity = 64;
  vehicle_options.operator_link = options.operator_link;
  Vehicle vehicle(config, rig, make_trial_backends(config, rig, conditions, options.realtime),
                  vehicle_options);
  std::string error;
  if (!vehicle.open(error)) throw std::runtime_error("mock HAL: " + error);
  if (options.realtime) {
    // Paced by the wall clock, a trial is a control loop like `rovctl run`'s: the same
    // scheduler.realtime settings (SCHED_FIFO, mlockall, CPU pinning) on this trial's thread.
    const RealtimeSetupResult& rt = vehicle.enter_realtime();
    for (const auto& w : rt.warnings) result.events.push_back("realtime set-up: " + w);
    for (const auto& a : rt.applied) result.events.push_back("realtime set-up: " + a);
  }
  if (!vehicle.arm(error)) throw std::runtime_error(error);
  VehicleLoop& loop = vehicle.loop();
  if (options.operator_hold_at_start) loop.hold_for_operator();
  hal::mock::SimulatedWorld& sim_world = vehicle.backends().sim->world();
  const hal::mock::SimulatedWorld& world = sim_world;
  // The mid-approach thruster failure: which and when drawn now, injected during APPROACH.
  std::mt19937_64 fault_rng(vehicle_options.seed ^ 0x7468727573746572ULL);
  const int fault_thruster = std::uniform_int_distribution<int>(
      0, static_cast<int>(config.vehicle.thrusters.thrusters.size()) - 1)(fault_rng);
  const double fault_delay_s =
      std::uniform_real_distribution<double>(0.0, options.thruster_fault_window_s)(fault_rng);
  bool fault_injected = options.thruster_fault.empty();
  double approach_start_s = -1.0;

  const auto max_ticks = static_cast<std::uint64_t>(
      options.max_time_s / std::chrono::duration<double>(vehicle.scheduler().period()).count());
  if (options.keep_records) result.records.reserve(max_ticks + 1);
  std::vector<double> estimate_errors_mm;
  estimate_errors_mm.reserve(max_ticks + 1);
  double estimator_ms_sum = 0.0;
  bool captured = false;
  using control::MissionState;
  result.recharge = config.mission.kind == "recharge";
  RechargeResult& charge = result.charge;
  charge.soc_start = world.charge().soc_fraction;
  if (options.keep_records && result.recharge) charge.samples.reserve(max_ticks + 1);
  const double tick_s = std::chrono::duration<double>(vehicle.scheduler().period()).count();
  double thruster_wh_last = world.charge().thruster_wh;
  bool charge_phase_over = false;
  double unseated_run_s = 0.0;
  bool undock_requested = false;

  // Logging, truth and bookkeeping after each tick: the simulation's non-real-time side. The
  // ring is drained every tick, so a record is this tick's and the world's truth is its truth.
  auto drain = [&]() {
    LoopEvent e;
    while (loop.pop_event(e)) {
      result.events.push_back(format_event(e));
      if (e.failsafe) {
        result.failsafe_log.push_back(
            {std::chrono::duration<double>(e.time).count(), e.tick, e.cause, e.failsafe_kind});
      }
      if (!e.failsafe && e.to == control::MissionState::undock) result.charge.end_reason = e.reason;
      if (options.log_events)
        std::cerr << "trial " << conditions.index << ": " << result.events.back() << "\n";
    }
    TelemetryRecord r;
    while (vehicle.telemetry().try_pop(r)) {
      // Drained every tick: the camera's last frame is this record's.
      if ((r.flags & telemetry_flag::full_view) != 0 && vehicle.backends().sim != nullptr) {
        TelemetryRecord at_capture = r;
        score_against_truth(vehicle.backends().sim->camera().last_T_cl_marker_truth(), at_capture);
        const double mm = at_capture.est_error_m * 1000.0;
        const double deg = at_capture.est_error_rad * 180.0 / M_PI;
        ++result.ok_ticks;
        if (mm >= kRightTranslationMm || deg >= kRightRotationDeg) ++result.ok_wrong_ticks;
        if (mm > r.error_bound_m * 1000.0 || deg > r.error_bound_deg) ++result.ok_over_bound_ticks;
        result.ok_error_mm_max = std::max(result.ok_error_mm_max, mm);
        result.ok_error_deg_max = std::max(result.ok_error_deg_max, deg);
      }
      score_against_truth(world.truth().T_cl_marker, r);
      if ((r.flags & telemetry_flag::recognised) && (r.flags & telemetry_flag::truth_valid)) {
        estimate_errors_mm.push_back(r.est_error_m * 1000.0);
      }
      if (options.keep_records) result.records.push_back(r);
    }
    // Injected at the drawn delay into APPROACH, or on its last tick if it ends sooner (it lasts
    // 1-3 s): always during the approach.
    const double now_s = std::chrono::duration<double>(world.time()).count();
    const bool approaching = loop.mission().state() == control::MissionState::approach;
    if (!fault_injected && approaching && approach_start_s < 0.0) approach_start_s = now_s;
    if (!fault_injected && approach_start_s >= 0.0 &&
        (!approaching || now_s >= approach_start_s + fault_delay_s)) {
      fault_injected = true;
      hal::mock::FaultInjection f = config.sim.faults;
      if (options.thruster_fault == "dead") {
        f.thruster_dead_index = fault_thruster;
        f.thruster_dead_at_s = now_s;
      } else if (options.thruster_fault == "weak") {
        f.thruster_weak_index = fault_thruster;
        f.thruster_weak_at_s = now_s;
      } else {
        f.thruster_stuck_index = fault_thruster;
        f.thruster_stuck_at_s = now_s;
      }
      sim_world.set_thruster_faults(f);
      char line[128];
      std::snprintf(line, sizeof(line), "%9.3f s  injected: thruster %d %s (%.3f s into APPROACH)",
                    now_s, fault_thruster, options.thruster_fault.c_str(),
                    now_s - approach_start_s);
      result.events.push_back(line);
      if (options.log_events) std::cerr << "trial " << conditions.index << ": " << line << "\n";
    }
    const auto& d = world.docking();
    if (result.recharge) {
      const control::Mission& m = loop.mission();
      const MissionState st = m.state();
      const auto& c = world.charge();
      if (st == MissionState::charging) charge.charging_reached = true;
      if (st == MissionState::undock || st == MissionState::departed || st == MissionState::failed)
        charge_phase_over = charge_phase_over || charge.charging_reached;
      if (charge.charging_reached && !charge_phase_over) {
        charge.hold_wh += c.thruster_wh - thruster_wh_last;
      }
      thruster_wh_last = c.thruster_wh;
      if (st == MissionState::charging) {
        charge.charging_physics_s += tick_s;
        if (options.undock_request_after_charging_s >= 0.0 && !undock_requested &&
            charge.charging_physics_s >= options.undock_request_after_charging_s) {
          undock_requested = true;
          loop.request_undock();
        }
        if (d.seated) {
          charge.seated_physics_s += tick_s;
          charge.seated_s += tick_s * config.sim.recharge.seated_time_scale;
          unseated_run_s = 0.0;
        } else {
          unseated_run_s += tick_s;
          charge.unseated_unnoticed_max_s =
              std::max(charge.unseated_unnoticed_max_s, unseated_run_s);
        }
      } else {
        unseated_run_s = 0.0;
      }
      if (st == MissionState::departed && !charge.departed) {
        charge.departed = true;
        charge.undock_clearance_m = d.axial_distance_m;
        charge.undock_marker_in_view = loop.last_estimate().recognised;
      }
      if (options.keep_records) {
        const Eigen::Vector3d w = world.current().velocity_world_mps();
        charge.samples.push_back(
            {std::chrono::duration<double>(world.time()).count(), c.soc_fraction,
             c.charge_current_a,
             hal::mock::thruster_power_w(world.thrusters(),
                                         config.sim.recharge.battery.thruster_power_w_per_n1_5),
             std::hypot(w.x(), w.y()), d.seated});
      }
    }
    if (d.contact) {
      result.touch_lateral_max_mm =
          std::max(result.touch_lateral_max_mm, d.lateral_error_m * 1000.0);
    }
    if (d.docked && !captured) {
      captured = true;
      result.time_to_dock_s = std::chrono::duration<double>(d.docked_at).count();
      result.lateral_error_mm = d.lateral_error_m * 1000.0;
      result.yaw_error_deg = d.yaw_error_rad * 180.0 / M_PI;
    }
  };

  const SchedulerStats& stats = vehicle.run(max_ticks, [&](const TickInfo&) {
    // CPU time, not the virtual clock's stage time (which does not advance while computing).
    estimator_ms_sum +=
        std::chrono::duration<double, std::milli>(loop.last_estimate().compute_time).count();
    drain();
  });
  vehicle.make_safe();
  drain();

  result.docked = world.docking().docked;
  // In the recharging mission DOCKED is passed through on the way to CHARGING.
  result.mission_docked = loop.mission().state() == control::MissionState::docked ||
                          (result.recharge && charge.charging_reached);
  if (result.recharge) {
    charge.charged = loop.mission().charge_complete();
    charge.reseats = loop.mission().reseats();
    charge.charged_wh = world.charge().charged_wh;
    charge.hold_fraction = charge.charged_wh > 0.0 ? charge.hold_wh / charge.charged_wh : 0.0;
    charge.contact_fraction =
        charge.charging_physics_s > 0.0 ? charge.seated_physics_s / charge.charging_physics_s : 0.0;
    charge.soc_end = world.charge().soc_fraction;
    charge.end_clearance_m = world.docking().axial_distance_m;
  }
  result.success = trial_docked(result);
  result.sim_time_s = std::chrono::duration<double>(world.time()).count();
  result.final_state = control::to_string(loop.mission().state());
  result.aborts = loop.mission().aborts();
  if (loop.failsafe().tripped()) result.failsafe = control::to_string(loop.failsafe().cause());
  result.ticks = stats.ticks;
  result.overruns = stats.skipped_releases;
  if (vehicle.backends().sim != nullptr) {
    result.bus_stale_sent = vehicle.backends().sim->bus().stale_sent();
    result.bus_landed_after_neutral = vehicle.backends().sim->bus().landed_after_neutral();
  }
  result.jitter_p99_ms = ms(stats.jitter.percentile(0.99));
  result.jitter_max_ms = ms(stats.jitter.max());
  result.estimator_ms_mean =
      stats.ticks > 0 ? estimator_ms_sum / static_cast<double>(stats.ticks) : 0.0;
  result.recognised_fraction = stats.ticks > 0 ? static_cast<double>(loop.recognised_ticks()) /
                                                     static_cast<double>(stats.ticks)
                                               : 0.0;
  result.estimate_error_mm_median =
      estimate_errors_mm.empty() ? -1.0 : hal::percentile(estimate_errors_mm, 0.5);
  return result;
}

}  // namespace rovctl::app
