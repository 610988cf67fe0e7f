// ThrusterBus on DroneCAN ESCs over SocketCAN: uavcan.equipment.esc.RawCommand out (channel i =
// ESC index i), uavcan.equipment.esc.Status in. The command stream itself is the heartbeat: ESCs
// stop their motors when RawCommand stops arriving.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include "drivers/socketcan/can_socket.hpp"
#include "drivers/socketcan/dronecan_codec.hpp"
#include "drivers/socketcan/dronecan_params.hpp"
#include "hal/interfaces/thruster_bus.hpp"

namespace rovctl::drivers {

// Telemetry fault flags of the DroneCAN bus.
namespace dronecan_fault {
constexpr std::uint16_t kStale = 1U << 0;       // no esc.Status within status_timeout_ms
constexpr std::uint16_t kErrorCount = 1U << 1;  // the ESC's error_count rose since its last Status
}  // namespace dronecan_fault

struct DronecanCounters {
  std::uint64_t transfers_sent = 0;
  std::uint64_t failed_ticks = 0;
  int consecutive_failures = 0;
  std::uint64_t status_received = 0;
  std::uint64_t status_crc_errors = 0;
  std::uint64_t status_toggle_errors = 0;
  std::uint64_t status_missed_starts = 0;
};

class DronecanThrusterBus final : public hal::ThrusterBus {
 public:
  DronecanThrusterBus(const DronecanParams& params, std::size_t thruster_count);
  // Over an already open descriptor (tests: one end of a socketpair); open() keeps it.
  DronecanThrusterBus(const DronecanParams& params, std::size_t thruster_count, CanSocket socket);
  ~DronecanThrusterBus() override;
  DronecanThrusterBus(const DronecanThrusterBus&) = delete;
  DronecanThrusterBus& operator=(const DronecanThrusterBus&) = delete;

  bool open(std::string& error) override;
  hal::BusStatus arm(bool armed) override;
  hal::BusStatus write(const hal::ThrusterCommand& command) override;
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override;
  void close() override;
  std::string name() const override;

  DronecanCounters counters() const;
  const CanErrorCounters& can_counters() const { return socket_.counters(); }
  bool armed() const { return armed_; }

 private:
  bool send_commands(const hal::ThrusterCommand* command);
  hal::BusStatus finish_tick(bool ok);

  DronecanParams params_;
  std::size_t thruster_count_;
  CanSocket socket_;
  bool adopted_ = false;
  bool opened_ = false;
  bool armed_ = false;
  std::uint8_t transfer_id_ = 0;
  std::uint32_t command_can_id_ = 0;
  dronecan::TransferReassembler status_rx_;
  std::array<std::chrono::steady_clock::time_point, hal::kMaxThrusters> status_time_{};
  std::array<bool, hal::kMaxThrusters> status_seen_{};
  std::array<std::uint32_t, hal::kMaxThrusters> esc_error_count_{};
  hal::ThrusterTelemetry telemetry_;
  DronecanCounters counters_;
};

}  // namespace rovctl::drivers
