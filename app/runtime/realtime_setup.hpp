// Real-time set-up of the control thread: SCHED_FIFO priority, locked memory, CPU affinity.
// Each is optional (config) and a refusal by the system is a warning, never a failed run.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hal/primitives/parameters.hpp"

namespace rovctl::app {

struct RealtimeParams {
  bool sched_fifo = false;  // SCHED_FIFO for the control thread
  int priority = 80;        // SCHED_FIFO priority, 1..99
  bool mlockall = false;    // mlockall(MCL_CURRENT | MCL_FUTURE): no page faults mid-tick
  int cpu_affinity = -1;    // pin the control thread to this CPU; -1: no pinning
};

void describe(hal::ParamVisitor& v, RealtimeParams& p);

struct RealtimeSetupResult {
  std::vector<std::string> applied;   // what took effect, for the start-up log
  std::vector<std::string> warnings;  // what the system refused, and why
};

// Applies `params` to the calling thread (mlockall is process-wide); call it on the thread that
// will run the scheduler, before the loop. Never throws for a refusal.
RealtimeSetupResult apply_realtime_setup(const RealtimeParams& params);

// Touches `bytes` of stack so that, with locked memory, the tick never faults a stack page in.
void prefault_stack(std::size_t bytes = 256 * 1024);

// Puts the calling thread back to SCHED_OTHER: for helper threads (telemetry writer) spawned
// by a SCHED_FIFO thread, which would otherwise inherit its policy.
void make_thread_non_realtime();

}  // namespace rovctl::app
