// `rovctl faults`: the fault matrix — every injectable fault flown once mid-approach on the mock
// HAL (transient ones --trials times), one row per fault; exit 1 when a row misses the acceptance.
#include <algorithm>
#include <iostream>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/fault_matrix.hpp"

namespace rovctl::app {
namespace {
// The acceptance: safe within 2 ticks of the injection; transient faults dock in 90 % of trials.
constexpr int kMaxTicksToSafe = 2;
constexpr double kMinDockedFraction = 0.9;
}  // namespace

int command_faults(const Words& words) {
  const CliArgs args = CliArgs::parse(
      "faults", words, {"--config", "--trials", "--seed", "--jobs", "--at", "--only", "--max-time"},
      {"--json"});
  const std::string config_file =
      args.has("--config") ? args.get("--config") : default_config_path();
  FaultMatrixOptions options;
  options.transient_trials = static_cast<int>(args.get_int("--trials", 1, 1, 10000));
  options.seed = static_cast<std::uint64_t>(args.get_int("--seed", 1, 0, 1L << 40));
  options.at_s = args.get_double("--at", options.at_s, 0.1, 3600.0);
  options.max_time_s = args.get_double("--max-time", options.max_time_s, 1.0, 3600.0);
  options.jobs = static_cast<int>(args.get_int(
      "--jobs", static_cast<long>(std::max(1u, std::thread::hardware_concurrency())), 1, 64));
  options.only = args.get_list("--only");

  const AppConfig config = load_app_config(config_file);
  const hal::StereoRig rig = load_rig(config);
  std::vector<FaultRow> rows;
  try {
    rows = run_fault_matrix(config, rig, options);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("rovctl faults: --only: ") + e.what());
  }
  std::cout << (args.has("--json") ? fault_matrix_json(rows) + "\n" : fault_matrix_text(rows));
  return fault_matrix_passes(rows, kMaxTicksToSafe, kMinDockedFraction) ? kExitOk
                                                                        : kExitRuntimeFailure;
}

}  // namespace rovctl::app
