// Percentile by sorting a copy: for reports and benchmarks, never the tick.
#include "hal/primitives/percentile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rovctl::hal {

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double h = (static_cast<double>(values.size()) - 1.0) * std::clamp(p, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const double w = h - static_cast<double>(lo);
  if (w == 0.0 || lo + 1 >= values.size()) return values[lo];
  if (std::isinf(values[lo + 1])) return values[lo + 1];
  return values[lo] + w * (values[lo + 1] - values[lo]);
}

}  // namespace rovctl::hal
