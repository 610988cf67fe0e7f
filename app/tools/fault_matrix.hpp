// The fault matrix (`rovctl faults`): each injected fault flown in the closed loop on the mock HAL
// mid-approach, one row per fault — detected as its cause?, ticks from injection to a safe
// command, logged?, recovered (transient faults)?, docked?
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/runtime/app_config.hpp"
#include "app/tools/injected_fault.hpp"
#include "hal/model/stereo_rig.hpp"

namespace rovctl::app {

struct FaultMatrixOptions {
  double at_s = 8.0;         // injection time: the default trials are in APPROACH by then
  int transient_trials = 1;  // trials per transient fault (hardware faults: one)
  std::uint64_t seed = 1;
  int jobs = 1;
  double max_time_s = 120.0;
  std::vector<std::string> only;  // fault names or cause keys; empty: all
};

struct FaultRow {
  std::string fault;
  std::string cause;
  bool transient = false;
  double at_s = 0.0;
  int trials = 0;
  int detected = 0;            // tripped with the expected cause, at or after the injection
  int logged = 0;              // the FAILSAFE line names the cause
  int ticks_to_safe_max = -1;  // over the trials: ticks from injection to a safe command
  int recovered = 0;           // a recovery logged (transient faults)
  int docked = 0;              // trial_docked
  // Over the trials, after the first safe command while the failsafe holds (not backing out):
  // non-zero commands written, plus those the mock bus sent after a later neutral (stale).
  int stale_after_trip_max = 0;
  // Over the trials: non-zero requests already in flight that landed after a neutral was
  // written (a slow peer cannot take back what it was sent).
  int landed_after_neutral_max = 0;
  std::string state_at_injection;  // of the first trial
};

// Throws std::invalid_argument for a name in `only` that is neither a fault nor a cause.
std::vector<FaultRow> run_fault_matrix(const AppConfig& config, const hal::StereoRig& rig,
                                       const FaultMatrixOptions& options);

// Every row meets the acceptance: detected, logged and safe within max_ticks in every trial, no
// stale command after the trip; transient faults recovered and docked in at least
// min_docked_fraction of their trials.
bool fault_matrix_passes(const std::vector<FaultRow>& rows, int max_ticks,
                         double min_docked_fraction);

std::string fault_matrix_json(const std::vector<FaultRow>& rows);
std::string fault_matrix_text(const std::vector<FaultRow>& rows);

}  // namespace rovctl::app
