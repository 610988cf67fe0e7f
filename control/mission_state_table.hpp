// The mission's states as declarations: for each, what enters it, what leaves it (with the reason
// logged), and what it commands. Mission's transition functions implement these rows; the
// documentation's table is rendered from them (mission_state_table_markdown).
#pragma once

#include <array>
#include <span>
#include <string>

#include "control/mission.hpp"

namespace rovctl::control {

// One way out of a state: the condition, the state it leads to, the reason the event logs.
struct MissionExit {
  const char* when;
  MissionState to;
  const char* reason;
};

struct MissionStateRow {
  MissionState state;
  const char* entered_when;
  std::span<const MissionExit> exits;  // empty: the mission ends here (or stays)
  const char* outputs;
};

// One row per MissionState, in the enum's order.
const std::array<MissionStateRow, kMissionStateCount>& mission_state_table();

// The table as Markdown, columns state | entered when | leaves when | outputs.
std::string mission_state_table_markdown();

}  // namespace rovctl::control
