// Runs the fault matrix: per fault a config with the fault injected, its trials in parallel, and
// each trial scored from its failsafe log and its telemetry.
#include "app/tools/fault_matrix.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "app/tools/docking_trial.hpp"
#include "app/tools/json_writer.hpp"
#include "hal/mock/trial_generator.hpp"

namespace rovctl::app {
namespace {

struct Job {
  std::size_t row = 0;
  int trial = 0;
};

struct TrialScore {
  bool detected = false;
  bool logged = false;
  int ticks_to_safe = -1;
  bool recovered = false;
  bool docked = false;
  int stale_after_trip = 0;
  int landed_after_neutral = 0;
  std::string state_at_injection;
};

bool selected(const InjectedFault& f, const std::vector<std::string>& only) {
  if (only.empty()) return true;
  return std::any_of(only.begin(), only.end(),
                     [&](const std::string& n) { return n == f.name || n == f.cause; });
}

bool safe_command(const TelemetryRecord& r) {
  if ((r.flags & telemetry_flag::failsafe) == 0) return false;
  if ((r.flags & telemetry_flag::armed) == 0) return true;
  for (std::int32_t i = 0;
       i < r.thruster_count && i < static_cast<std::int32_t>(hal::kMaxThrusters); ++i) {
    if (r.thruster_cmd[static_cast<std::size_t>(i)] != 0.0) return false;
  }
  return true;
}

TrialScore score(const TrialResult& result, control::FailsafeCause cause, double at_s) {
  constexpr double kEps = 1e-6;
  TrialScore s;
  for (const FailsafeLogEntry& e : result.failsafe_log) {
    if (e.cause != cause || e.time_s < at_s - kEps) continue;
    if (e.kind == control::FailsafeEventKind::trip) s.detected = true;
    if (e.kind == control::FailsafeEventKind::recovered) s.recovered = true;
  }
  const std::string line = std::string("FAILSAFE ") + control::to_string(cause);
  s.logged = std::any_of(result.events.begin(), result.events.end(),
                         [&](const std::string& e) { return e.find(line) != std::string::npos; });
  const auto& recs = result.records;
  std::size_t first = 0;
  while (first < recs.size() && recs[first].time_s < at_s - kEps) ++first;
  if (first < recs.size()) {
    s.state_at_injection =
        control::to_string(static_cast<control::MissionState>(recs[first].mission_state));
  }
  std::size_t safe_at = recs.size();
  for (std::size_t i = first; i < recs.size(); ++i) {
    if (safe_command(recs[i])) {
      s.ticks_to_safe = static_cast<int>(i - first) + 1;
      safe_at = i;
      break;
    }
  }
  // From the first safe command on, while the failsafe holds: thrust only to back out.
  for (std::size_t i = safe_at; i < recs.size(); ++i) {
    const TelemetryRecord& r = recs[i];
    const bool backing_out =
        r.mission_state == static_cast<std::int32_t>(control::MissionState::undock);
    if ((r.flags & telemetry_flag::failsafe) != 0 && !backing_out && !safe_command(r)) {
      ++s.stale_after_trip;
    }
  }
  s.stale_after_trip += static_cast<int>(result.bus_stale_sent);
  s.landed_after_neutral = static_cast<int>(result.bus_landed_after_neutral);
  s.docked = trial_docked(result);
  return s;
}

}  // namespace

std::vector<FaultRow> run_fault_matrix(const AppConfig& config, const hal::StereoRig& rig,
                                       const FaultMatrixOptions& options) {
  for (const std::string& n : options.only) {
    bool known = false;
    for (const InjectedFault* f = injected_faults(); f->name != nullptr; ++f) {
      known = known || n == f->name || n == f->cause;
    }
    if (!known) {
      throw std::invalid_argument("unknown fault or cause '" + n +
                                  "' (faults: " + injected_fault_names_text() + ")");
    }
  }
  std::vector<FaultRow> rows;
  std::vector<AppConfig> configs;
  std::vector<const InjectedFault*> faults;
  std::vector<Job> jobs;
  for (const InjectedFault* f = injected_faults(); f->name != nullptr; ++f) {
    if (!selected(*f, options.only)) continue;
    FaultRow row;
    row.fault = f->name;
    row.cause = f->cause;
    row.transient = f->transient;
    row.at_s = options.at_s;
    row.trials = f->transient ? options.transient_trials : 1;
    AppConfig c = config;
    apply_injected_fault(*f, options.at_s, c);
    for (int t = 0; t < row.trials; ++t) jobs.push_back({rows.size(), t});
    rows.push_back(row);
    configs.push_back(std::move(c));
    faults.push_back(f);
  }

  std::vector<TrialScore> scores(jobs.size());
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::string failure;
  TrialOptions trial_options;
  trial_options.max_time_s = options.max_time_s;
  trial_options.keep_records = true;
  auto worker = [&]() {
    for (std::size_t j = next++; j < jobs.size(); j = next++) {
      try {
        const Job& job = jobs[j];
        const AppConfig& c = configs[job.row];
        const hal::mock::TrialGenerator generator(c.sim, c.vehicle, rig, c.marker);
        control::FailsafeCause cause = control::FailsafeCause::none;
        control::cause_from_key(faults[job.row]->cause, cause);
        const TrialResult result =
            run_docking_trial(c, rig, generator.make(job.trial, options.seed), trial_options);
        scores[j] = score(result, cause, options.at_s);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        failure = e.what();
        next = jobs.size();
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  const int threads = std::max(1, std::min(options.jobs, static_cast<int>(jobs.size())));
  for (int k = 0; k < threads; ++k) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (!failure.empty()) throw std::runtime_error(failure);

  for (std::size_t j = 0; j < jobs.size(); ++j) {
    FaultRow& row = rows[jobs[j].row];
    const TrialScore& s = scores[j];
    row.detected += s.detected ? 1 : 0;
    row.logged += s.logged ? 1 : 0;
    row.recovered += s.recovered ? 1 : 0;
    row.docked += s.docked ? 1 : 0;
    row.stale_after_trip_max = std::max(row.stale_after_trip_max, s.stale_after_trip);
    row.landed_after_neutral_max = std::max(row.landed_after_neutral_max, s.landed_after_neutral);
    if (!s.detected || s.ticks_to_safe < 0) {
      row.ticks_to_safe_max = std::max(row.ticks_to_safe_max, 1 << 20);
    } else {
      row.ticks_to_safe_max = std::max(row.ticks_to_safe_max, s.ticks_to_safe);
    }
    if (jobs[j].trial == 0) row.state_at_injection = s.state_at_injection;
  }
  return rows;
}

bool fault_matrix_passes(const std::vector<FaultRow>& rows, int max_ticks,
                         double min_docked_fraction) {
  return std::all_of(rows.begin(), rows.end(), [&](const FaultRow& r) {
    const bool safe = r.detected == r.trials && r.logged == r.trials && r.ticks_to_safe_max >= 1 &&
                      r.ticks_to_safe_max <= max_ticks && r.stale_after_trip_max == 0;
    const bool recovers =
        !r.transient || (r.recovered == r.trials && r.docked >= min_docked_fraction * r.trials);
    return safe && recovers;
  });
}

std::string fault_matrix_json(const std::vector<FaultRow>& rows) {
  JsonWriter j;
  j.begin_object().begin_array("faults");
  for (const FaultRow& r : rows) {
    j.begin_object()
        .field("fault", r.fault)
        .field("cause", r.cause)
        .field("transient", r.transient)
        .field("at_s", r.at_s)
        .field("state_at_injection", r.state_at_injection)
        .field("trials", r.trials)
        .field("detected", r.detected)
        .field("ticks_to_safe_max", r.ticks_to_safe_max)
        .field("logged", r.logged)
        .field("recovered", r.recovered)
        .field("docked", r.docked)
        .field("stale_after_trip_max", r.stale_after_trip_max)
        .field("landed_after_neutral_max", r.landed_after_neutral_max)
        .end_object();
  }
  j.end_array().end_object();
  return j.str();
}

std::string fault_matrix_text(const std::vector<FaultRow>& rows) {
  std::string out =
      "fault               cause               kind       trials detected ticks logged "
      "recovered docked stale landed  state at injection\n";
  char line[256];
  for (const FaultRow& r : rows) {
    std::snprintf(line, sizeof(line), "%-19s %-19s %-10s %6d %8d %5d %6d %9s %6d %5d %6d  %s\n",
                  r.fault.c_str(), r.cause.c_str(), r.transient ? "transient" : "latching",
                  r.trials, r.detected, r.ticks_to_safe_max, r.logged,
                  r.transient ? std::to_string(r.recovered).c_str() : "-", r.docked,
                  r.stale_after_trip_max, r.landed_after_neutral_max, r.state_at_injection.c_str());
    out += line;
  }
  return out;
}

}  // namespace rovctl::app
