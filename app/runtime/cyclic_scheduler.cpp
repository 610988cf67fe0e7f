// Release grid, overrun skipping and the per-tick bookkeeping of the cyclic executive.
#include "app/runtime/cyclic_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rovctl::app {
namespace {

constexpr std::array<std::string_view, kStageCount> kStageNames = {
    "capture", "segment", "estimate", "control", "actuate", "telemetry"};

std::chrono::nanoseconds from_ms(double ms) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(ms * 1e6)));
}

double to_ms(std::chrono::nanoseconds ns) { return static_cast<double>(ns.count()) * 1e-6; }

std::string stats_line(const char* name, const LatencyStats& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-10s n %7llu  mean %8.3f  p99 %8.3f  max %8.3f ms", name,
                static_cast<unsigned long long>(s.count()), to_ms(s.mean()),
                to_ms(s.percentile(0.99)), to_ms(s.max()));
  return buf;
}

}  // namespace

std::string_view stage_name(Stage stage) noexcept {
  return kStageNames[static_cast<std::size_t>(stage)];
}

std::chrono::nanoseconds SchedulerParams::period() const { return from_ms(period_ms); }

std::chrono::nanoseconds SchedulerParams::spin_margin() const { return from_ms(spin_margin_ms); }

std::chrono::nanoseconds SchedulerParams::stage_budget(Stage stage) const {
  return from_ms(stage_budget_ms[static_cast<std::size_t>(stage)]);
}

void describe(hal::ParamVisitor& v, SchedulerParams& p) {
  v.param("period_ms", p.period_ms,
          {"ms", 1.0, 1000.0, "control period: one tick (capture to actuate) per period"});
  v.param("spin_margin_ms", p.spin_margin_ms,
          {"ms", 0.0, 100.0,
           "wake this early and busy-wait to the release (for non-preemptive kernels; costs CPU); "
           "0: sleep to the release"});
  v.section("realtime", "real-time options; a refusal by the system is a warning",
            [&p](hal::ParamVisitor& s) { describe(s, p.realtime); });
  v.section("stage_budget_ms",
            "per-stage time budgets; a stage over budget is counted and reported (0: no check)",
            [&p](hal::ParamVisitor& s) {
              for (std::size_t i = 0; i < kStageCount; ++i) {
                s.param(kStageNames[i], p.stage_budget_ms[i],
                        {"ms", 0.0, 1000.0, "time budget of this stage of the tick"});
              }
            });
}

std::string format_scheduler_report(const SchedulerStats& stats, const SchedulerParams& params) {
  char head[256];
  std::snprintf(head, sizeof head,
                "scheduler: %llu ticks of %.3f ms, %llu overrun ticks, %llu skipped releases\n",
                static_cast<unsigned long long>(stats.ticks), params.period_ms,
                static_cast<unsigned long long>(stats.overrun_ticks),
                static_cast<unsigned long long>(stats.skipped_releases));
  std::string out = head;
  out += "  " + stats_line("jitter", stats.jitter) + "\n";
  out += "  " + stats_line("execution", stats.execution) + "\n";
  for (std::size_t i = 0; i < kStageCount; ++i) {
    const StageStats& s = stats.stages[i];
    if (s.time.count() == 0) continue;
    out += "  " + stats_line(kStageNames[i].data(), s.time);
    if (params.stage_budget_ms[i] > 0.0) {
      char b[96];
      std::snprintf(b, sizeof b, "  over %.3f ms budget: %llu", params.stage_budget_ms[i],
                    static_cast<unsigned long long>(s.over_budget));
      out += b;
    }
    out += "\n";
  }
  return out;
}

CyclicScheduler::CyclicScheduler(hal::Clock& clock, SchedulerParams params)
    : clock_(clock),
      params_(params),
      period_(params.period()),
      spin_margin_(std::min(params.spin_margin(), params.period())) {
  if (period_.count() <= 0) throw std::invalid_argument("scheduler period must be positive");
  if (spin_margin_.count() < 0) throw std::invalid_argument("spin margin must not be negative");
  for (std::size_t i = 0; i < kStageCount; ++i) budget_[i] = params_.stage_budget(Stage(i));
}

void CyclicScheduler::start_run() noexcept {
  stop_requested_.store(false, std::memory_order_relaxed);
  stats_ = SchedulerStats();
  start_ = clock_.now();
  next_release_ = 0;
  pending_skipped_ = 0;
}

const TickInfo& CyclicScheduler::wait_for_release() noexcept {
  const std::chrono::nanoseconds deadline = start_ + period_ * next_release_;
  if (spin_margin_.count() > 0) {
    clock_.sleep_until(deadline - spin_margin_);
    // Busy-wait; a clock that does not move by itself (virtual) ends the spin at once.
    std::chrono::nanoseconds last = clock_.now();
    for (int still = 0; last < deadline && still < 64;) {
      const std::chrono::nanoseconds t = clock_.now();
      still = t == last ? still + 1 : 0;
      last = t;
    }
  }
  clock_.sleep_until(deadline);
  const std::chrono::nanoseconds wakeup = clock_.now();
  stats_.jitter.add(wakeup - deadline);

  info_.index = stats_.ticks;
  info_.release = next_release_;
  info_.start = start_;
  info_.deadline = deadline;
  info_.wakeup = wakeup;
  info_.period = period_;
  info_.skipped_before = pending_skipped_;
  info_.skipped_total = stats_.skipped_releases;

  stage_time_.fill(std::chrono::nanoseconds(0));
  ran_mask_ = 0;
  over_budget_mask_ = 0;
  return info_;
}

void CyclicScheduler::end_tick() noexcept {
  const std::chrono::nanoseconds end = clock_.now();
  stats_.execution.add(end - info_.wakeup);
  ++stats_.ticks;
  for (std::size_t i = 0; i < kStageCount; ++i) {
    if ((ran_mask_ & (1u << i)) == 0) continue;
    stats_.stages[i].time.add(stage_time_[i]);
    if ((over_budget_mask_ & (1u << i)) != 0) ++stats_.stages[i].over_budget;
  }

  // Overrun policy: resume at the first release not in the past; skipped ones are counted.
  const std::uint64_t next = info_.release + 1;
  pending_skipped_ = 0;
  if (end > start_ + period_ * next) {
    const std::int64_t since_start = (end - start_).count();
    const auto first_future =
        static_cast<std::uint64_t>((since_start + period_.count() - 1) / period_.count());
    pending_skipped_ = first_future - next;
    ++stats_.overrun_ticks;
    stats_.skipped_releases += pending_skipped_;
    next_release_ = first_future;
  } else {
    next_release_ = next;
  }
}

void CyclicScheduler::begin_stage(Stage stage) noexcept {
  stage_begin_[static_cast<std::size_t>(stage)] = clock_.now();
}

void CyclicScheduler::end_stage(Stage stage) noexcept {
  const auto i = static_cast<std::size_t>(stage);
  stage_time_[i] += clock_.now() - stage_begin_[i];
  ran_mask_ |= 1u << i;
  if (budget_[i].count() > 0 && stage_time_[i] > budget_[i]) over_budget_mask_ |= 1u << i;
}

bool CyclicScheduler::tick_overrunning() const noexcept {
  return clock_.now() > info_.deadline + period_;
}

std::chrono::nanoseconds CyclicScheduler::stage_time(Stage stage) const noexcept {
  return stage_time_[static_cast<std::size_t>(stage)];
}

}  // namespace rovctl::app
