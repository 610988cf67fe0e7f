// Thread-level scheduling on Linux: sched_setscheduler and setpriority on the thread's own id.
#include "app/view/background_priority.hpp"

#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace rovctl::app {

void run_below_the_tick() noexcept {
  const auto tid = static_cast<pid_t>(syscall(SYS_gettid));
  sched_param none{};
  none.sched_priority = 0;
  // Failure leaves the thread as it was (a container may refuse): the view still works.
  sched_setscheduler(tid, SCHED_BATCH, &none);
  setpriority(PRIO_PROCESS, static_cast<id_t>(tid), 10);
}

}  // namespace rovctl::app
