// MockThrusterBus: the ThrusterBus of the simulation. Commands reach the world's thruster model
// as an ESC bus would deliver them; arming, neutral when disarmed, and injectable faults (open
// failure, timeouts, a slow peer, an ignored disarm). Records the last commands for tests.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "hal/interfaces/thruster_bus.hpp"
#include "hal/mock/fault_injection.hpp"
#include "hal/mock/simulated_world.hpp"

namespace rovctl::hal::mock {

class MockThrusterBus final : public ThrusterBus {
 public:
  MockThrusterBus(SimulatedWorld& world, const FaultInjection& faults);

  bool open(std::string& error) override;
  BusStatus arm(bool armed) override;
  // Disarmed: neutral is delivered whatever is asked. Non-finite commands are delivered as
  // neutral for that thruster and the write reports `degraded`. No heap allocation.
  BusStatus write(const ThrusterCommand& command) override;
  BusStatus read(ThrusterTelemetry& telemetry) override;
  void close() override;
  std::string name() const override { return "mock thruster bus"; }

  // For tests and fault scenarios.
  bool is_open() const { return open_; }
  bool armed() const { return armed_; }
  const ThrusterCommand& last_command() const { return last_command_; }  // as asked
  std::uint64_t write_count() const { return write_count_; }
  std::uint64_t non_finite_count() const { return non_finite_count_; }
  // Non-zero commands sent to the peer although a neutral one had been written after them (a
  // queue replaying stale commands; the latest-value slot must keep this 0).
  std::uint64_t stale_sent() const { return stale_sent_; }
  // Non-zero commands that took effect after a later neutral one was written: the request
  // already in flight to a slow peer when the loop went neutral.
  std::uint64_t landed_after_neutral() const { return landed_after_neutral_; }
  FaultInjection& faults() { return faults_; }

 private:
  bool timed_out() const;
  // The slow peer (faults.bus_slow_*), as the I/O thread drives a real one: one request in
  // flight, answered bus_latency_ms later; meanwhile only the newest command waits in a slot.
  // Delivers every answer due by `now`.
  void serve(std::chrono::nanoseconds now);
  void deliver(const ThrusterCommand& command, std::chrono::nanoseconds written_at);
  // A request of an earlier tick still unanswered: the peer is behind.
  BusStatus peer_status(std::chrono::nanoseconds now) const;

  SimulatedWorld& world_;
  FaultInjection faults_;
  bool open_ = false;
  bool armed_ = false;
  ThrusterCommand last_command_{};
  std::uint64_t write_count_ = 0;
  std::uint64_t non_finite_count_ = 0;
  std::uint64_t stale_sent_ = 0;
  std::uint64_t landed_after_neutral_ = 0;
  bool in_flight_ = false;
  ThrusterCommand in_flight_command_{};
  std::chrono::nanoseconds in_flight_written_at_{0};
  std::chrono::nanoseconds in_flight_sent_at_{0};
  std::chrono::nanoseconds in_flight_due_{0};
  bool slot_full_ = false;
  ThrusterCommand slot_command_{};
  std::chrono::nanoseconds slot_written_at_{0};
  std::chrono::nanoseconds last_neutral_at_{-1};  // the newest all-zero command written
};

}  // namespace rovctl::hal::mock
