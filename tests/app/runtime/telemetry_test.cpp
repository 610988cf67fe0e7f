// Telemetry ring (order, wrap-around, drops, concurrency) and the CSV writer.
#include "app/runtime/telemetry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/runtime/allocation_counter.hpp"
#include "estimator/pose_estimator.hpp"
#include "hal/mock/virtual_clock.hpp"

namespace rovctl::app {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(cell);
  return out;
}

std::vector<std::string> read_lines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("rovctl_telemetry_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(SpscRing, CapacityRoundsUpToPowerOfTwo) {
  EXPECT_EQ(SpscRing<int>(1000).capacity(), 1024u);
  EXPECT_EQ(SpscRing<int>(1024).capacity(), 1024u);
  EXPECT_EQ(SpscRing<int>(0).capacity(), 2u);
}

TEST(SpscRing, KeepsOrderAcrossWrapAround) {
  SpscRing<int> ring(8);
  int next_in = 0;
  int next_out = 0;
  for (int round = 0; round < 10; ++round) {
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(ring.try_push(next_in++));
    EXPECT_EQ(ring.size(), 5u);
    int v = -1;
    for (int i = 0; i < 5; ++i) {
      ASSERT_TRUE(ring.try_pop(v));
      EXPECT_EQ(v, next_out++);
    }
    EXPECT_FALSE(ring.try_pop(v));
  }
  EXPECT_EQ(ring.pushed(), 50u);
  EXPECT_EQ(ring.dropped(), 0u);
}

TEST(SpscRing, FullRingDropsNewItemsAndCountsThem) {
  SpscRing<int> ring(4);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.try_push(i));
  EXPECT_FALSE(ring.try_push(4));
  EXPECT_FALSE(ring.try_push(5));
  EXPECT_EQ(ring.dropped(), 2u);
  int v = -1;
  ASSERT_TRUE(ring.try_pop(v));
  EXPECT_EQ(v, 0);  // the oldest stays; the newest were dropped
  EXPECT_TRUE(ring.try_push(6));
  std::vector<int> rest;
  while (ring.try_pop(v)) rest.push_back(v);
  EXPECT_EQ(rest, (std::vector<int>{1, 2, 3, 6}));
}

TEST(SpscRing, ConcurrentProducerAndConsumerSeeEveryItemInOrder) {
  struct Item {
    std::uint64_t seq;
    std::uint64_t check;
  };
  SpscRing<Item> ring(64);
  constexpr std::uint64_t kItems = 200'000;
  std::uint64_t dropped = 0;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems;) {
      if (ring.try_push({i, i * 2654435761u})) {
        ++i;
      } else {
        ++dropped;
        std::this_thread::yield();
      }
    }
  });
  std::uint64_t expected = 0;
  bool torn = false;
  while (expected < kItems) {
    Item it{};
    if (!ring.try_pop(it)) continue;
    if (it.seq != expected || it.check != it.seq * 2654435761u) torn = true;
    ++expected;
  }
  producer.join();
  EXPECT_FALSE(torn);
  EXPECT_EQ(ring.dropped(), dropped);
  EXPECT_EQ(ring.popped(), kItems);
}

TEST(SpscRing, PushAndPopAllocateNothing) {
  SpscRing<TelemetryRecord> ring(16);
  TelemetryRecord r;
  AllocationProbe probe;
  for (int i = 0; i < 100; ++i) {
    r.tick = static_cast<std::uint64_t>(i);
    ring.try_push(r);
    if (i % 3 == 0) ring.try_pop(r);
  }
  EXPECT_EQ(probe.allocations(), 0u);
  EXPECT_GT(ring.dropped(), 0u);
}

TEST(Telemetry, HeaderAndRowHaveTheSameColumns) {
  TelemetryRecord r;
  r.tick = 7;
  r.fitness = 0.75;
  r.thruster_cmd[3] = -0.5;
  r.error_bound_deg = 5.5;
  r.not_ok_reason = static_cast<std::int32_t>(estimator::NotOkReason::bound_over_limit);
  char buf[2048];
  const std::size_t n = format_telemetry_csv_row(r, buf, sizeof buf);
  const std::string row(buf, n);
  const auto header = split(telemetry_csv_header());
  const auto cells = split(row);
  ASSERT_EQ(header.size(), cells.size()) << row;
  auto col = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return cells[i];
    }
    return std::string("<missing>");
  };
  EXPECT_EQ(col("tick"), "7");
  EXPECT_EQ(col("fitness"), "0.75");
  EXPECT_EQ(col("cmd3"), "-0.5");
  EXPECT_EQ(col("truth_x_m"), "nan");                   // not simulated: NaN, not a fake zero
  EXPECT_EQ(col("not_ok_reason"), "bound_over_limit");  // a word the engineer reads, not a code
  EXPECT_EQ(col("error_bound_deg"), "5.5");
  EXPECT_EQ(col("error_bound_m"), "nan");
}

TEST(Telemetry, ScheduleFieldsComeFromTheTick) {
  hal::mock::VirtualClock clock;
  SchedulerParams p;
  p.period_ms = 10.0;
  CyclicScheduler s(clock, p);
  std::vector<TelemetryRecord> records;
  s.run(
      [&](const TickInfo& t) {
        {
          auto timer = s.stage(Stage::capture);
          clock.advance(std::chrono::milliseconds(t.index == 0 ? 15 : 2));
        }
        TelemetryRecord r;
        fill_schedule_fields(r, t, s);
        records.push_back(r);
        return true;
      },
      2);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].release, 2u);
  EXPECT_DOUBLE_EQ(records[1].time_s, 0.020);
  EXPECT_EQ(records[1].deadline_ns, 20'000'000);
  EXPECT_EQ(records[0].stage_ns[0], 15'000'000);
  EXPECT_EQ(records[1].skipped_total, 1u);
  EXPECT_TRUE(records[1].flags & telemetry_flag::overrun);
  EXPECT_TRUE(records[0].flags & telemetry_flag::stage_over_budget);  // 15 ms > 4 ms budget
  EXPECT_FALSE(records[1].flags & telemetry_flag::stage_over_budget);
}

TEST(TelemetryWriter, WritesHeaderAndOneRowPerRecordThenRenames) {
  const fs::path dir = temp_dir("writer");
  const fs::path file = dir / "telemetry.csv";
  TelemetryRing ring(64);
  TelemetryWriter writer(ring, file.string(), std::chrono::milliseconds(5));
  writer.start();
  EXPECT_TRUE(fs::exists(file.string() + ".tmp"));
  EXPECT_FALSE(fs::exists(file));
  constexpr int kRows = 500;  // more than the ring holds: the writer drains while we push
  for (int i = 0; i < kRows; ++i) {
    TelemetryRecord r;
    r.tick = static_cast<std::uint64_t>(i);
    r.est_t_m = {0.1 * i, 0.0, 1.5};
    while (!ring.try_push(r)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  writer.stop();
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  EXPECT_EQ(writer.rows_written(), static_cast<std::uint64_t>(kRows));
  const auto lines = read_lines(file);
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kRows + 1));
  EXPECT_EQ(lines[0], telemetry_csv_header());
  for (int i = 0; i < kRows; ++i) {
    ASSERT_EQ(split(lines[static_cast<std::size_t>(i + 1)])[0], std::to_string(i));
  }
  writer.stop();  // idempotent
  fs::remove_all(dir);
}

TEST(TelemetryWriter, UnwritableFileIsAnErrorNamingIt) {
  TelemetryRing ring(16);
  TelemetryWriter writer(ring, "/nonexistent_dir/telemetry.csv");
  try {
    writer.start();
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir/telemetry.csv.tmp"), std::string::npos);
  }
}

}  // namespace
}  // namespace rovctl::app
