// What the operator page shows of one tick, as JSON: mission state, failsafe and hold banners,
// the estimate's confidence, the docking errors and the thruster commands. Served by /state and
// streamed by /events.
#pragma once

#include <cstdint>
#include <string>

#include "app/runtime/telemetry.hpp"

namespace rovctl::app {

struct OperatorStateContext {
  const char* source = "live";             // "live" or "replay"
  bool commands_enabled = false;           // a token is configured: ABORT and START are accepted
  std::uint64_t abort_requested_tick = 0;  // tick published when the last ABORT came in (0: none)
};

std::string operator_state_json(const TelemetryRecord& r, const OperatorStateContext& context);

}  // namespace rovctl::app
