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

// A pose as the telemetry record holds it (m, quaternion w x y z) against the truth: m and rad.
void pose_error(const Eigen::Isometry3d& truth, const std::array<double, 3>& t_m,
                const std::array<double, 4>& q_wxyz, double& error_m, double& error_rad) {
  const Eigen::Vector3d t(t_m[0], t_m[1], t_m[2]);
  const Eigen::Quaterniond q(q_wxyz[0], q_wxyz[1], q_wxyz[2], q_wxyz[3]);
  error_m = (truth.translation() - t).norm();
  error_rad = Eigen::AngleAxisd(truth.linear().transpose() * q.toRotationMatrix()).angle();
}

// The simulator's truth beside the estimate in one record; the loop itself never sees it.
void score_against_truth(const Eigen::Isometry3d& truth, TelemetryRecord& r) {
  put_pose(truth, r.truth_t_m, r.truth_q_wxyz);
  r.flags |= telemetry_flag::truth_valid;
  if ((r.flags & telemetry_flag::estimate_valid) != 0) {
    pose_error(truth, r.est_t_m, r.est_q_wxyz, r.est_error_m, r.est_error_rad);
  }
}

// The current's drag on the vehicle at rest (N, body x and y): what the servo's estimate of the
// push should converge to while it holds the vehicle still.
void score_current_push(const hal::mock::WorldTruth& truth,
                        const hal::mock::VehicleDynamicsParams& dynamics, TelemetryRecord& r) {
  const Eigen::Vector3d v_c = truth.T_world_body.linear().transpose() * truth.current_world_mps;
  for (int i = 0; i < 2; ++i) {
    // Fossen's derivatives are negative: the water moving at v_c past a still hull drags it along.
    r.push_truth_n[i] =
        -(dynamics.damping_linear[i] + dynamics.damping_quadratic_linear[i] * std::abs(v_c[i])) *
        v_c[i];
  }
}

// The simulation's non-real-time side of one trial, run after each tick: logs the loop's events,
// scores the telemetry against the simulator's truth, injects the mid-approach thruster failure,
// keeps the recharging figures and notes the capture. The ring is drained every tick, so a
// record is this tick's and the world's truth is its truth.
class TrialRecorder {
 public:
  TrialRecorder(const AppConfig& config, const hal::mock::TrialConditions& conditions,
                const TrialOptions& options, Vehicle& vehicle, std::uint64_t seed,
                std::uint64_t max_ticks, TrialResult& result)
      : config_(config),
        conditions_(conditions),
        options_(options),
        vehicle_(vehicle),
        loop_(vehicle.loop()),
        sim_world_(vehicle.backends().sim->world()),
        world_(sim_world_),
        result_(result),
        charge_(result.charge),
        tick_s_(std::chrono::duration<double>(vehicle.scheduler().period()).count()) {
    // The mid-approach thruster failure: which and when drawn now, injected during APPROACH.
    std::mt19937_64 fault_rng(seed ^ 0x7468727573746572ULL);
    fault_thruster_ = std::uniform_int_distribution<int>(
        0, static_cast<int>(config.vehicle.thrusters.thrusters.size()) - 1)(fault_rng);
    fault_delay_s_ =
        std::uniform_real_distribution<double>(0.0, options.thruster_fault_window_s)(fault_rng);
    fault_injected_ = options.thruster_fault.empty();
    if (options.keep_records) result.records.reserve(max_ticks + 1);
    estimate_errors_mm_.reserve(max_ticks + 1);
    result.recharge = config.mission.kind == "recharge";
    charge_.soc_start = world_.charge().soc_fraction;
    if (options.keep_records && result.recharge) charge_.samples.reserve(max_ticks + 1);
    thruster_wh_last_ = world_.charge().thruster_wh;
  }

  void drain() {
    drain_events();
    drain_telemetry();
    inject_thruster_fault();
    if (result_.recharge) record_charge();
    record_docking();
  }

  // The estimate's error against the truth (mm) on every recognised tick.
  const std::vector<double>& estimate_errors_mm() const { return estimate_errors_mm_; }

 private:
  void log_live(const std::string& line) const {
    if (options_.log_events) std::cerr << "trial " << conditions_.index << ": " << line << "\n";
  }

  void drain_events() {
    LoopEvent e;
    while (loop_.pop_event(e)) {
      result_.events.push_back(format_event(e));
      if (e.failsafe) {
        result_.failsafe_log.push_back(
            {std::chrono::duration<double>(e.time).count(), e.tick, e.cause, e.failsafe_kind});
      }
      if (!e.failsafe && e.to == control::MissionState::undock) charge_.end_reason = e.reason;
      log_live(result_.events.back());
    }
  }

  void drain_telemetry() {
    TelemetryRecord r;
    while (vehicle_.telemetry().try_pop(r)) {
      // Drained every tick: the camera's last frame is this record's.
      // The pose the mission acted on: the tracker's when it is on, else the estimate.
      const bool tracking = (r.flags & telemetry_flag::tracking) != 0;
      const bool acted_ok = tracking ? (r.flags & telemetry_flag::track_ok) != 0
                                     : (r.flags & telemetry_flag::full_view) != 0;
      // The tracked pose is the frame's (or predicted to a tick without one): against the truth
      // of the last capture. The estimate's columns are against the tick's truth (below).
      if (vehicle_.backends().sim != nullptr) {
        const Eigen::Isometry3d& at_capture =
            vehicle_.backends().sim->camera().last_T_cl_marker_truth();
        if (std::isfinite(r.track_t_m[0])) {
          pose_error(at_capture, r.track_t_m, r.track_q_wxyz, r.track_error_m, r.track_error_rad);
        }
        if (acted_ok) score_ok_tick(r, at_capture, tracking);
      }
      const hal::mock::WorldTruth truth = world_.truth();
      score_against_truth(truth.T_cl_marker, r);
      score_current_push(truth, world_.params().dynamics, r);
      if ((r.flags & telemetry_flag::recognised) && (r.flags & telemetry_flag::truth_valid)) {
        estimate_errors_mm_.push_back(r.est_error_m * 1000.0);
      }
      if (options_.keep_records) result_.records.push_back(r);
    }
  }

  // An ok pose (the tracker's or the estimate's) against the truth of its frame: right, and
  // within its error bound?
  void score_ok_tick(const TelemetryRecord& r, const Eigen::Isometry3d& at_capture, bool tracked) {
    double error_m = r.track_error_m, error_rad = r.track_error_rad;
    if (!tracked) pose_error(at_capture, r.est_t_m, r.est_q_wxyz, error_m, error_rad);
    const double mm = error_m * 1000.0;
    const double deg = error_rad * 180.0 / M_PI;
    const double bound_mm = (tracked ? r.track_bound_m : r.error_bound_m) * 1000.0;
    const double bound_deg = tracked ? r.track_bound_deg : r.error_bound_deg;
    ++result_.ok_ticks;
    const auto source = static_cast<control::TrackSource>(r.track_source);
    if (tracked &&
        (source == control::TrackSource::coasting || source == control::TrackSource::aided ||
         source == control::TrackSource::nudged)) {
      ++result_.ok_carried_ticks;
    }
    if (mm >= kRightTranslationMm || deg >= kRightRotationDeg) ++result_.ok_wrong_ticks;
    if (mm > bound_mm || deg > bound_deg) ++result_.ok_over_bound_ticks;
    result_.ok_error_mm_max = std::max(result_.ok_error_mm_max, mm);
    result_.ok_error_deg_max = std::max(result_.ok_error_deg_max, deg);
  }

  // Injected at the drawn delay into APPROACH, or on its last tick if it ends sooner (it lasts
  // 1-3 s): always during the approach.
  void inject_thruster_fault() {
    const double now_s = std::chrono::duration<double>(world_.time()).count();
    const bool approaching = loop_.mission().state() == control::MissionState::approach;
    if (!fault_injected_ && approaching && approach_start_s_ < 0.0) approach_start_s_ = now_s;
    if (fault_injected_ || approach_start_s_ < 0.0 ||
        (approaching && now_s < approach_start_s_ + fault_delay_s_)) {
      return;
    }
    fault_injected_ = true;
    hal::mock::FaultInjection f = config_.sim.faults;
    if (options_.thruster_fault == "dead") {
      f.thruster_dead_index = fault_thruster_;
      f.thruster_dead_at_s = now_s;
    } else if (options_.thruster_fault == "weak") {
      f.thruster_weak_index = fault_thruster_;
      f.thruster_weak_at_s = now_s;
    } else {
      f.thruster_stuck_index = fault_thruster_;
      f.thruster_stuck_at_s = now_s;
    }
    sim_world_.set_thruster_faults(f);
    char line[128];
    std::snprintf(line, sizeof(line), "%9.3f s  injected: thruster %d %s (%.3f s into APPROACH)",
                  now_s, fault_thruster_, options_.thruster_fault.c_str(),
                  now_s - approach_start_s_);
    result_.events.push_back(line);
    log_live(line);
  }

  void record_charge() {
    using control::MissionState;
    const MissionState st = loop_.mission().state();
    const auto& c = world_.charge();
    if (st == MissionState::charging) charge_.charging_reached = true;
    if (st == MissionState::undock || st == MissionState::departed || st == MissionState::failed)
      charge_phase_over_ = charge_phase_over_ || charge_.charging_reached;
    if (charge_.charging_reached && !charge_phase_over_) {
      charge_.hold_wh += c.thruster_wh - thruster_wh_last_;
    }
    thruster_wh_last_ = c.thruster_wh;
    if (st == MissionState::charging) {
      record_charging_tick();
    } else {
      unseated_run_s_ = 0.0;
    }
    const auto& d = world_.docking();
    if (st == MissionState::departed && !charge_.departed) {
      charge_.departed = true;
      charge_.undock_clearance_m = d.axial_distance_m;
      charge_.undock_marker_in_view = loop_.last_estimate().recognised;
    }
    if (options_.keep_records) {
      const Eigen::Vector3d w = world_.current().velocity_world_mps();
      charge_.samples.push_back(
          {std::chrono::duration<double>(world_.time()).count(), c.soc_fraction, c.charge_current_a,
           hal::mock::thruster_power_w(world_.thrusters(),
                                       config_.sim.recharge.battery.thruster_power_w_per_n1_5),
           std::hypot(w.x(), w.y()), d.seated});
    }
  }

  // A tick in CHARGING: the simulated operator's undock request, the time seated (truth).
  void record_charging_tick() {
    charge_.charging_physics_s += tick_s_;
    if (options_.undock_request_after_charging_s >= 0.0 && !undock_requested_ &&
        charge_.charging_physics_s >= options_.undock_request_after_charging_s) {
      undock_requested_ = true;
      loop_.request_undock();
    }
    if (world_.docking().seated) {
      charge_.seated_physics_s += tick_s_;
      charge_.seated_s += tick_s_ * config_.sim.recharge.seated_time_scale;
      unseated_run_s_ = 0.0;
    } else {
      unseated_run_s_ += tick_s_;
      charge_.unseated_unnoticed_max_s =
          std::max(charge_.unseated_unnoticed_max_s, unseated_run_s_);
    }
  }

  void record_docking() {
    const auto& d = world_.docking();
    if (d.contact) {
      result_.touch_lateral_max_mm =
          std::max(result_.touch_lateral_max_mm, d.lateral_error_m * 1000.0);
    }
    if (d.docked && !captured_) {
      captured_ = true;
      result_.time_to_dock_s = std::chrono::duration<double>(d.docked_at).count();
      result_.lateral_error_mm = d.lateral_error_m * 1000.0;
      result_.yaw_error_deg = d.yaw_error_rad * 180.0 / M_PI;
    }
  }

  const AppConfig& config_;
  const hal::mock::TrialConditions& conditions_;
  const TrialOptions& options_;
  Vehicle& vehicle_;
  VehicleLoop& loop_;
  hal::mock::SimulatedWorld& sim_world_;
  const hal::mock::SimulatedWorld& world_;
  TrialResult& result_;
  RechargeResult& charge_;
  const double tick_s_;
  // The thruster failure to inject (TrialOptions::thruster_fault).
  int fault_thruster_ = 0;
  double fault_delay_s_ = 0.0;
  bool fault_injected_ = true;
  double approach_start_s_ = -1.0;  // when APPROACH began, once it has
  std::vector<double> estimate_errors_mm_;
  bool captured_ = false;  // the simulator captured the probe (time and errors noted)
  // Recharging: thruster energy at the last tick, CHARGING over (no more hold energy counted),
  // the current unseated stretch in CHARGING, the operator's undock asked for.
  double thruster_wh_last_ = 0.0;
  bool charge_phase_over_ = false;
  double unseated_run_s_ = 0.0;
  bool undock_requested_ = false;
};

// The trial's outcome once the vehicle is safe: the simulator's verdict, the mission's, the
// schedule's figures.
void fill_outcome(Vehicle& vehicle, const SchedulerStats& stats, double estimator_ms_sum,
                  const TrialRecorder& recorder, TrialResult& result) {
  const hal::mock::SimulatedWorld& world = vehicle.backends().sim->world();
  const VehicleLoop& loop = vehicle.loop();
  RechargeResult& charge = result.charge;
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
  const std::vector<double>& errors_mm = recorder.estimate_errors_mm();
  result.estimate_error_mm_median = errors_mm.empty() ? -1.0 : hal::percentile(errors_mm, 0.5);
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
  const auto max_ticks = static_cast<std::uint64_t>(
      options.max_time_s / std::chrono::duration<double>(vehicle.scheduler().period()).count());
  TrialRecorder recorder(config, conditions, options, vehicle, vehicle_options.seed, max_ticks,
                         result);
  double estimator_ms_sum = 0.0;
  std::vector<double> frame_cpu_ms;
  frame_cpu_ms.reserve(max_ticks + 1);
  const SchedulerStats& stats = vehicle.run(max_ticks, [&](const TickInfo&) {
    // CPU time, not the virtual clock's stage time (which does not advance while computing).
    estimator_ms_sum +=
        std::chrono::duration<double, std::milli>(loop.last_estimate().compute_time).count();
    frame_cpu_ms.push_back(ms(loop.last_compute_time()));
    recorder.drain();
  });
  vehicle.make_safe();
  recorder.drain();
  fill_outcome(vehicle, stats, estimator_ms_sum, recorder, result);
  if (!frame_cpu_ms.empty()) result.frame_cpu_ms_p95 = hal::percentile(frame_cpu_ms, 0.95);
  return result;
}

}  // namespace rovctl::app
