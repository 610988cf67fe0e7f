// The faults `rovctl sim --fault NAME[@t_s]` and `rovctl faults` inject into the mock HAL (or the
// config's limits), each with the failsafe cause it must trip and whether it passes by itself.
#pragma once

#include <string>

#include "app/runtime/app_config.hpp"

namespace rovctl::app {

struct InjectedFault {
  const char* name;   // as on the command line
  const char* cause;  // the control::FailsafeCause key it must trip
  bool transient;     // it passes after sim.faults.*_for_s: the trip must recover
  const char* what;
};

// Every fault; the last entry has a null name.
const InjectedFault* injected_faults();
// "camera_lost, camera_drop, ..." for usage messages.
std::string injected_fault_names_text();
// The fault called `name`, or null.
const InjectedFault* find_injected_fault(const std::string& name);
// "NAME" or "NAME@t_s" -> the fault and its time (`default_at_s` without one). False with
// `error` set on an unknown name or a bad time.
bool parse_fault_spec(const std::string& spec, double default_at_s, const InjectedFault*& fault,
                      double& at_s, std::string& error);
// Sets config.sim.faults (or the failsafe's limits) so that `f` strikes at sim time `at_s`.
void apply_injected_fault(const InjectedFault& f, double at_s, AppConfig& config);

}  // namespace rovctl::app
