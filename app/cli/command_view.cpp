// `rovctl view --out DIR`: the live operator page, fed by a finished run's telemetry instead of
// the tick — the same page, plots and banners, at the recorded pace — until SIGINT/SIGTERM.
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/operator_link.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/telemetry_csv_reader.hpp"
#include "app/view/operator_view.hpp"

namespace rovctl::app {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_view_stop(int) { g_stop = true; }

}  // namespace

int command_view(const Words& words) {
  const CliArgs args = CliArgs::parse(
      "view", words, {"--out", "--config", "--listen", "--trial", "--speed", "--linger"}, {});
  if (!args.has("--out")) throw UsageError("rovctl view: --out DIR (a `rovctl sim --out` folder)");
  namespace fs = std::filesystem;
  const fs::path dir = args.get("--out");
  std::vector<fs::path> files;
  if (args.has("--trial")) {
    char name[32];
    std::snprintf(name, sizeof(name), "trial_%03ld.csv", args.get_int("--trial", 0, 0, 99999));
    files.push_back(dir / name);
    if (!fs::is_regular_file(files.back())) {
      throw UsageError("rovctl view: " + files.back().string() + " does not exist");
    }
  } else {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("trial_", 0) == 0 && entry.path().extension() == ".csv") {
        files.push_back(entry.path());
      }
    }
    if (ec) throw UsageError("rovctl view: cannot read " + dir.string() + ": " + ec.message());
    std::sort(files.begin(), files.end());
    if (files.empty()) {
      throw UsageError("rovctl view: no trial_NNN.csv in " + dir.string() +
                       " (write them with `rovctl sim --out DIR`)");
    }
  }
  const double speed = args.get_double("--speed", 1.0, 0.01, 1000.0);
  // 0: until SIGINT/SIGTERM; otherwise stop that many seconds after the replay ends.
  const double linger_s = args.get_double("--linger", 0.0, 0.0, 86400.0);
  std::vector<std::vector<TelemetryRecord>> runs;
  for (const fs::path& f : files) {
    try {
      runs.push_back(read_telemetry_csv(f.string()));
    } catch (const std::runtime_error& e) {
      throw ConfigError(e.what());
    }
  }

  AppConfig config =
      load_app_config(args.has("--config") ? args.get("--config") : default_config_path());
  config.operator_view.listen = args.get("--listen", "127.0.0.1:8080");
  config.operator_view.token.clear();  // a replay takes no commands
  const hal::StereoRig rig = load_rig(config);
  OperatorLink link(rig, std::chrono::seconds(1));
  OperatorViewOptions options;
  options.source = "replay";
  options.images = false;
  OperatorView view(config.operator_view, rig, config.marker, link, options);
  std::string error;
  if (!view.start(error)) throw UsageError("rovctl view: " + error);
  std::cerr << "rovctl view: replaying " << files.size() << " trial(s) from " << dir.string()
            << " at " << view.url() << " (Ctrl-C ends)\n";
  std::cerr << "rovctl view: " << view.exposure() << "\n";
  std::signal(SIGINT, on_view_stop);
  std::signal(SIGTERM, on_view_stop);

  // Each record at its recorded time (scaled by --speed), trial after trial.
  for (std::size_t k = 0; k < runs.size() && !g_stop; ++k) {
    std::cerr << "rovctl view: " << files[k].filename().string() << "\n";
    const auto start = std::chrono::steady_clock::now();
    const double t0 = runs[k].empty() ? 0.0 : runs[k].front().time_s;
    for (const TelemetryRecord& r : runs[k]) {
      if (g_stop) break;
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>((r.time_s - t0) / speed)));
      link.publish(r, nullptr, std::chrono::nanoseconds(0));
    }
  }
  const auto ended = std::chrono::steady_clock::now();
  while (!g_stop && (linger_s == 0.0 || std::chrono::steady_clock::now() - ended <
                                            std::chrono::duration<double>(linger_s))) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  view.stop();
  return kExitOk;
}

}  // namespace rovctl::app
