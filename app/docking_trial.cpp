// The trial runner: builds the mock HAL for the trial, arms, runs the cyclic scheduler over the
// VehicleLoop, and reads the outcome from the simulator's truth (never shown to the loop).
#include "app/docking_trial.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "app/cyclic_scheduler.hpp"
#include "app/vehicle_loop.hpp"
#include "hal/mock/simulated_hal.hpp"

namespace rovctl::app {
namespace {

double ms(std::chrono::nanoseconds d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return -1.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

TrialResult run_docking_trial(const AppConfig& config, const hal::StereoRig& rig,
                              const hal::mock::TrialConditions& conditions,
                              const TrialOptions& options) {
  TrialResult result;
  result.conditions = conditions;

  hal::mock::SimParams sim = hal::mock::params_for_trial(config.sim, conditions);
  sim.realtime = options.realtime;
  auto hal = std::make_unique<hal::mock::SimulatedHal>(sim, config.vehicle, config.station, rig,
                                                       config.marker, conditions);
  std::string error;
  if (!hal->camera().open(error) || !hal->bus().open(error)) {
    throw std::runtime_error("mock HAL: " + error);
  }
  auto scheduler = std::make_unique<CyclicScheduler>(hal->clock(), config.scheduler);
  TelemetryRing ring(static_cast<std::size_t>(std::max(config.telemetry.ring_capacity, 64)));
  VehicleLoop loop(config, rig, hal->camera(), hal->bus(), &hal->sensors(), *scheduler, &ring,
                   conditions.seed * 7919u + static_cast<std::uint64_t>(conditions.index));
  hal::mock::SimulatedWorld& world = hal->world();
  loop.set_truth([&world](Eigen::Isometry3d& T) {
    T = world.truth().T_cl_marker;
    return true;
  });
  if (!loop.arm(error)) throw std::runtime_error(error);

  const auto max_ticks = static_cast<std::uint64_t>(
      options.max_time_s / std::chrono::duration<double>(scheduler->period()).count());
  if (options.keep_records) result.records.reserve(max_ticks + 1);
  std::vector<double> estimate_errors_mm;
  estimate_errors_mm.reserve(max_ticks + 1);
  double estimator_ms_sum = 0.0;
  bool captured = false;

  // Logging and bookkeeping after each tick: this is the simulation's non-real-time side.
  auto drain = [&]() {
    LoopEvent e;
    while (loop.pop_event(e)) {
      result.events.push_back(format_event(e));
      if (options.log_events)
        std::cerr << "trial " << conditions.index << ": " << result.events.back() << "\n";
    }
    TelemetryRecord r;
    while (ring.try_pop(r)) {
      if ((r.flags & telemetry_flag::recognised) && (r.flags & telemetry_flag::truth_valid)) {
        estimate_errors_mm.push_back(r.est_error_m * 1000.0);
      }
      if (options.keep_records) result.records.push_back(r);
    }
    const auto& d = world.docking();
    if (d.docked && !captured) {
      captured = true;
      result.time_to_dock_s = std::chrono::duration<double>(d.docked_at).count();
      result.lateral_error_mm = d.lateral_error_m * 1000.0;
      result.yaw_error_deg = d.yaw_error_rad * 180.0 / M_PI;
    }
  };

  const SchedulerStats& stats = scheduler->run(
      [&](const TickInfo& info) {
        const bool more = loop.tick(info);
        // CPU time, not the virtual clock's stage time (which does not advance while computing).
        estimator_ms_sum +=
            std::chrono::duration<double, std::milli>(loop.last_estimate().compute_time).count();
        drain();
        return more;
      },
      max_ticks);
  loop.disarm();
  drain();

  result.docked = world.docking().docked;
  result.mission_docked = loop.mission().state() == control::MissionState::docked;
  result.success = result.docked && result.lateral_error_mm <= kSuccessLateralMm &&
                   std::abs(result.yaw_error_deg) <= kSuccessYawDeg;
  result.sim_time_s = std::chrono::duration<double>(world.time()).count();
  result.final_state = control::to_string(loop.mission().state());
  result.aborts = loop.mission().aborts();
  if (loop.failsafe().tripped()) result.failsafe = control::to_string(loop.failsafe().cause());
  result.ticks = stats.ticks;
  result.overruns = stats.skipped_releases;
  result.jitter_p99_ms = ms(stats.jitter.percentile(0.99));
  result.jitter_max_ms = ms(stats.jitter.max());
  result.estimator_ms_mean =
      stats.ticks > 0 ? estimator_ms_sum / static_cast<double>(stats.ticks) : 0.0;
  result.recognised_fraction = stats.ticks > 0 ? static_cast<double>(loop.recognised_ticks()) /
                                                     static_cast<double>(stats.ticks)
                                               : 0.0;
  result.estimate_error_mm_median = median(estimate_errors_mm);
  return result;
}

}  // namespace rovctl::app
