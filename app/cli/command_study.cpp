// `rovctl study`: the paper's GA-parameter study on this machine (Fig. 8, Table 1, Fig. 9,
// Table 2) for the faithful and the improved estimator, with progress on stderr.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "app/cli/cli_args.hpp"
#include "app/cli/commands.hpp"
#include "app/runtime/app_config.hpp"
#include "app/runtime/errors.hpp"
#include "app/runtime/vehicle_backends.hpp"
#include "app/tools/output_folder.hpp"
#include "app/tools/study.hpp"
#include "app/tools/study_report.hpp"

namespace rovctl::app {
namespace {

constexpr const char* kUsage =
    "usage: rovctl study [--config FILE] [--quick] [--full] [--seeds N] [--out DIR] [--limit-s S] "
    "[--only VARIANT,...] [--setting P/S/M,...] [--json]";

// One updating line on a terminal; elsewhere (a log, CI) a line per phase and every 10 %.
class ProgressPrinter {
 public:
  ProgressPrinter(std::ostream& err, bool terminal) : err_(err), terminal_(terminal) {}
  ~ProgressPrinter() { finish(); }

  void operator()(const std::string& phase, long done, long total) {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const int percent = total > 0 ? static_cast<int>(100 * done / total) : 100;
    char line[256];
    std::snprintf(line, sizeof line, "study: %s %ld/%ld (%d %%), %.0f s elapsed", phase.c_str(),
                  done, total, percent, elapsed);
    if (terminal_) {
      if (now - last_ < std::chrono::milliseconds(150) && done < total && phase == phase_) return;
      last_ = now;
      const std::string text = line;
      err_ << "\r" << text << std::string(width_ > text.size() ? width_ - text.size() : 0, ' ')
           << std::flush;
      width_ = text.size();
      dirty_ = true;
    } else if (phase != phase_ || percent / 10 > decile_) {
      decile_ = percent / 10;
      err_ << line << "\n" << std::flush;
    }
    if (phase != phase_) {
      phase_ = phase;
      decile_ = percent / 10;
    }
  }

  void finish() {
    if (terminal_ && dirty_) err_ << "\n" << std::flush;
    dirty_ = false;
  }

 private:
  std::ostream& err_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_{};
  std::string phase_;
  int decile_ = -1;
  std::size_t width_ = 0;
  bool dirty_ = false;
};

}  // namespace

int run_study_command(const std::vector<std::string>& words, std::ostream& out, std::ostream& err) {
  const CliArgs args = CliArgs::parse(
      "study", words, {"--config", "--seeds", "--out", "--limit-s", "--only", "--setting"},
      {"--quick", "--full", "--json"});
  const bool quick = args.has("--quick");
  const std::string config_path =
      args.has("--config") ? args.get("--config") : default_config_path();
  const AppConfig config = load_app_config(config_path);
  const hal::StereoRig rig = load_rig(config);

  StudySettings settings = quick ? StudySettings::quick_subset(rig) : StudySettings::full(rig);
  settings.seeds = static_cast<int>(args.get_int("--seeds", settings.seeds, 1, 10000));
  // --full: the variants at this machine's budget on every seed too (about 17 min CPU more).
  settings.full_seeds = args.has("--full");
  settings.time_limit_s =
      args.get_double("--limit-s", settings.time_limit_s, settings.frame_period_s, 600.0);
  settings.threads = static_cast<int>(
      std::clamp(std::thread::hardware_concurrency(), 1u, 2u));  // the project's two cores
  std::vector<GaCombination> wanted_settings;
  if (args.has("--only")) {
    for (const std::string& name : args.get_list("--only")) {
      const bool known = std::any_of(settings.variants.begin(), settings.variants.end(),
                                     [&name](const StudyVariant& v) { return v.name == name; });
      if (!known) {
        std::string names;
        for (const StudyVariant& v : settings.variants) names += " " + v.name;
        throw UsageError("rovctl study --only: no variant '" + name + "' (variants:" + names + ")");
      }
      settings.only.push_back(name);
    }
  }
  if (args.has("--setting")) {
    // population/selection/mutation, as the report names them; each must be one of the study's.
    for (const std::string& item : args.get_list("--setting")) {
      GaCombination c;
      char slash1 = 0, slash2 = 0;
      std::istringstream in(item);
      in >> c.population >> slash1 >> c.selection_rate >> slash2 >> c.mutation_rate;
      settings.only_settings = {c};
      const bool known =
          in && slash1 == '/' && slash2 == '/' && !StudySettings(settings).settings_run().empty();
      settings.only_settings.clear();
      if (!known) {
        throw UsageError("rovctl study --setting: '" + item +
                         "' is not population/selection/mutation of a setting of this study");
      }
      wanted_settings.push_back(c);
    }
    settings.only_settings = wanted_settings;
  }
  const std::string out_dir = args.get("--out", "study-out");
  if (out_dir.empty())
    throw UsageError("rovctl study: --out needs a directory (" + std::string(kUsage) + ")");
  prepare_output_folder("study", out_dir);  // before hours of work, not after

  std::string command_line = "rovctl study";
  for (const std::string& w : words) command_line += " " + w;

  ProgressPrinter printer(err, &err == &std::cerr && ::isatty(STDERR_FILENO) == 1);
  const StudyResult result = run_study(
      rig, config.marker, config.estimator, config.sim.camera.render, settings,
      [&printer](const std::string& phase, long done, long total) { printer(phase, done, total); });
  printer.finish();
  const StudyFiles files = write_study_outputs(out_dir, result, command_line);
  if (args.has("--json")) {
    out << study_json(result, files) << "\n";
  } else {
    out << study_text(result, files);
  }
  return kExitOk;
}

int command_study(const Words& words) { return run_study_command(words, std::cout, std::cerr); }

}  // namespace rovctl::app
