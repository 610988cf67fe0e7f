// MockThrusterBus: the ThrusterBus of the simulation. Commands reach the world's thruster model
// as an ESC bus would deliver them; arming, neutral when disarmed, and injectable faults (open
// failure, bus timeouts from a given time). Records the last commands for tests.
#pragma once

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
  FaultInjection& faults() { return faults_; }

 private:
  bool timed_out() const;

  SimulatedWorld& world_;
  FaultInjection faults_;
  bool open_ = false;
  bool armed_ = false;
  ThrusterCommand last_command_{};
  std::uint64_t write_count_ = 0;
  std::uint64_t non_finite_count_ = 0;
};

}  // namespace rovctl::hal::mock
