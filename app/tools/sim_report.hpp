// What `rovctl sim` reports over its trials: the summary figures (JSON and text), the per-trial
// table, each trial's tick-by-tick CSV and the PNG plots a person reviews after a run.
#pragma once

#include <string>
#include <vector>

#include "app/tools/docking_trial.hpp"

namespace rovctl::app {

// A probe that touches the station further than this off the socket axis hits the rim: the
// estimate it was driven on was wrong, whatever the mission says next.
inline constexpr double kTouchOffCentreMm = 20.0;

struct SimSummary {
  int trials = 0;
  int docked = 0;    // trial_docked(): captured within tolerances and the mission said DOCKED
  int captured = 0;  // captured by the socket at all
  // Trials whose probe touched the station more than kTouchOffCentreMm off the socket axis, and
  // the largest such lateral error over all trials (-1: no trial touched).
  int touched_off_centre = 0;
  double touch_lateral_mm_max = -1.0;
  double success_rate = 0.0;
  double time_to_dock_s_median = -1.0;
  double final_lateral_error_mm_p95 = -1.0;
  double final_yaw_error_deg_p95 = -1.0;
  std::uint64_t ticks = 0;  // over all trials
  std::uint64_t overruns = 0;
  double tick_jitter_ms_p99 = 0.0;  // worst trial's p99
  double tick_jitter_ms_max = 0.0;  // worst tick of any trial
  double estimator_ms_mean = 0.0;
  double estimate_error_mm_median = -1.0;
  // Over all trials: ticks with an ok estimate, those ok but wrong against their own image's truth
  // (TrialResult::ok_wrong_ticks), the trials with any, and the worst ok tick's errors.
  std::uint64_t ok_ticks = 0;
  std::uint64_t ok_wrong_ticks = 0;
  std::uint64_t ok_over_bound_ticks = 0;  // ok ticks off by more than their own error bound
  int trials_ok_wrong = 0;
  double ok_error_mm_max = 0.0, ok_error_deg_max = 0.0;
  std::uint64_t ok_carried_ticks = 0;  // ok ticks the tracker carried (TrialResult)
  // The trials' p95 of the frame's processor time (TrialResult::frame_cpu_ms_p95): median, worst.
  double frame_cpu_ms_p95_median = 0.0, frame_cpu_ms_p95_max = 0.0;
  // The recharging mission (mission.kind recharge); absent from the reports otherwise.
  bool recharge = false;
  int recharged = 0;  // trial_recharged(): docked, charged and departed clear, marker in view
  double recharge_rate = 0.0;
  int charged = 0;
  int departed = 0;
  int undock_clear = 0;                // departed with the marker in view
  double contact_fraction_min = -1.0;  // over trials that reached CHARGING
  double contact_fraction_median = -1.0;
  double unseated_unnoticed_max_s = 0.0;  // worst trial
  int reseats = 0;                        // over all trials
  double seated_h_median = -1.0;          // battery time seated while charging
  double hold_wh_median = -1.0;
  double charged_wh_median = -1.0;
  double hold_fraction_median = -1.0;
  double hold_fraction_max = -1.0;
  double undock_clearance_m_min = -1.0;
};

SimSummary summarise(const std::vector<TrialResult>& results);
std::string summary_json(const SimSummary& s);
std::string summary_text(const SimSummary& s, const std::vector<TrialResult>& results);

// trials.csv (one row per trial), trial_NNN.csv (every tick) and trial_NNN.png (plots) into
// `dir`, each written to a temporary name and renamed. Plots for the first `plot_trials` trials and
// for every trial that did not dock within tolerance.
void write_sim_outputs(const std::string& dir, const std::vector<TrialResult>& results,
                       const SimSummary& summary, int plot_trials);

// The plots of one trial: estimate vs truth, pose error, fitness, thrusters, mission state.
void plot_trial(const TrialResult& trial, const std::string& png_path);

}  // namespace rovctl::app
