// Histogram bookkeeping; negative samples (a clock stepping back) count in the first bin.
#include "app/runtime/latency_stats.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::app {

void LatencyStats::add(std::chrono::nanoseconds sample) noexcept {
  const std::int64_t ns = sample.count();
  const std::int64_t bin = std::max<std::int64_t>(ns, 0) / kBinWidth.count();
  ++bins_[static_cast<std::size_t>(std::min<std::int64_t>(bin, kBins))];
  if (count_ == 0) {
    min_ns_ = ns;
    max_ns_ = ns;
  } else {
    min_ns_ = std::min(min_ns_, ns);
    max_ns_ = std::max(max_ns_, ns);
  }
  ++count_;
  sum_ns_ += ns;
}

void LatencyStats::reset() noexcept { *this = LatencyStats(); }

std::chrono::nanoseconds LatencyStats::min() const noexcept {
  return std::chrono::nanoseconds(min_ns_);
}

std::chrono::nanoseconds LatencyStats::max() const noexcept {
  return std::chrono::nanoseconds(max_ns_);
}

std::chrono::nanoseconds LatencyStats::mean() const noexcept {
  return std::chrono::nanoseconds(count_ == 0 ? 0 : sum_ns_ / static_cast<std::int64_t>(count_));
}

std::chrono::nanoseconds LatencyStats::percentile(double p) const noexcept {
  if (count_ == 0) return std::chrono::nanoseconds(0);
  const double clamped = std::clamp(p, 0.0, 1.0);
  const auto rank = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(clamped * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < kBins; ++b) {
    seen += bins_[b];
    if (seen >= rank) {
      const std::int64_t upper = static_cast<std::int64_t>(b + 1) * kBinWidth.count();
      return std::chrono::nanoseconds(std::min(upper, max_ns_));
    }
  }
  return max();
}

}  // namespace rovctl::app
