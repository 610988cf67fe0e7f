// Reads a telemetry CSV (as `rovctl run` and `rovctl sim --out` write it) back into records, by
// column name, so a finished run can be replayed and re-scored.
#pragma once

#include <string>
#include <vector>

#include "app/runtime/telemetry.hpp"

namespace rovctl::app {

// Throws std::runtime_error naming file and line on a missing column or a malformed row.
std::vector<TelemetryRecord> read_telemetry_csv(const std::string& path);

}  // namespace rovctl::app
