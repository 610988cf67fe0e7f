// `rovctl sim`: closed-loop docking trials on the mock HAL — the real scheduler, estimator and
// controller against the simulated vehicle — with a summary, and CSV logs and plots with --out.
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/charge_fault.hpp"
#include "app/tools/docking_trial.hpp"
#include "app/tools/injected_fault.hpp"
#include "app/tools/output_folder.hpp"
#include "app/tools/sim_report.hpp"
#include "app/view/operator_view.hpp"
#include "hal/mock/render_scenario.hpp"
#include "hal/mock/sim_params.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {
constexpr double kRechargeMaxTimeS = 400.0;

struct TrialRange {
  int trials = 1;
  int first_trial = 0;
  std::uint64_t seed = 1;
};

// Flies `trials` trials from `first_trial` on `jobs` threads, each reported on stderr as it ends;
// false (said on stderr) when one threw.
bool fly_trials(const AppConfig& config, const hal::StereoRig& rig,
                const hal::mock::TrialGenerator& generator, const TrialOptions& options,
                const TrialRange& range, int jobs, bool json, std::vector<TrialResult>& results) {
  const int trials = range.trials, first_trial = range.first_trial;
  const std::uint64_t seed = range.seed;
  results.clear();
  results.resize(static_cast<std::size_t>(trials));
  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::mutex report_mutex;
  std::string failure;
  const bool tty = isatty(STDERR_FILENO) != 0;
  auto worker = [&]() {
    for (int i = next++; i < trials; i = next++) {
      try {
        results[static_cast<std::size_t>(i)] =
            run_docking_trial(config, rig, generator.make(first_trial + i, seed), options);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(report_mutex);
        failure = e.what();
        next = trials;
        return;
      }
      const int finished = ++done;
      std::lock_guard<std::mutex> lock(report_mutex);
      const TrialResult& r = results[static_cast<std::size_t>(i)];
      if (tty || !json) {
        std::cerr << (tty ? "\r" : "") << "trial " << first_trial + i << ": "
                  << (r.recharge        ? (trial_recharged(r) ? "docked, charged, departed"
                                                              : "recharge incomplete")
                      : trial_docked(r) ? "docked"
                      : r.docked        ? "docked off tolerance"
                                        : "not docked")
                  << " (" << r.final_state << ", " << r.sim_time_s << " s)  [" << finished << "/"
                  << trials << "]" << (tty ? "          " : "\n") << std::flush;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int j = 0; j < std::min(jobs, trials); ++j) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (tty) std::cerr << "\n";
  if (!failure.empty()) {
    std::cerr << "rovctl sim: " << failure << "\n";
    return false;
  }
  return true;
}

// The exposure scenario flies the cameras' auto exposure against the config's manual one
// (camera.v4l2.exposure_time_us), the same trials each; --exposure flies one of them.
struct ExposureArm {
  std::string label;  // "auto exposure (33 ms)", "exposure 4000 us"
  bool auto_exposure = true;
  int exposure_time_us = 0;
};

std::vector<ExposureArm> exposure_arms(const CliArgs& args, const AppConfig& config) {
  const drivers::V4l2CameraParams& cam = config.camera.v4l2;
  const ExposureArm auto_arm{
      "auto exposure (" +
          std::to_string(config.sim.scenarios.exposure.auto_exposure_ms).substr(0, 4) +
          " ms, unknown to the frames)",
      true, cam.exposure_time_us};
  auto manual = [](int us) {
    return ExposureArm{"exposure " + std::to_string(us) + " us", false, us};
  };
  if (args.has("--exposure")) {
    const std::string e = args.get("--exposure");
    if (e == "auto") return {auto_arm};
    const int frame_us = 1000000 / cam.fps;
    const long us = args.get_int("--exposure", 0, 100, frame_us);
    return {manual(static_cast<int>(us))};
  }
  if (config.sim.scenario != "exposure") {
    return {cam.auto_exposure ? auto_arm : manual(cam.exposure_time_us)};
  }
  return {auto_arm, manual(cam.exposure_time_us)};
}

}  // namespace

namespace {

// Each arm's summary, and one line per arm side by side: docked, and the estimator's ok ticks.
void print_exposure_arms(const std::vector<std::pair<ExposureArm, std::vector<TrialResult>>>& flown,
                         bool json) {
  std::string lines;
  if (json) std::cout << "{\"arms\": [";
  for (std::size_t i = 0; i < flown.size(); ++i) {
    const auto& [arm, results] = flown[i];
    const SimSummary s = summarise(results);
    if (json) {
      std::cout << (i == 0 ? "" : ", ")
                << "{\"auto_exposure\": " << (arm.auto_exposure ? "true" : "false")
                << ", \"exposure_time_us\": "
                << (arm.auto_exposure ? std::string("null") : std::to_string(arm.exposure_time_us))
                << ", \"summary\": " << summary_json(s) << "}";
    } else {
      std::cout << arm.label << ":\n" << summary_text(s, results) << "\n";
    }
    const double ok_pct = s.ticks == 0 ? 0.0 : 100.0 * static_cast<double>(s.ok_ticks) / s.ticks;
    lines += "  " + arm.label + ": docked " + std::to_string(s.docked) + " of " +
             std::to_string(s.trials) + ", ok estimates on " +
             std::to_string(ok_pct).substr(0, std::to_string(ok_pct).find('.') + 2) +
             " % of ticks, ok but wrong " + std::to_string(s.ok_wrong_ticks) + "\n";
  }
  if (json) {
    std::cout << "]}\n";
  } else {
    std::cout << "exposure arms, the same trials:\n" << lines;
  }
}

}  // namespace

int command_sim(const Words& words) {
  const CliArgs args = CliArgs::parse(
      "sim", words,
      {"--config", "--trials", "--seed", "--out", "--jobs", "--max-time", "--plots", "--scenario",
       "--mission", "--serve", "--token", "--serve-linger", "--charge-fault", "--first-trial",
       "--thruster-fault", "--fault", "--exposure"},
      {"--realtime", "--json", "--verbose", "--hold"});
  const std::string config_file =
      args.has("--config") ? args.get("--config") : default_config_path();
  const int trials = static_cast<int>(args.get_int("--trials", 1, 1, 100000));
  // Trials are drawn by index: --first-trial I --trials 1 flies trial I of a run again alone.
  const int first_trial = static_cast<int>(args.get_int("--first-trial", 0, 0, 100000));
  const auto seed = static_cast<std::uint64_t>(args.get_int("--seed", 1, 0, 1L << 40));
  // A live view shows the vehicle at its own pace: served trials run in real time, one by one.
  const bool serve = args.has("--serve");
  const bool realtime = args.has("--realtime") || serve;
  const bool json = args.has("--json");
  const std::string out_dir = args.get("--out");
  const int plots = static_cast<int>(args.get_int("--plots", 3, 0, 100000));
  TrialOptions options;
  options.realtime = realtime;
  options.max_time_s = args.get_double("--max-time", options.max_time_s, 1.0, 3600.0);
  options.keep_records = !out_dir.empty();
  options.log_events = args.has("--verbose");
  // Trials are independent: one per core in virtual time; real time paces one trial at a time
  // so the jitter figures are those of a single control loop.
  const int default_jobs =
      realtime ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int jobs = serve ? 1 : static_cast<int>(args.get_int("--jobs", default_jobs, 1, 64));
  const double linger_s = args.get_double("--serve-linger", 5.0, 0.0, 86400.0);
  if (!serve && (args.has("--token") || args.has("--hold") || args.has("--serve-linger"))) {
    throw UsageError("rovctl sim: --token, --hold and --serve-linger need --serve ADDR");
  }

  AppConfig config = load_app_config(config_file);
  if (args.has("--mission")) {
    const std::string mission = args.get("--mission");
    if (mission != "dock" && mission != "recharge") {
      throw UsageError("rovctl sim: --mission must be dock or recharge, got '" + mission + "'");
    }
    config.mission.kind = mission;
  }
  if (config.mission.kind == "recharge") {
    // The recharge trials dock into their own sea (current, tide, gusts) with the latch open, and
    // need the time to charge and back out as well as to dock.
    hal::mock::apply_recharge_sea(config.sim);
    if (!args.has("--max-time")) options.max_time_s = kRechargeMaxTimeS;
  }
  if (args.has("--charge-fault")) {
    const std::string name = args.get("--charge-fault");
    const ChargeFault* fault = find_charge_fault(name);
    if (fault == nullptr) {
      throw UsageError("rovctl sim: --charge-fault must be one of " + charge_fault_names_text() +
                       ", got '" + name + "'");
    }
    if (config.mission.kind != "recharge") {
      throw UsageError(
          "rovctl sim: --charge-fault needs the recharging mission (--mission recharge)");
    }
    apply_charge_fault(*fault, config, options);
  }
  if (args.has("--thruster-fault")) {
    // One thruster (drawn per trial) dead, weak or stuck at a random time in APPROACH.
    const std::string name = args.get("--thruster-fault");
    if (name != "dead" && name != "weak" && name != "stuck") {
      throw UsageError("rovctl sim: --thruster-fault must be dead, weak or stuck, got '" + name +
                       "'");
    }
    options.thruster_fault = name;
  }
  for (const std::string& spec : args.all("--fault")) {
    const InjectedFault* fault = nullptr;
    double at_s = 0.0;
    std::string error;
    if (!parse_fault_spec(spec, 0.0, fault, at_s, error)) {
      throw UsageError("rovctl sim: --fault: " + error);
    }
    apply_injected_fault(*fault, at_s, config);
  }
  if (args.has("--scenario")) {
    // Overrides sim.scenario, checked here so that a typo is a usage error before any trial.
    const std::string scenario = args.get("--scenario");
    hal::mock::Scenario unused;
    if (!hal::mock::scenario_from_name(scenario, unused)) {
      throw UsageError("rovctl sim: --scenario must be one of " + hal::mock::scenario_names_text() +
                       ", got '" + scenario + "'");
    }
    config.sim.scenario = scenario;
  }
  if (serve) {
    config.operator_view.listen = args.get("--serve");
    if (args.has("--token")) config.operator_view.token = args.get("--token");
    ListenAddress address;
    std::string error;
    if (!parse_listen_address(config.operator_view.listen, address, error)) {
      throw UsageError("rovctl sim: --serve: " + error);
    }
  }
  const hal::StereoRig rig = load_rig(config);
  for (const std::string& w : config.warnings) std::cerr << "rovctl sim: warning: " << w << "\n";
  // Before any trial runs: a sweep must not find at its end that it cannot write its logs.
  if (!out_dir.empty()) prepare_output_folder("sim", out_dir);
  const hal::mock::TrialGenerator generator(config.sim, config.vehicle, rig, config.marker);

  std::unique_ptr<OperatorLink> link;
  std::unique_ptr<OperatorView> view;
  if (serve) {
    link = std::make_unique<OperatorLink>(
        rig, std::chrono::duration_cast<std::chrono::nanoseconds>(
                 std::chrono::duration<double>(1.0 / config.operator_view.frame_rate_hz)));
    view = std::make_unique<OperatorView>(config.operator_view, rig, config.marker, *link);
    std::string error;
    if (!view->start(error)) throw UsageError("rovctl sim: " + error);
    std::cerr << "rovctl sim: operator view at " << view->url()
              << (config.operator_view.token.empty() ? " (read-only: no --token)" : "") << "\n";
    std::cerr << "rovctl sim: " << view->exposure() << "\n";
    options.operator_link = link.get();
    options.operator_hold_at_start = args.has("--hold");
  }

  const std::vector<ExposureArm> arms = exposure_arms(args, config);
  if (arms.size() > 1 && (!out_dir.empty() || serve)) {
    throw UsageError(
        "rovctl sim: --scenario exposure flies two arms (auto and manual exposure); give "
        "--exposure auto or --exposure MICROSECONDS to fly one with --out or --serve");
  }
  std::vector<std::pair<ExposureArm, std::vector<TrialResult>>> flown;
  for (const ExposureArm& arm : arms) {
    AppConfig arm_config = config;
    arm_config.camera.v4l2.auto_exposure = arm.auto_exposure;
    arm_config.camera.v4l2.exposure_time_us = arm.exposure_time_us;
    if (arms.size() > 1 && (isatty(STDERR_FILENO) != 0 || !json)) {
      std::cerr << arm.label << ":\n";
    }
    std::vector<TrialResult> results;
    if (!fly_trials(arm_config, rig, generator, options, {trials, first_trial, seed}, jobs, json,
                    results)) {
      return kExitRuntimeFailure;
    }
    flown.emplace_back(arm, std::move(results));
  }

  if (view) {
    // The page keeps the final state for a while, so a watcher sees how the run ended.
    std::this_thread::sleep_for(std::chrono::duration<double>(linger_s));
    view->stop();
  }

  if (flown.size() == 1) {
    const std::vector<TrialResult>& results = flown.front().second;
    const SimSummary summary = summarise(results);
    if (!out_dir.empty()) write_sim_outputs(out_dir, results, summary, plots);
    if (json) {
      std::cout << summary_json(summary) << "\n";
    } else {
      std::cout << summary_text(summary, results);
      if (!out_dir.empty()) std::cout << "logs and plots in " << out_dir << "/\n";
    }
    return kExitOk;
  }
  print_exposure_arms(flown, json);
  return kExitOk;
}

}  // namespace rovctl::app
