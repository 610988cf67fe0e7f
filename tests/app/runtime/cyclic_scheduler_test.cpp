// The cyclic executive on the virtual clock: release grid, overrun skipping, jitter and stage
// statistics; and (opt-in, ROVCTL_RT_MEASURE=1) a 3,000-tick measurement on the real clock.
#include "app/runtime/cyclic_scheduler.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <vector>

#include "app/runtime/allocation_counter.hpp"
#include "app/runtime/realtime_setup.hpp"
#include "drivers/monotonic_clock.hpp"
#include "hal/mock/virtual_clock.hpp"

namespace rovctl::app {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

SchedulerParams params_ms(double period_ms) {
  SchedulerParams p;
  p.period_ms = period_ms;
  return p;
}

TEST(CyclicScheduler, DeadlinesAreExactMultiplesOfThePeriod) {
  hal::mock::VirtualClock clock;
  clock.advance(milliseconds(5));  // the grid starts wherever the clock is
  CyclicScheduler s(clock, params_ms(33.0));
  std::vector<TickInfo> ticks;
  s.run(
      [&](const TickInfo& t) {
        ticks.push_back(t);
        clock.advance(milliseconds(3));
        return true;
      },
      10);
  ASSERT_EQ(ticks.size(), 10u);
  for (std::size_t k = 0; k < ticks.size(); ++k) {
    EXPECT_EQ(ticks[k].index, k);
    EXPECT_EQ(ticks[k].release, k);
    EXPECT_EQ(ticks[k].start, milliseconds(5));
    EXPECT_EQ(ticks[k].deadline, milliseconds(5) + milliseconds(33) * static_cast<long>(k));
    EXPECT_EQ(ticks[k].jitter(), nanoseconds(0));
    EXPECT_DOUBLE_EQ(ticks[k].time_s(), 0.033 * static_cast<double>(k));
  }
  EXPECT_EQ(s.stats().ticks, 10u);
  EXPECT_EQ(s.stats().overrun_ticks, 0u);
  EXPECT_EQ(s.stats().skipped_releases, 0u);
  EXPECT_EQ(s.stats().execution.max(), milliseconds(3));
}

TEST(CyclicScheduler, OverrunOfTwoAndAHalfPeriodsSkipsTwoReleasesAndStaysOnTheGrid) {
  hal::mock::VirtualClock clock;
  CyclicScheduler s(clock, params_ms(10.0));
  std::vector<TickInfo> ticks;
  s.run(
      [&](const TickInfo& t) {
        ticks.push_back(t);
        clock.advance(t.index == 1 ? microseconds(25'000) : microseconds(1'000));
        return true;
      },
      5);
  ASSERT_EQ(ticks.size(), 5u);
  // Tick 1 (release 1 at 10 ms) ends at 35 ms: releases 2 and 3 are skipped, not run late.
  EXPECT_EQ(ticks[1].release, 1u);
  EXPECT_EQ(ticks[2].release, 4u);
  EXPECT_EQ(ticks[2].deadline, milliseconds(40));
  EXPECT_EQ(ticks[2].skipped_before, 2u);
  EXPECT_EQ(ticks[2].skipped_total, 2u);
  EXPECT_EQ(ticks[3].release, 5u);
  EXPECT_EQ(ticks[3].skipped_before, 0u);
  EXPECT_EQ(ticks[4].deadline, milliseconds(60));
  EXPECT_EQ(s.stats().overrun_ticks, 1u);
  EXPECT_EQ(s.stats().skipped_releases, 2u);
}

TEST(CyclicScheduler, TickEndingExactlyOnTheNextReleaseIsNotAnOverrun) {
  hal::mock::VirtualClock clock;
  CyclicScheduler s(clock, params_ms(10.0));
  std::vector<std::uint64_t> releases;
  s.run(
      [&](const TickInfo& t) {
        releases.push_back(t.release);
        clock.advance(milliseconds(10));
        return true;
      },
      3);
  EXPECT_EQ(releases, (std::vector<std::uint64_t>{0, 1, 2}));
  EXPECT_EQ(s.stats().overrun_ticks, 0u);
}

// A clock that wakes late by a programmed amount, as a loaded OS would.
class LateClock final : public hal::Clock {
 public:
  std::chrono::nanoseconds now() const override { return now_; }
  void sleep_until(std::chrono::nanoseconds deadline) override {
    const auto late = lateness_[std::min(calls_++, lateness_.size() - 1)];
    if (deadline > now_) now_ = deadline + late;
  }
  std::vector<std::chrono::nanoseconds> lateness_;
  std::size_t calls_ = 0;
  std::chrono::nanoseconds now_{0};
};

TEST(CyclicScheduler, JitterStatistics) {
  LateClock clock;
  // 100 ticks: 98 wake 20 us late, one 450 us, one 2 ms (the first release is at start: 0 late).
  clock.lateness_.assign(101, microseconds(20));
  clock.lateness_[50] = microseconds(450);
  clock.lateness_[70] = microseconds(2000);
  CyclicScheduler s(clock, params_ms(33.0));
  s.run([](const TickInfo&) { return true; }, 101);
  const LatencyStats& j = s.stats().jitter;
  EXPECT_EQ(j.count(), 101u);
  EXPECT_EQ(j.min(), nanoseconds(0));
  EXPECT_EQ(j.max(), microseconds(2000));
  // p99 of 101 samples is the 100th smallest: 450 us, reported as its bin's upper edge.
  EXPECT_EQ(j.percentile(0.99), microseconds(460));
  EXPECT_EQ(j.percentile(0.5), microseconds(30));
  EXPECT_EQ(j.percentile(1.0), microseconds(2000));
  EXPECT_EQ(j.mean(), (nanoseconds(microseconds(20)) * 98 + microseconds(2450)) / 101);
  EXPECT_EQ(s.stats().overrun_ticks, 0u);
}

TEST(CyclicScheduler, StageTimingAndBudgets) {
  hal::mock::VirtualClock clock;
  SchedulerParams p = params_ms(33.0);
  p.stage_budget_ms = {1.0, 0.0, 20.0, 0.0, 0.0, 0.0};
  CyclicScheduler s(clock, p);
  std::vector<nanoseconds> estimate_seen;
  std::vector<std::uint32_t> masks;
  s.run(
      [&](const TickInfo& t) {
        {
          auto timer = s.stage(Stage::capture);
          clock.advance(t.index == 2 ? microseconds(1500) : microseconds(500));
        }
        s.begin_stage(Stage::estimate);
        clock.advance(milliseconds(10));
        s.end_stage(Stage::estimate);
        s.begin_stage(Stage::estimate);  // a second slice accumulates
        clock.advance(milliseconds(2));
        s.end_stage(Stage::estimate);
        estimate_seen.push_back(s.stage_time(Stage::estimate));
        EXPECT_EQ(s.stage_time(Stage::control), nanoseconds(0));
        masks.push_back(s.over_budget_mask());
        return true;
      },
      4);
  for (const auto e : estimate_seen) EXPECT_EQ(e, milliseconds(12));
  EXPECT_EQ(masks, (std::vector<std::uint32_t>{0, 0, 1, 0}));
  const auto& capture = s.stats().stages[static_cast<std::size_t>(Stage::capture)];
  EXPECT_EQ(capture.time.count(), 4u);
  EXPECT_EQ(capture.time.max(), microseconds(1500));
  EXPECT_EQ(capture.over_budget, 1u);
  EXPECT_EQ(s.stats().stages[static_cast<std::size_t>(Stage::estimate)].time.mean(),
            milliseconds(12));
  EXPECT_EQ(s.stats().stages[static_cast<std::size_t>(Stage::control)].time.count(), 0u);
  const std::string report = s.report();
  EXPECT_NE(report.find("4 ticks"), std::string::npos) << report;
  EXPECT_NE(report.find("capture"), std::string::npos) << report;
  EXPECT_EQ(report.find("control"), std::string::npos) << report;
}

TEST(CyclicScheduler, StopsWhenTickReturnsFalseOrStopIsRequested) {
  hal::mock::VirtualClock clock;
  CyclicScheduler s(clock, params_ms(33.0));
  EXPECT_EQ(s.run([](const TickInfo& t) { return t.index < 4; }).ticks, 5u);
  EXPECT_EQ(s.run([&](const TickInfo& t) {
               if (t.index == 6) s.request_stop();
               return true;
             }).ticks,
            7u);
  // A new run restarts the grid and the statistics.
  EXPECT_EQ(s.run([](const TickInfo&) { return true; }, 2).ticks, 2u);
}

TEST(CyclicScheduler, TickLoopAllocatesNothing) {
  ASSERT_TRUE(allocation_counting_active());
  hal::mock::VirtualClock clock;
  CyclicScheduler s(clock, params_ms(33.0));
  std::uint64_t during = 0;
  AllocationProbe whole_run;
  s.run(
      [&](const TickInfo& t) {
        AllocationProbe probe;
        {
          auto timer = s.stage(Stage::estimate);
          clock.advance(t.index % 7 == 3 ? milliseconds(70) : milliseconds(5));
        }
        during += probe.allocations();
        return true;
      },
      200);
  EXPECT_EQ(during, 0u);
  EXPECT_EQ(whole_run.allocations(), 0u);
  EXPECT_GT(s.stats().skipped_releases, 0u);
}

TEST(CyclicScheduler, SpinMarginKeepsTheGridAndEndsOnAVirtualClock) {
  hal::mock::VirtualClock clock;
  SchedulerParams p = params_ms(10.0);
  p.spin_margin_ms = 3.0;
  CyclicScheduler s(clock, p);
  std::vector<nanoseconds> wakeups;
  s.run(
      [&](const TickInfo& t) {
        wakeups.push_back(t.wakeup);
        clock.advance(milliseconds(2));
        return true;
      },
      3);
  EXPECT_EQ(wakeups,
            (std::vector<nanoseconds>{milliseconds(0), milliseconds(10), milliseconds(20)}));
}

TEST(CyclicScheduler, DescribedParametersHaveDefaults) {
  SchedulerParams p;
  EXPECT_DOUBLE_EQ(p.period_ms, 33.0);
  EXPECT_EQ(p.period(), nanoseconds(33'000'000));
  EXPECT_FALSE(p.realtime.sched_fifo);
  EXPECT_EQ(p.realtime.cpu_affinity, -1);
  EXPECT_EQ(stage_name(Stage::estimate), "estimate");
}

// The real-time measurement of the target: 3,000 ticks of 33 ms (100 s) on the
// monotonic clock with a 5 ms busy workload. Opt-in: ROVCTL_RT_MEASURE=1 (add ROVCTL_RT_FIFO=1
// for SCHED_FIFO + mlockall, ROVCTL_RT_CPU=n to pin, ROVCTL_RT_SPIN_MS=x for a spin margin).
TEST(CyclicSchedulerMeasurement, RealClockJitterOver3000Ticks) {
  const char* on = std::getenv("ROVCTL_RT_MEASURE");
  if (on == nullptr || std::string(on) != "1") GTEST_SKIP() << "set ROVCTL_RT_MEASURE=1";
  SchedulerParams p = params_ms(33.0);
  const char* fifo = std::getenv("ROVCTL_RT_FIFO");
  p.realtime.sched_fifo = fifo != nullptr && std::string(fifo) == "1";
  p.realtime.mlockall = p.realtime.sched_fifo;
  if (const char* cpu = std::getenv("ROVCTL_RT_CPU")) p.realtime.cpu_affinity = std::atoi(cpu);
  if (const char* spin = std::getenv("ROVCTL_RT_SPIN_MS")) p.spin_margin_ms = std::atof(spin);
  std::cout << "spin margin " << p.spin_margin_ms << " ms\n";
  const RealtimeSetupResult setup = apply_realtime_setup(p.realtime);
  for (const auto& a : setup.applied) std::cout << "realtime: " << a << "\n";
  for (const auto& w : setup.warnings) std::cout << "realtime warning: " << w << "\n";

  drivers::MonotonicClock clock;
  CyclicScheduler s(clock, p);
  std::uint64_t allocations = 0;
  s.run(
      [&](const TickInfo&) {
        AllocationProbe probe;
        {
          auto timer = s.stage(Stage::estimate);
          const auto until = clock.now() + milliseconds(5);
          while (clock.now() < until) {
          }
        }
        allocations += probe.allocations();
        return true;
      },
      3000);
  std::cout << s.report();
  std::cout << "jitter p99 " << s.stats().jitter.percentile(0.99).count() / 1000 << " us, max "
            << s.stats().jitter.max().count() / 1000 << " us, overruns " << s.stats().overrun_ticks
            << ", allocations in ticks " << allocations << "\n";
  EXPECT_EQ(s.stats().ticks, 3000u);
  EXPECT_EQ(allocations, 0u);
  EXPECT_LE(s.stats().jitter.percentile(0.99), milliseconds(1));
  EXPECT_EQ(s.stats().overrun_ticks, 0u);
}

}  // namespace
}  // namespace rovctl::app
