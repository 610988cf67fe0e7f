// BusIoThread: a ThrusterBus that runs a real bus on its own I/O thread, so the tick never waits
// for the peer; commands, status and telemetry cross lock-free and stale commands are dropped.
#pragma once

#include <semaphore.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "drivers/thruster_bus_params.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/primitives/latest_slot.hpp"

namespace rovctl::app {

// What the I/O thread did, for the report and the tests (read after close()).
struct BusIoStats {
  std::uint64_t written = 0;         // commands handed to the bus
  std::uint64_t acknowledged = 0;    // of those, answered ok
  std::uint64_t dropped_stale = 0;   // older than command_deadline_ms when the bus was free
  std::uint64_t superseded = 0;      // overwritten by a newer command before the bus was free
  std::uint64_t withheld = 0;        // not sent while an unanswered peer was probed with reads
  std::uint64_t reads_deferred = 0;  // telemetry reads left out for a newer waiting command
  std::vector<double> heartbeat_period_ms;  // time between acknowledged writes
};

class BusIoThread final : public hal::ThrusterBus {
 public:
  // `bus` and `clock` outlive this; `clock` stamps commands (the tick's time base) and must be
  // readable from any thread.
  BusIoThread(hal::ThrusterBus& bus, const hal::Clock& clock,
              const drivers::BusTimingParams& timing);
  ~BusIoThread() override;  // close()
  BusIoThread(const BusIoThread&) = delete;
  BusIoThread& operator=(const BusIoThread&) = delete;

  // Opens the bus on the caller's thread (start-up may wait), then starts the I/O thread.
  bool open(std::string& error) override;
  // Arming is a start-up step whose outcome must be known: waits, at most close_timeout_ms, for
  // the bus's answer. Disarming is what the tick does on a trip: queued, never waits; returns the
  // current status.
  hal::BusStatus arm(bool armed) override;
  // Hands the command (stamped now) to the I/O thread and returns at once with the bus status:
  // the heartbeat gap's (degraded_ms, watchdog_ms), or fault when the bus itself reported one.
  hal::BusStatus write(const hal::ThrusterCommand& command) override;
  // The newest telemetry the I/O thread read; the same status as write().
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override;
  // Final neutral and disarm through the I/O thread, waiting at most close_timeout_ms for their
  // acknowledgement, then stops the thread and closes the bus. Idempotent.
  void close() override;
  std::string name() const override { return name_; }
  // The bus's own reason, or when the heartbeat gap is the cause, the gap's story with figures:
  // a local stall ("tick late 240 ms", "I/O thread late 240 ms") or the bus not answering.
  const char* fault_reason() const override {
    return reason_is_gap_ ? gap_reason_.data() : bus_.fault_reason();
  }

  // After close(): whether the final neutral and disarm were acknowledged in time.
  bool safe_acknowledged() const { return safe_acknowledged_; }
  // After close() (the I/O thread has stopped); empty periods before.
  const BusIoStats& stats() const { return stats_; }
  // Any thread: the time since the last acknowledged write, on the clock.
  std::chrono::nanoseconds heartbeat_age() const;

 private:
  struct StampedCommand {
    hal::ThrusterCommand command;
    std::chrono::nanoseconds stamp{0};
  };

  void run();
  // The I/O thread's pass: a pending arm or disarm request, then the newest command.
  void answer_arm_request(std::uint32_t& answered);
  void serve_command();
  void wake() noexcept;
  void wait_for_work() noexcept;
  // The tick's status (write and read): the gap's, where a gap this machine caused itself (the
  // tick or the I/O thread held off the CPU) that stayed within watchdog_ms, so the controller's
  // own watchdog never saw it, is not held against the bus; and the worse of it and the bus's.
  hal::BusStatus status_for_tick(std::chrono::nanoseconds now);
  // Sends one arm/disarm request and waits at most close_timeout_ms; false on timeout.
  bool request_arm(bool armed, hal::BusStatus& answer);
  void record_ack(std::chrono::nanoseconds now);

  hal::ThrusterBus& bus_;
  const hal::Clock& clock_;
  drivers::BusTimingParams timing_;
  std::string name_;

  LatestSlot<StampedCommand> commands_;           // tick -> I/O thread
  LatestSlot<hal::ThrusterTelemetry> telemetry_;  // I/O thread -> tick
  sem_t wake_{};
  std::atomic<bool> running_{false};
  std::atomic<std::int64_t> last_ack_ns_{0};
  std::atomic<std::int64_t> last_wake_ns_{0};   // the I/O thread's last pass (every <= 20 ms)
  std::atomic<std::int64_t> busy_since_ns_{0};  // a bus call under way since; 0: none
  // The tick's own (write and read): the gap between its last two writes, and the gap's story.
  std::chrono::nanoseconds prev_write_{0};
  std::chrono::nanoseconds tick_gap_{0};
  bool reason_is_gap_ = false;
  std::array<char, 192> gap_reason_{};
  std::atomic<int> bus_status_{static_cast<int>(hal::BusStatus::ok)};
  // Arm requests: the caller sets the value, then bumps the sequence; the thread answers it.
  std::atomic<bool> arm_value_{false};
  std::atomic<std::uint32_t> arm_requested_{0};
  std::atomic<std::uint32_t> arm_answered_{0};
  std::atomic<int> arm_status_{static_cast<int>(hal::BusStatus::ok)};
  hal::ThrusterTelemetry last_telemetry_;  // the tick's copy when nothing new arrived

  // The I/O thread's own: a command went unanswered (reads only until the peer answers), and
  // telemetry reads deferred behind newer commands.
  bool probing_ = false;
  int reads_skipped_ = 0;
  std::thread thread_;
  BusIoStats stats_;  // the I/O thread's own until it is joined
  bool opened_ = false;
  bool closed_ = false;
  bool safe_acknowledged_ = false;
};

}  // namespace rovctl::app
