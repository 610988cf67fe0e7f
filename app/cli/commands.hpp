// The rovctl sub-commands. Each takes the words after its name and returns the exit code;
// usage and config problems are thrown as UsageError / ConfigError (exit 2).
#pragma once

#include <string>
#include <vector>

namespace rovctl::app {

using Words = std::vector<std::string>;

int command_estimate(const Words& words);     // one stereo pair -> marker pose
int command_bench(const Words& words);        // estimator throughput and convergence
int command_sim(const Words& words);          // closed-loop docking on the mock HAL
int command_run(const Words& words);          // the vehicle, on the backends the config names
int command_check(const Words& words);        // pre-flight checks
int command_thrusters(const Words& words);    // motor test
int command_record(const Words& words);       // save timestamped stereo pairs
int command_tune_marker(const Words& words);  // marker colours learnt from a recording
int command_study(const Words& words);        // the paper's GA-parameter study
int command_params(const Words& words);       // every declared parameter, as a markdown table
int command_view(const Words& words);         // the operator view replaying a finished run
int command_faults(const Words& words);       // the failsafe fault matrix on the mock HAL
int command_calibrate(const Words& words);    // stereo calibration from chessboard pairs

}  // namespace rovctl::app
