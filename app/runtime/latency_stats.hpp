// Allocation-free latency statistics (count, min, max, mean, percentiles) over a fixed histogram
// of 10 us bins, for the scheduler's jitter and per-stage times.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace rovctl::app {

class LatencyStats {
 public:
  static constexpr std::chrono::nanoseconds kBinWidth{10'000};
  // 4096 bins of 10 us cover 0..40.96 ms (more than one 33 ms period); longer samples land in an
  // overflow bin and a percentile falling there reports the exact maximum.
  static constexpr std::size_t kBins = 4096;

  void add(std::chrono::nanoseconds sample) noexcept;
  void reset() noexcept;

  std::uint64_t count() const noexcept { return count_; }
  std::chrono::nanoseconds min() const noexcept;
  std::chrono::nanoseconds max() const noexcept;
  std::chrono::nanoseconds mean() const noexcept;
  // Upper edge of the bin holding the p-quantile (p in [0, 1]), never above max(): a bound
  // within one bin width. 0 when empty.
  std::chrono::nanoseconds percentile(double p) const noexcept;

 private:
  std::array<std::uint32_t, kBins + 1> bins_{};  // last bin: overflow
  std::uint64_t count_ = 0;
  std::int64_t sum_ns_ = 0;
  std::int64_t min_ns_ = 0;
  std::int64_t max_ns_ = 0;
};

}  // namespace rovctl::app
