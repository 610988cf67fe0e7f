// rovctl entry point: dispatches sub-commands and maps errors to the exit codes (0 ok, 1 run-time
// failure, 2 usage/config).
#include <cstring>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "app/cli/commands.hpp"
#include "app/runtime/errors.hpp"

namespace {

constexpr const char* kUsage = R"(usage: rovctl <command> [options]

commands:
  sim        [--config FILE] [--trials N] [--seed S] [--realtime] [--json] [--out DIR]
             [--mission dock|recharge] [--scenario NAME] [--jobs N] [--max-time S]
             [--first-trial I] [--charge-fault FAULT] [--fault NAME[@T_S]]...
             [--thruster-fault dead|weak|stuck] [--exposure auto|US]
             closed-loop docking (or dock, charge, undock: --mission recharge) on the mock
             HAL; NAME: clear, turbid, side_light, bubbles, occluders, noisy, exposure
             (exposure: auto exposure against camera.v4l2.exposure_time_us, or --exposure);
             FAULT (recharge, injected mid-charge): none, knock, knocks, surge, charger,
             operator, camera; --fault (repeatable) injects NAME at T_S (default 0):
             camera_lost, camera_drop, frozen_frames, stale_frames, stamp_skew,
             camera_black, bus_timeout, bus_slow, disarm_unacked, sensor_lost,
             sensor_nan, sensor_implausible, tilt, cpu_stall, mission_time, search_time
  faults     [--config FILE] [--json] [--trials N] [--only A,B] [--at T_S] [--jobs N]
             the fault matrix: each fault above injected mid-approach (transient
             ones N times): detected, ticks to safe, logged, recovered, docked
  sim        --serve HOST:PORT [--token T] [--hold] [--serve-linger S] ...
             the same, in real time, with the live operator view in a browser
  view       --out DIR [--listen HOST:PORT] [--trial N] [--speed X]
             the operator view replaying a finished `rovctl sim --out DIR` run
  estimate   --config FILE --left L.png --right R.png [--frames N] [--seed S] [--json]
             marker pose in the left camera frame from one stereo pair
  bench      [--config FILE] [--json]     estimator throughput and convergence
  bench      --set DIR [--frames N] [--seed S] [--range-bands-m 0.5,1.0,1.3] [--json] [--verbose]
             [--by FIELD --by-edges E1,E2,...]
             the estimator on a validation set (DIR/manifest.json), per condition,
             per band of the marker's true range, and per band of a manifest number
  bench      --sequence DIR [--frames N] [--seed S] [--json] [--verbose]
             rendered sequences (DIR/sequences.json, or one sequence folder) frame by frame:
             the still estimator beside it with the pose tracker (right / ok-but-wrong / not ok)
  study      [--config FILE] [--quick] [--seeds N] [--out DIR] [--json]
             the paper's GA-parameter study on this machine
  run        --config FILE                the vehicle, with the backends the config names
  check      --config FILE                pre-flight checks
  thrusters  --config FILE --test [--yes] motor test, one thruster at a time
  thrusters  --config FILE --safe [--timeout-ms N] neutral + disarm, exit 0 once acknowledged
  record     --config FILE --out DIR [--frames N]  save timestamped stereo pairs
  calibrate  --pairs DIR --board chessboard:COLSxROWS:SQUARE_MM --out FILE [--json] [--force]
             stereo calibration from a recording of a chessboard (COLSxROWS inner corners)
  tune-marker --config FILE --pairs DIR --out FILE [--range-m NEAR,FAR] [--images DIR] [--json] [--force]
             the marker's hue windows and floors measured in a recording (DIR as
             `record` writes it), as a `marker:` config fragment, with figures
  params     [--config FILE]              every config parameter: unit, range, default, meaning

exit codes: 0 success, 1 runtime failure, 2 usage or config error
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace rovctl::app;
  if (argc < 2 || std::strcmp(argv[1], "help") == 0 || std::strcmp(argv[1], "--help") == 0 ||
      std::strcmp(argv[1], "-h") == 0) {
    std::cout << kUsage;
    return argc < 2 ? kExitUsage : kExitOk;
  }
  if (std::strcmp(argv[1], "--version") == 0) {
    std::cout << "rovctl " << ROVCTL_VERSION << "\n";
    return kExitOk;
  }
  const std::string command = argv[1];
  const Words words(argv + 2, argv + argc);
  try {
    if (command == "estimate") return command_estimate(words);
    if (command == "bench") return command_bench(words);
    if (command == "sim") return command_sim(words);
    if (command == "run") return command_run(words);
    if (command == "check") return command_check(words);
    if (command == "thrusters") return command_thrusters(words);
    if (command == "record") return command_record(words);
    if (command == "tune-marker") return command_tune_marker(words);
    if (command == "study") return command_study(words);
    if (command == "params") return command_params(words);
    if (command == "view") return command_view(words);
    if (command == "faults") return command_faults(words);
    if (command == "calibrate") return command_calibrate(words);
    std::cerr << "rovctl: unknown command '" << command << "'\n" << kUsage;
    return kExitUsage;
  } catch (const UsageError& e) {
    std::cerr << e.what() << "\n";
    return kExitUsage;
  } catch (const ConfigError& e) {
    std::cerr << "rovctl " << command << ": " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::invalid_argument& e) {
    // A part's constructor rejecting its parameters at start-up (docs/architecture.md, "Errors").
    std::cerr << "rovctl " << command << ": " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "rovctl " << command << ": error: " << e.what() << "\n";
    return kExitRuntimeFailure;
  }
}
