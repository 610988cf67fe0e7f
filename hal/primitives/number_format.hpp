// The one way a number is written in messages and tables (config errors, `rovctl params`, the
// ArduSub failsafe verdicts): the stream's default, 6 significant digits, no trailing zeros.
#pragma once

#include <string>

namespace rovctl::hal {

// 0.25 -> "0.25", 1e-07 -> "1e-07", 33 -> "33", 1234567 -> "1.23457e+06". A float is widened
// first, as a stream does.
std::string format_number(double v);

}  // namespace rovctl::hal
