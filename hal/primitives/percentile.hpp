// The one percentile of the project's reports: linear interpolation between the closest ranks
// (NumPy's default), so a median of an even count is the mean of the middle two.
#pragma once

#include <vector>

namespace rovctl::hal {

// The p-quantile (p in [0, 1], clamped) of `values`; NaN when empty. Infinite values sort last
// and an interpolation that reaches one is infinite (a failure counted as never).
double percentile(std::vector<double> values, double p);

}  // namespace rovctl::hal
