// ThrusterBus: the interface every thruster backend (Modbus, DroneCAN, mock) implements.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace rovctl::hal {

constexpr std::size_t kMaxThrusters = 8;

// Commands as a fraction of full thrust in [-1, 1] (positive = the thruster's positive
// direction); backends convert to their wire units (permille, int14, ...).
struct ThrusterCommand {
  std::array<double, kMaxThrusters> thrust_fraction{};
  std::size_t count = 0;
};

struct ThrusterTelemetry {
  std::array<double, kMaxThrusters> speed_rpm{};
  std::array<std::uint16_t, kMaxThrusters> fault_flags{};
  std::size_t count = 0;
  bool valid = false;
};

enum class BusStatus { ok, degraded, fault };
const char* to_string(BusStatus s);

class ThrusterBus {
 public:
  virtual ~ThrusterBus() = default;
  // Opens the bus and commands neutral; false and `error` (naming the device) on failure.
  virtual bool open(std::string& error) = 0;
  // Arms or disarms. Disarming commands neutral first.
  virtual BusStatus arm(bool armed) = 0;
  // One tick's commands, with the heartbeat. Disarmed buses send neutral whatever is asked.
  virtual BusStatus write(const ThrusterCommand& command) = 0;
  // The latest telemetry the controllers reported (no blocking I/O beyond the bus timeout).
  virtual BusStatus read(ThrusterTelemetry& telemetry) = 0;
  // Neutral, disarm and release the device; safe to call more than once.
  virtual void close() = 0;
  virtual std::string name() const = 0;
  // Why the bus last reported `fault`, for the log and the ground station: a static string, or
  // null when the bus does not tell its faults apart. Safe to call from the tick.
  virtual const char* fault_reason() const { return nullptr; }
};

}  // namespace rovctl::hal
