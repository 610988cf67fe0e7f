// POSIX/Linux calls behind the real-time options; every failure is reported with errno's text.
#include "app/runtime/realtime_setup.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rovctl::app {

void describe(hal::ParamVisitor& v, RealtimeParams& p) {
  v.param("sched_fifo", p.sched_fifo,
          "run the control thread under SCHED_FIFO (needs CAP_SYS_NICE or an rtprio limit)");
  v.param("priority", p.priority, {"-", 1, 99, "SCHED_FIFO priority of the control thread"});
  v.param("mlockall", p.mlockall,
          "lock all current and future memory (mlockall) so a tick never waits on a page fault");
  v.param("cpu_affinity", p.cpu_affinity,
          {"-", -1, 1023, "pin the control thread to this CPU index; -1: no pinning"});
}

RealtimeSetupResult apply_realtime_setup(const RealtimeParams& params) {
  RealtimeSetupResult r;
  if (params.mlockall) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      r.applied.push_back("memory locked (mlockall)");
    } else {
      r.warnings.push_back(std::string("mlockall refused: ") + std::strerror(errno) +
                           " (raise the memlock limit or grant CAP_IPC_LOCK)");
    }
  }
  if (params.cpu_affinity >= 0) {
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    if (params.cpu_affinity >= CPU_SETSIZE || (cpus > 0 && params.cpu_affinity >= cpus)) {
      r.warnings.push_back("cpu_affinity " + std::to_string(params.cpu_affinity) +
                           " ignored: this machine has " + std::to_string(cpus) + " CPUs online");
    } else {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(static_cast<unsigned>(params.cpu_affinity), &set);
      const int err = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
      if (err == 0) {
        r.applied.push_back("pinned to CPU " + std::to_string(params.cpu_affinity));
      } else {
        r.warnings.push_back("CPU affinity " + std::to_string(params.cpu_affinity) +
                             " refused: " + std::strerror(err));
      }
    }
  }
  if (params.sched_fifo) {
    sched_param sp{};
    sp.sched_priority = params.priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (err == 0) {
      r.applied.push_back("SCHED_FIFO priority " + std::to_string(params.priority));
    } else {
      r.warnings.push_back("SCHED_FIFO priority " + std::to_string(params.priority) +
                           " refused: " + std::strerror(err) +
                           " (needs CAP_SYS_NICE or an rtprio limit); running under SCHED_OTHER");
    }
  }
  if (params.mlockall) prefault_stack();
  return r;
}

void prefault_stack(std::size_t bytes) {
  // A volatile buffer the compiler cannot drop; alloca-free so the size is bounded at compile
  // time per call: touch in 16 KiB frames.
  constexpr std::size_t kChunk = 16 * 1024;
  struct Frame {
    static void touch(std::size_t remaining) {
      volatile unsigned char buf[kChunk];
      for (std::size_t i = 0; i < kChunk; i += 4096) buf[i] = 0;
      if (remaining > kChunk) touch(remaining - kChunk);
      buf[0] = buf[0];
    }
  };
  Frame::touch(bytes);
}

void make_thread_non_realtime() {
  sched_param sp{};
  sp.sched_priority = 0;
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
}

}  // namespace rovctl::app
