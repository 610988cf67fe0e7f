// Puts the calling thread below the tick: the operator view's encoding and streaming lose every
// contest for a CPU against the control loop, whatever the number of viewers.
#pragma once

namespace rovctl::app {

// SCHED_BATCH at nice 10 for this thread only (lowering needs no privilege). Against the tick at
// SCHED_FIFO (`rovctl run`) the view only runs when the tick sleeps; against a tick at
// SCHED_OTHER nice 0 (`rovctl sim`) it weighs about a tenth as much per thread.
void run_below_the_tick() noexcept;

}  // namespace rovctl::app
