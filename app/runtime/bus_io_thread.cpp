// The bus I/O thread: one cycle writes the newest fresh command, answers arm requests, reads the
// telemetry and publishes what the bus said; the tick only touches lock-free slots and atomics.
#include "app/runtime/bus_io_thread.hpp"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cstdio>
#include <ctime>

#include "app/runtime/realtime_setup.hpp"

namespace rovctl::app {
namespace {

// Long enough not to spin, short enough that a stop or arm request is seen promptly even if a
// wake-up was missed.
constexpr std::chrono::milliseconds kIdleWait{20};
// Periods kept for the report: a day of 33 ms ticks would be 2.6 M; the first hour is plenty.
constexpr std::size_t kMaxPeriods = 1 << 17;

// SCHED_FIFO priority of the I/O thread: the lowest real-time one.
constexpr int kIoThreadPriority = 1;
// Telemetry is read at least every this many cycles, however busy the bus.
constexpr int kReadEvery = 3;

hal::BusStatus worst(hal::BusStatus a, hal::BusStatus b) {
  return static_cast<int>(a) > static_cast<int>(b) ? a : b;
}

// What the tick hears of the bus's own answer: its fault (its consecutive-failure limit), not a
// single failed request. A request that failed is retried or superseded next cycle; whether the
// bus is slow is the heartbeat gap's to say (degraded_ms), which is what the controller's watchdog
// judges too. A 15 ms controller on a loaded machine misses a 20 ms timeout now and then (p90
// 27.7 ms measured at load 8) without its heartbeat ever coming near 100 ms.
hal::BusStatus as_published(hal::BusStatus s) {
  return s == hal::BusStatus::fault ? hal::BusStatus::fault : hal::BusStatus::ok;
}

}  // namespace

BusIoThread::BusIoThread(hal::ThrusterBus& bus, const hal::Clock& clock,
                         const drivers::BusTimingParams& timing)
    : bus_(bus), clock_(clock), timing_(timing), name_(bus.name()) {
  sem_init(&wake_, 0, 0);
  stats_.heartbeat_period_ms.reserve(kMaxPeriods);
}

BusIoThread::~BusIoThread() {
  close();
  sem_destroy(&wake_);
}

bool BusIoThread::open(std::string& error) {
  if (opened_) return true;
  if (!bus_.open(error)) return false;
  opened_ = true;
  closed_ = false;
  // Opening commanded neutral and was answered: the heartbeat's first beat.
  last_ack_ns_.store(clock_.now().count(), std::memory_order_release);
  last_wake_ns_.store(clock_.now().count(), std::memory_order_release);
  running_.store(true);
  thread_ = std::thread([this]() { run(); });
  return true;
}

void BusIoThread::wake() noexcept { sem_post(&wake_); }

void BusIoThread::wait_for_work() noexcept {
  timespec deadline{};
  clock_gettime(CLOCK_REALTIME, &deadline);
  deadline.tv_nsec += std::chrono::nanoseconds(kIdleWait).count();
  if (deadline.tv_nsec >= 1'000'000'000) {
    deadline.tv_nsec -= 1'000'000'000;
    ++deadline.tv_sec;
  }
  while (sem_timedwait(&wake_, &deadline) != 0 && errno == EINTR) {
  }
}

void BusIoThread::record_ack(std::chrono::nanoseconds now) {
  const std::int64_t previous = last_ack_ns_.exchange(now.count(), std::memory_order_acq_rel);
  ++stats_.acknowledged;
  if (stats_.heartbeat_period_ms.size() < kMaxPeriods) {
    stats_.heartbeat_period_ms.push_back(static_cast<double>(now.count() - previous) * 1e-6);
  }
}

void BusIoThread::answer_arm_request(std::uint32_t& answered) {
  const std::uint32_t requested = arm_requested_.load(std::memory_order_acquire);
  if (requested != answered) {
    const hal::BusStatus s = bus_.arm(arm_value_.load(std::memory_order_acquire));
    bus_status_.store(static_cast<int>(as_published(s)), std::memory_order_release);
    // Answered, but not a heartbeat (the controller's watchdog looks at the beat register): it
    // restarts the gap without counting as a period.
    if (s == hal::BusStatus::ok)
      last_ack_ns_.store(clock_.now().count(), std::memory_order_release);
    arm_status_.store(static_cast<int>(s), std::memory_order_release);
    answered = requested;
    arm_answered_.store(answered, std::memory_order_release);
  }
}

void BusIoThread::serve_command() {
  const std::uint64_t published = commands_.published();
  if (const StampedCommand* c = commands_.take()) {
    if (clock_.now() - c->stamp > std::chrono::milliseconds(timing_.command_deadline_ms)) {
      // The tick has moved on (or stopped): late thrust is worse than none, and the
      // controller's watchdog stops the thrusters if nothing fresher comes.
      ++stats_.dropped_stale;
      if (reads_skipped_ > 0) {  // the read deferred for it: the bus is free now
        reads_skipped_ = 0;
        hal::ThrusterTelemetry& t = telemetry_.back();
        if (bus_.read(t) != hal::BusStatus::fault) telemetry_.publish();
      }
    } else if (probing_) {
      // A request that went unanswered may still sit in a stalled peer's input (a stream
      // cannot take it back), to be executed when it resumes: send no more commands into that
      // queue, only telemetry reads, harmless when replayed, until one is answered.
      ++stats_.withheld;
      hal::ThrusterTelemetry& t = telemetry_.back();
      if (bus_.read(t) != hal::BusStatus::fault && t.valid) {
        telemetry_.publish();
        probing_ = false;
        // A command published while the peer was silent is a tick or more old by now: the
        // peer that is back gets only commands made after it answered.
        if (commands_.take() != nullptr) ++stats_.dropped_stale;
      }
    } else {
      ++stats_.written;
      const hal::BusStatus s = bus_.write(c->command);
      bus_status_.store(static_cast<int>(as_published(s)), std::memory_order_release);
      if (s == hal::BusStatus::ok) {
        record_ack(clock_.now());
        // A newer command already waiting goes first: on a slow controller the read would
        // push every heartbeat past the tick. Telemetry is still read every kReadEvery cycles.
        const bool newer_waiting = commands_.published() != published;
        if (!newer_waiting || ++reads_skipped_ >= kReadEvery) {
          reads_skipped_ = 0;
          hal::ThrusterTelemetry& t = telemetry_.back();
          if (bus_.read(t) != hal::BusStatus::fault) telemetry_.publish();
        } else {
          ++stats_.reads_deferred;
        }
      } else {
        probing_ = true;
      }
    }
  }
}

void BusIoThread::run() {
  // Above every ordinary process, below the tick (SCHED_FIFO 80 on the vehicle): the heartbeat
  // is what keeps the controller's watchdog quiet, and with this thread a normal one a busy
  // machine held it off the CPU for over 100 ms between two requests (a "bus slow" with every
  // answer inside 21 ms). It only sends and waits, so it takes the CPU for microseconds at a time.
  // Without the privilege it stays an ordinary thread.
  sched_param fifo{};
  fifo.sched_priority = kIoThreadPriority;
  if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &fifo) != 0) make_thread_non_realtime();
  std::uint32_t answered = 0;
  probing_ = false;
  reads_skipped_ = 0;
  while (true) {
    wait_for_work();
    // What the tick needs to tell a stall of this thread from a bus that does not answer: when
    // it last ran, and since when it is inside a bus call (the whole pass: the rest is
    // microseconds).
    const std::int64_t woke = clock_.now().count();
    last_wake_ns_.store(woke, std::memory_order_release);
    busy_since_ns_.store(woke, std::memory_order_release);
    // Arm requests first: a disarm must not wait behind a command, and arming always writes
    // neutral before it arms (the bus's contract), so no queued command jumps ahead of it.
    answer_arm_request(answered);
    serve_command();
    busy_since_ns_.store(0, std::memory_order_release);
    // Stop only once nothing is left to answer, so close()'s final disarm is always attempted.
    if (!running_.load(std::memory_order_acquire) &&
        arm_requested_.load(std::memory_order_acquire) == answered) {
      break;
    }
  }
}

std::chrono::nanoseconds BusIoThread::heartbeat_age() const {
  return clock_.now() - std::chrono::nanoseconds(last_ack_ns_.load(std::memory_order_acquire));
}

hal::BusStatus BusIoThread::status_for_tick(std::chrono::nanoseconds now) {
  reason_is_gap_ = false;
  if (!opened_ || closed_) return hal::BusStatus::fault;
  const auto own = static_cast<hal::BusStatus>(bus_status_.load(std::memory_order_acquire));
  const std::chrono::nanoseconds age =
      now - std::chrono::nanoseconds(last_ack_ns_.load(std::memory_order_acquire));
  const std::chrono::milliseconds degraded_ms(timing_.degraded_ms);
  const std::chrono::milliseconds watchdog_ms(timing_.watchdog_ms);
  hal::BusStatus gap = age > watchdog_ms   ? hal::BusStatus::fault
                       : age > degraded_ms ? hal::BusStatus::degraded
                                           : hal::BusStatus::ok;
  if (gap == hal::BusStatus::ok) return own;
  const auto ms = [](std::chrono::nanoseconds d) {
    return static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(d).count());
  };
  const std::int64_t busy_since = busy_since_ns_.load(std::memory_order_acquire);
  const std::chrono::nanoseconds io_idle =
      now - std::chrono::nanoseconds(last_wake_ns_.load(std::memory_order_acquire));
  const char* local = nullptr;
  std::chrono::nanoseconds local_gap{0};
  if (tick_gap_ > degraded_ms) {
    local = "tick late";
    local_gap = tick_gap_;
  } else if (busy_since == 0 && io_idle > degraded_ms) {
    local = "I/O thread late";
    local_gap = io_idle;
  }
  // A stall of this machine's own that stayed under the controller's watchdog: the vehicle kept
  // its last command throughout and the next cycle catches up; holding it against the bus would
  // end a mission the vehicle never saw interrupted.
  if (local != nullptr && gap == hal::BusStatus::degraded) return own;
  if (own != hal::BusStatus::fault) {
    reason_is_gap_ = true;
    if (local != nullptr) {
      std::snprintf(gap_reason_.data(), gap_reason_.size(),
                    "%s %lld ms (a stall of this machine): no command acknowledged for %lld ms, "
                    "past watchdog_ms %d",
                    local, ms(local_gap), ms(age), timing_.watchdog_ms);
    } else if (busy_since != 0) {
      std::snprintf(gap_reason_.data(), gap_reason_.size(),
                    "bus not answering: a request waiting %lld ms, no acknowledgement for %lld ms "
                    "(limits %d / %d ms)",
                    ms(now - std::chrono::nanoseconds(busy_since)), ms(age), timing_.degraded_ms,
                    timing_.watchdog_ms);
    } else {
      std::snprintf(gap_reason_.data(), gap_reason_.size(),
                    "no acknowledgement for %lld ms (limits %d / %d ms)", ms(age),
                    timing_.degraded_ms, timing_.watchdog_ms);
    }
  }
  return worst(gap, own);
}

hal::BusStatus BusIoThread::write(const hal::ThrusterCommand& command) {
  if (!opened_ || closed_) return hal::BusStatus::fault;
  StampedCommand& slot = commands_.back();
  slot.command = command;
  const std::chrono::nanoseconds now = clock_.now();
  slot.stamp = now;
  commands_.publish();
  wake();
  tick_gap_ = prev_write_.count() == 0 ? std::chrono::nanoseconds{0} : now - prev_write_;
  prev_write_ = now;
  return status_for_tick(now);
}

hal::BusStatus BusIoThread::read(hal::ThrusterTelemetry& telemetry) {
  if (const hal::ThrusterTelemetry* t = telemetry_.take()) last_telemetry_ = *t;
  telemetry = last_telemetry_;
  return status_for_tick(clock_.now());
}

bool BusIoThread::request_arm(bool armed, hal::BusStatus& answer) {
  arm_value_.store(armed, std::memory_order_release);
  const std::uint32_t ticket = arm_requested_.fetch_add(1, std::memory_order_acq_rel) + 1;
  wake();
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(timing_.close_timeout_ms);
  while (arm_answered_.load(std::memory_order_acquire) != ticket) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  answer = static_cast<hal::BusStatus>(arm_status_.load(std::memory_order_acquire));
  return true;
}

hal::BusStatus BusIoThread::arm(bool armed) {
  if (!opened_ || closed_) return hal::BusStatus::fault;
  if (!armed) {
    arm_value_.store(false, std::memory_order_release);
    arm_requested_.fetch_add(1, std::memory_order_acq_rel);
    wake();
    return status_for_tick(clock_.now());
  }
  hal::BusStatus answer = hal::BusStatus::fault;
  if (!request_arm(true, answer)) return hal::BusStatus::fault;  // no answer in time
  return answer;
}

void BusIoThread::close() {
  if (closed_) return;
  if (opened_ && thread_.joinable()) {
    // The disarm writes neutral first (the bus's contract): both answered ok, or not safe.
    hal::BusStatus answer = hal::BusStatus::fault;
    safe_acknowledged_ = request_arm(false, answer) && answer == hal::BusStatus::ok;
    running_.store(false, std::memory_order_release);
    wake();
    // Bounded by the bus's own timeouts: the thread is inside at most one transaction (and the
    // disarm it still owes).
    thread_.join();
    stats_.superseded =
        commands_.published() - stats_.written - stats_.dropped_stale - stats_.withheld;
  }
  closed_ = true;
  bus_.close();
}

}  // namespace rovctl::app
