// Default policy and its parameter declarations (one section per cause).
#include "control/failsafe_policy.hpp"

namespace rovctl::control {

FailsafePolicy::FailsafePolicy() {
  for (const FailsafeCause c :
       {FailsafeCause::estimate_not_finite, FailsafeCause::vision_lost, FailsafeCause::vision_stale,
        FailsafeCause::vision_frozen, FailsafeCause::stereo_skew, FailsafeCause::bus_slow,
        FailsafeCause::attitude_limit, FailsafeCause::cpu_overrun}) {
    rule(c) = {"neutral", "auto"};
  }
  // The ESCs may still be armed: zero thrust is all that is left to command (and the disarm is
  // retried every tick).
  rule(FailsafeCause::disarm_unacked) = {"neutral", "latch"};
}

void describe(hal::ParamVisitor& v, FailsafePolicy& p) {
  for (std::size_t i = 1; i < p.rules.size(); ++i) {
    const auto cause = static_cast<FailsafeCause>(i);
    FailsafeRule& r = p.rules[i];
    v.section(cause_key(cause), to_string(cause), [&r](hal::ParamVisitor& s) {
      s.param("action", r.action,
              "safe action: default (control.failsafe.action), neutral, or disarm",
              {"default", "neutral", "disarm"});
      s.param("recovery", r.recovery,
              "auto: resume from SEARCH once the cause clears; latch: until the operator re-arms",
              {"auto", "latch"});
    });
  }
}

}  // namespace rovctl::control
