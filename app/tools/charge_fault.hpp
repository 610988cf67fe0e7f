// The charging faults `rovctl sim --charge-fault NAME` injects into the recharge trials, mid-charge
// in the closed loop (the seat-timed sim.faults keys, or the simulated operator), each with the
// state the mission must end in and the cause its log line must name.
#pragma once

#include <string>

#include "app/runtime/app_config.hpp"
#include "app/tools/docking_trial.hpp"

namespace rovctl::app {

struct ChargeFault {
  const char* name;
  const char* what;         // what is injected
  const char* final_state;  // the mission's state at the end (control::to_string)
  const char* cause;        // in the transition (or failsafe) line that handles it
};

// Every fault, "none" first; the last entry has a null name.
const ChargeFault* charge_faults();
// "none, knock, ..." for usage messages.
std::string charge_fault_names_text();
// The fault called `name`, or null.
const ChargeFault* find_charge_fault(const std::string& name);

// Sets config.sim.faults and the trial options for fault `f`: each comes 3 s into the seat (the
// charger fault from the start, as a dead charger is found on arrival).
void apply_charge_fault(const ChargeFault& f, AppConfig& config, TrialOptions& options);

}  // namespace rovctl::app
