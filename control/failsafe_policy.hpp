// The failsafe policy table (as ArduSub's FS_* parameters): for each cause, the safe action and
// whether the trip recovers by itself once the cause clears or latches until an operator re-arms.
#pragma once

#include <array>
#include <string>

#include "control/failsafe_cause.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::control {

struct FailsafeRule {
  // "default" (control.failsafe.action), "neutral" (armed, zero thrust) or "disarm". At the
  // station a cause that leaves the thrusters obeying backs out of the socket first (backout_s).
  std::string action = "default";
  // "auto": the trip clears once the cause has been gone for recover_ticks and the mission
  // resumes from SEARCH; "latch": only an operator's START (a re-arm) clears it.
  std::string recovery = "latch";
};

// Indexed by FailsafeCause; the entry for `none` is unused. Defaults: faults of the data that
// pass (a dropped, frozen or skewed frame burst, a tilt, a CPU stall) recover at neutral;
// hardware that stopped working (a dead camera or bus, lost or lying sensors) and the mission's
// own limits latch.
struct FailsafePolicy {
  std::array<FailsafeRule, kFailsafeCauseCount> rules;
  FailsafePolicy();
  const FailsafeRule& rule(FailsafeCause c) const { return rules[static_cast<std::size_t>(c)]; }
  FailsafeRule& rule(FailsafeCause c) { return rules[static_cast<std::size_t>(c)]; }
};

void describe(hal::ParamVisitor& v, FailsafePolicy& p);

}  // namespace rovctl::control
