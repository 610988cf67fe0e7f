// The fixed-period cyclic executive: absolute deadlines start + k * period on a hal::Clock (real
// clock_nanosleep on the vehicle, virtual in simulation and tests), per-stage timing and jitter
// statistics, all without allocation once constructed.
//
// Overrun policy: a tick that ends after the next release makes the scheduler skip every release
// it missed (counted) and wait for the first future release on the original grid. It never runs
// ticks back to back to catch up, so the control loop's period and phase stay fixed.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "app/runtime/latency_stats.hpp"
#include "app/runtime/realtime_setup.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

// The stages of one tick (docs/architecture.md, "One tick"), timed separately.
enum class Stage : std::uint8_t { capture, segment, estimate, control, actuate, telemetry };
constexpr std::size_t kStageCount = 6;
// "capture", "segment", ... (config keys and CSV column names).
std::string_view stage_name(Stage stage) noexcept;

struct SchedulerParams {
  double period_ms = 33.0;
  // Wake this long before each release and busy-wait the rest on the clock: for kernels without
  // full preemption (PREEMPT_NONE), where a timer wake-up can wait milliseconds behind another
  // task's kernel work. Costs that much CPU per period; 0 (default) sleeps to the deadline.
  double spin_margin_ms = 0.0;
  RealtimeParams realtime;
  // Per-stage time budget; a stage taking longer is counted (never logged from the tick).
  // 0 disables the check for that stage.
  std::array<double, kStageCount> stage_budget_ms{4.0, 4.0, 20.0, 1.0, 2.0, 1.0};

  std::chrono::nanoseconds period() const;
  std::chrono::nanoseconds spin_margin() const;
  std::chrono::nanoseconds stage_budget(Stage stage) const;
};

void describe(hal::ParamVisitor& v, SchedulerParams& p);

// What a tick is told about its release.
struct TickInfo {
  std::uint64_t index = 0;               // ticks run before this one in this run()
  std::uint64_t release = 0;             // k: deadline = start + k * period
  std::chrono::nanoseconds start{0};     // the grid's origin (clock time at run())
  std::chrono::nanoseconds deadline{0};  // absolute release time on the clock
  std::chrono::nanoseconds wakeup{0};    // when the scheduler actually woke for it
  std::chrono::nanoseconds period{0};
  std::uint64_t skipped_before = 0;  // releases skipped right before this one (an overrun)
  std::uint64_t skipped_total = 0;   // releases skipped so far in this run()

  std::chrono::nanoseconds jitter() const { return wakeup - deadline; }
  // Release time since start, in seconds (the telemetry's time axis).
  double time_s() const { return std::chrono::duration<double>(deadline - start).count(); }
};

struct StageStats {
  LatencyStats time;
  std::uint64_t over_budget = 0;  // ticks in which this stage exceeded its budget
};

struct SchedulerStats {
  std::uint64_t ticks = 0;             // ticks run
  std::uint64_t overrun_ticks = 0;     // ticks that ended after the next release
  std::uint64_t skipped_releases = 0;  // releases not run because of those overruns
  LatencyStats jitter;                 // wake-up minus deadline
  LatencyStats execution;              // wake-up to end of tick
  std::array<StageStats, kStageCount> stages;
};

// Human-readable summary (allocates; call it after the run).
std::string format_scheduler_report(const SchedulerStats& stats, const SchedulerParams& params);

class CyclicScheduler {
 public:
  static constexpr std::uint64_t kNoTickLimit = std::numeric_limits<std::uint64_t>::max();

  // Keeps a reference to `clock`. The statistics make this object ~130 KB: fine on a thread's
  // stack, or hold it in a unique_ptr.
  CyclicScheduler(hal::Clock& clock, SchedulerParams params);

  // Runs `tick(const TickInfo&) -> bool` once per release until it returns false, `max_ticks`
  // ticks have run, or request_stop(). Statistics restart with each run().
  template <class Tick>
  const SchedulerStats& run(Tick&& tick, std::uint64_t max_ticks = kNoTickLimit) {
    static_assert(std::is_invocable_r_v<bool, Tick&, const TickInfo&>,
                  "tick must be callable as bool(const TickInfo&)");
    start_run();
    while (stats_.ticks < max_ticks && !stop_requested_.load(std::memory_order_relaxed)) {
      const TickInfo& info = wait_for_release();
      const bool more = tick(info);
      end_tick();
      if (!more) break;
    }
    return stats_;
  }

  // From any thread or a signal handler: the loop ends after the current tick.
  void request_stop() noexcept { stop_requested_.store(true, std::memory_order_relaxed); }

  // Stage timing inside a tick; a stage begun and ended twice in one tick accumulates.
  void begin_stage(Stage stage) noexcept;
  void end_stage(Stage stage) noexcept;

  class ScopedStage {
   public:
    ScopedStage(CyclicScheduler& s, Stage stage) noexcept : s_(s), stage_(stage) {
      s_.begin_stage(stage_);
    }
    ~ScopedStage() { s_.end_stage(stage_); }
    ScopedStage(const ScopedStage&) = delete;
    ScopedStage& operator=(const ScopedStage&) = delete;

   private:
    CyclicScheduler& s_;
    Stage stage_;
  };
  // `auto timer = scheduler.stage(Stage::capture);` times the enclosing scope.
  [[nodiscard]] ScopedStage stage(Stage s) noexcept { return ScopedStage(*this, s); }

  // This tick's stage times so far (0 for stages not run yet), e.g. for its telemetry record.
  std::chrono::nanoseconds stage_time(Stage stage) const noexcept;
  // Inside a tick: it has already run past the next release (it will overrun). The tick can act
  // on its own overrun before it actuates, instead of learning it from the next tick's
  // skipped_before.
  bool tick_overrunning() const noexcept;
  // Bit i set: stage i exceeded its budget in this tick.
  std::uint32_t over_budget_mask() const noexcept { return over_budget_mask_; }

  const SchedulerStats& stats() const noexcept { return stats_; }
  const SchedulerParams& params() const noexcept { return params_; }
  std::chrono::nanoseconds period() const noexcept { return period_; }
  hal::Clock& clock() noexcept { return clock_; }
  std::string report() const { return format_scheduler_report(stats_, params_); }

 private:
  void start_run() noexcept;
  const TickInfo& wait_for_release() noexcept;
  void end_tick() noexcept;

  hal::Clock& clock_;
  SchedulerParams params_;
  std::chrono::nanoseconds period_;
  std::chrono::nanoseconds spin_margin_;
  std::array<std::chrono::nanoseconds, kStageCount> budget_{};
  std::atomic<bool> stop_requested_{false};

  std::chrono::nanoseconds start_{0};
  std::uint64_t next_release_ = 0;
  std::uint64_t pending_skipped_ = 0;
  TickInfo info_;

  std::array<std::chrono::nanoseconds, kStageCount> stage_begin_{};
  std::array<std::chrono::nanoseconds, kStageCount> stage_time_{};
  std::uint32_t ran_mask_ = 0;
  std::uint32_t over_budget_mask_ = 0;

  SchedulerStats stats_;
};

}  // namespace rovctl::app
