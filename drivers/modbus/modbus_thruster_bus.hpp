// ThrusterBus on Modbus (RTU over RS-485, or TCP) with libmodbus, speaking rovctl's register map
// (deploy/modbus-register-map.md): commands in permille, a heartbeat and an armed flag.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "drivers/modbus/modbus_params.hpp"
#include "hal/interfaces/thruster_bus.hpp"

struct _modbus;  // libmodbus context (modbus_t), kept out of this header

namespace rovctl::drivers {

// The register map, shared with the thruster controller's firmware.
namespace modbus_map {
constexpr int kCommandRegister = 0;     // holding 0-7: int16 permille of full thrust, -1000..1000
constexpr int kHeartbeatRegister = 16;  // holding 16: +1 every tick; a 200 ms stall stops thrusters
constexpr int kArmedRegister = 17;      // holding 17: 1 armed, 0 disarmed
constexpr int kSpeedRegister = 0;       // input 0-7: int16 rpm
constexpr int kFaultRegister = 8;       // input 8-15: fault flags
constexpr int kChannels = 8;
}  // namespace modbus_map

// Thrust fraction in [-1, 1] to permille, saturated; NaN is neutral.
std::int16_t thrust_permille(double thrust_fraction);

// Answer times of requests, 1 ms bins; the last bin holds everything from 63 ms on.
constexpr std::size_t kLatencyBins = 64;

struct ModbusCounters {
  std::uint64_t transactions = 0;  // requests answered
  std::uint64_t late = 0;          // of those, answered after response_timeout_ms
  std::uint64_t errors = 0;        // failed attempts (timeouts, bad answers, broken link)
  std::uint64_t failed_ticks = 0;  // write()/read() calls that failed after all retries
  int consecutive_failures = 0;
  std::array<std::uint32_t, kLatencyBins> latency_ms{};  // answered requests by answer time
  std::string last_error;  // set at start-up and on failure only, never on the per-tick path
};

// One line for the log: requests answered, their answer times (p50 / p99 / max, 1 ms bins) and
// how many came after response_timeout_ms, failed attempts and failed ticks.
std::string summary(const ModbusCounters& counters, int response_timeout_ms);

class ModbusThrusterBus final : public hal::ThrusterBus {
 public:
  // Channel i of a ThrusterCommand goes to holding register i; `thruster_count` <= 8.
  ModbusThrusterBus(const ModbusParams& params, std::size_t thruster_count);
  ~ModbusThrusterBus() override;
  ModbusThrusterBus(const ModbusThrusterBus&) = delete;
  ModbusThrusterBus& operator=(const ModbusThrusterBus&) = delete;

  bool open(std::string& error) override;
  hal::BusStatus arm(bool armed) override;
  hal::BusStatus write(const hal::ThrusterCommand& command) override;
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override;
  void close() override;
  std::string name() const override;

  const ModbusCounters& counters() const { return counters_; }
  std::uint16_t heartbeat() const { return heartbeat_; }
  bool armed() const { return armed_; }

 private:
  enum class Op { write_commands, write_heartbeat, write_armed, read_inputs };
  // One request, re-sent up to `retries` times while unanswered; false once every attempt failed.
  bool transact(Op op, std::uint16_t value = 0, int retries = -1);
  bool attempt(Op op, std::uint16_t value);
  bool write_neutral();
  hal::BusStatus finish_tick(bool ok);

  ModbusParams params_;
  std::chrono::nanoseconds late_after_{0};
  std::size_t thruster_count_;
  std::string name_;
  _modbus* ctx_ = nullptr;
  bool connected_ = false;
  bool armed_ = false;
  std::uint16_t heartbeat_ = 0;
  std::array<std::uint16_t, modbus_map::kChannels> command_registers_{};
  std::array<std::uint16_t, 2 * modbus_map::kChannels> input_registers_{};
  hal::ThrusterTelemetry telemetry_;
  ModbusCounters counters_;
};

}  // namespace rovctl::drivers
