// DroneCAN thruster bus: one RawCommand transfer per tick (neutral while disarmed), esc.Status
// reassembled from whatever the ESCs publish; bus-off or N failed ticks in a row is a fault.
#include "drivers/socketcan/dronecan_thruster_bus.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace rovctl::drivers {

DronecanThrusterBus::DronecanThrusterBus(const DronecanParams& params, std::size_t thruster_count)
    : params_(params),
      thruster_count_(std::min<std::size_t>(thruster_count, hal::kMaxThrusters)),
      status_rx_(dronecan::kStatusId, dronecan::kStatusSignature) {
  command_can_id_ =
      dronecan::message_can_id(params_.priority, dronecan::kRawCommandId, params_.node_id);
}

DronecanThrusterBus::DronecanThrusterBus(const DronecanParams& params, std::size_t thruster_count,
                                         CanSocket socket)
    : DronecanThrusterBus(params, thruster_count) {
  socket_ = std::move(socket);
  adopted_ = socket_.is_open();
}

DronecanThrusterBus::~DronecanThrusterBus() { close(); }

std::string DronecanThrusterBus::name() const {
  return "dronecan " + (adopted_ ? socket_.label() : params_.interface) + " node " +
         std::to_string(params_.node_id);
}

bool DronecanThrusterBus::open(std::string& error) {
  if (thruster_count_ == 0) {
    error = name() + ": no thrusters to drive";
    return false;
  }
  if (!socket_.is_open() && !socket_.open(params_.interface, error)) return false;
  opened_ = true;
  armed_ = false;
  status_seen_.fill(false);
  if (!send_commands(nullptr)) {
    error = name() + ": cannot send the neutral command: " + std::strerror(socket_.last_errno());
    close();
    return false;
  }
  return true;
}

bool DronecanThrusterBus::send_commands(const hal::ThrusterCommand* command) {
  std::array<std::int16_t, hal::kMaxThrusters> raw{};
  for (std::size_t i = 0; i < thruster_count_; ++i) {
    const bool drive = armed_ && command != nullptr && i < command->count;
    raw[i] = drive ? dronecan::raw_command_from_fraction(command->thrust_fraction[i]) : 0;
  }
  std::array<std::uint8_t, dronecan::kRawCommandMaxBytes> payload{};
  const std::size_t len = dronecan::encode_raw_command({raw.data(), thruster_count_}, payload);
  std::array<dronecan::CanFrame, 6> frames{};
  const std::size_t n = dronecan::make_transfer_frames(
      command_can_id_, dronecan::kRawCommandSignature, {payload.data(), len}, transfer_id_, frames);
  transfer_id_ = static_cast<std::uint8_t>((transfer_id_ + 1) & 0x1F);
  for (std::size_t i = 0; i < n; ++i) {
    if (socket_.send(frames[i]) != CanSocket::Io::ok) return false;
  }
  ++counters_.transfers_sent;
  return true;
}

hal::BusStatus DronecanThrusterBus::finish_tick(bool ok) {
  if (ok) {
    counters_.consecutive_failures = 0;
  } else {
    ++counters_.failed_ticks;
    ++counters_.consecutive_failures;
  }
  if (socket_.bus_off() || counters_.consecutive_failures >= params_.max_consecutive_failures) {
    return hal::BusStatus::fault;
  }
  return ok ? hal::BusStatus::ok : hal::BusStatus::degraded;
}

hal::BusStatus DronecanThrusterBus::arm(bool armed) {
  if (!opened_) return hal::BusStatus::fault;
  // RawCommand has no armed flag: arming is ours, a disarmed bus streams neutral. Either way
  // the next transfer is neutral, so arming never jumps to a stale command.
  armed_ = armed;
  return finish_tick(send_commands(nullptr));
}

hal::BusStatus DronecanThrusterBus::write(const hal::ThrusterCommand& command) {
  if (!opened_) return hal::BusStatus::fault;
  return finish_tick(send_commands(&command));
}

hal::BusStatus DronecanThrusterBus::read(hal::ThrusterTelemetry& telemetry) {
  if (!opened_) {
    telemetry = telemetry_;
    telemetry.valid = false;
    return hal::BusStatus::fault;
  }
  const auto now = std::chrono::steady_clock::now();
  bool io_ok = true;
  // Bounded drain: a babbling bus cannot hold the tick.
  for (int i = 0; i < 256; ++i) {
    dronecan::CanFrame frame;
    const CanSocket::Io r = socket_.receive(frame);
    if (r == CanSocket::Io::would_block) break;
    if (r == CanSocket::Io::error) {
      io_ok = false;
      break;
    }
    if (!status_rx_.accept(frame)) continue;
    dronecan::EscStatus s;
    if (!dronecan::decode_status(status_rx_.payload(), s)) continue;
    ++counters_.status_received;
    if (s.esc_index >= thruster_count_) continue;
    const std::size_t ch = s.esc_index;
    telemetry_.speed_rpm[ch] = s.rpm;
    telemetry_.fault_flags[ch] = (status_seen_[ch] && s.error_count > esc_error_count_[ch])
                                     ? dronecan_fault::kErrorCount
                                     : 0;
    esc_error_count_[ch] = s.error_count;
    status_time_[ch] = now;
    status_seen_[ch] = true;
  }
  telemetry_.count = thruster_count_;
  bool all_fresh = true;
  const auto timeout = std::chrono::milliseconds(params_.status_timeout_ms);
  for (std::size_t ch = 0; ch < thruster_count_; ++ch) {
    const bool fresh = status_seen_[ch] && now - status_time_[ch] <= timeout;
    if (fresh) {
      telemetry_.fault_flags[ch] =
          static_cast<std::uint16_t>(telemetry_.fault_flags[ch] & ~dronecan_fault::kStale);
    } else {
      telemetry_.fault_flags[ch] =
          static_cast<std::uint16_t>(telemetry_.fault_flags[ch] | dronecan_fault::kStale);
    }
    all_fresh = all_fresh && fresh;
  }
  telemetry_.valid = all_fresh;
  telemetry = telemetry_;
  if (socket_.bus_off()) return hal::BusStatus::fault;
  if (!io_ok) return hal::BusStatus::degraded;
  return all_fresh ? hal::BusStatus::ok : hal::BusStatus::degraded;
}

DronecanCounters DronecanThrusterBus::counters() const {
  DronecanCounters c = counters_;
  c.status_crc_errors = status_rx_.crc_errors;
  c.status_toggle_errors = status_rx_.toggle_errors;
  c.status_missed_starts = status_rx_.missed_starts;
  return c;
}

void DronecanThrusterBus::close() {
  if (opened_ && socket_.is_open()) {
    armed_ = false;
    (void)send_commands(nullptr);  // best effort; ESCs also stop when the stream stops
  }
  opened_ = false;
  armed_ = false;
  socket_.close();
}

}  // namespace rovctl::drivers
