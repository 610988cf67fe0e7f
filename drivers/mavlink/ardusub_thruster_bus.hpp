// ThrusterBus on ArduSub over MAVLink (wrench mode): the allocator's fractions leave as one
// MANUAL_CONTROL per command from the GCS id ArduSub obeys, arming is MAV_CMD_COMPONENT_ARM_DISARM
// with its COMMAND_ACK, and ArduSub's HEARTBEAT is the bus's health (link, armed, mode). It owns
// the link, so it also feeds ArduSub's sensors (ArdusubSensors) when they are attached.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/mavlink/ardusub_sensors.hpp"
#include "drivers/mavlink/ardusub_wrench_map.hpp"
#include "drivers/mavlink/mavlink_codec.hpp"
#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::drivers {

// Why the bus reports a fault; none while it does not.
enum class ArdusubFault { none, link_lost, disarmed_under_us, mode_changed, arm_refused };
const char* to_string(ArdusubFault f);

struct ArdusubCounters {
  std::uint64_t manual_control_sent = 0;
  std::uint64_t heartbeats_sent = 0;
  std::uint64_t heartbeats_received = 0;  // from ArduSub (vehicle system and component id)
  std::uint64_t acks_received = 0;
  std::uint64_t send_failures = 0;
};

class ArdusubThrusterBus final : public hal::ThrusterBus {
 public:
  // Throws std::invalid_argument (naming the key) for a link that does not parse or a flight
  // mode ArduSub does not have; config validation reports both earlier with file:line.
  ArdusubThrusterBus(const ArdusubParams& params, const hal::ThrusterLayout& layout);
  ~ArdusubThrusterBus() override;
  ArdusubThrusterBus(const ArdusubThrusterBus&) = delete;
  ArdusubThrusterBus& operator=(const ArdusubThrusterBus&) = delete;

  // Opens the socket and waits (start-up, at most link_timeout_ms) for ArduSub's HEARTBEAT.
  bool open(std::string& error) override;
  // Sends neutral, then ARM_DISARM, and waits at most ack_timeout_ms for its COMMAND_ACK. Runs
  // on the bus I/O thread (BusIoThread), never on the tick. Arming needs the link and the
  // configured flight mode.
  hal::BusStatus arm(bool armed) override;
  // One MANUAL_CONTROL (neutral while disarmed), our HEARTBEAT when due; drains what arrived.
  hal::BusStatus write(const hal::ThrusterCommand& command) override;
  // No per-thruster telemetry through ArduSub: `valid` stays false (health judges nothing).
  hal::BusStatus read(hal::ThrusterTelemetry& telemetry) override;
  void close() override;
  std::string name() const override;

  // Before open(): ArduSub's telemetry goes to `sensors` (which outlives this bus) from the I/O
  // thread that owns the socket, and open() requests its streams (SET_MESSAGE_INTERVAL).
  void attach(ArdusubSensors& sensors) { sensors_ = &sensors; }
  // Before open(): called in place of the poll sleep while open() waits for the first HEARTBEAT
  // and arm() for its COMMAND_ACK, so a peer stepped in the caller's thread (the mock ArduSub of
  // `rovctl sim`, in virtual time) answers there.
  void set_wait_hook(std::function<void()> hook) { wait_hook_ = std::move(hook); }

  std::uint16_t local_port() const { return link_.local_port(); }
  ArdusubFault fault() const;
  const ArdusubCounters& counters() const { return counters_; }
  bool armed() const { return armed_; }
  // The axes of the last MANUAL_CONTROL sent.
  const ArdusubAxes& last_axes() const { return last_axes_; }

 private:
  using Clock = std::chrono::steady_clock;
  void pump();
  void wait_a_little();
  bool send_manual_control(const ArdusubAxes& axes);
  bool send_heartbeat();
  bool send_arm(bool armed, Clock::duration wait);
  template <typename Message>
  bool send(const Message& m);
  hal::BusStatus status();

  bool request_streams();

  ArdusubParams params_;
  ArdusubWrenchMap map_;
  ArdusubSensors* sensors_ = nullptr;
  std::function<void()> wait_hook_;
  mavlink::UdpEndpoint endpoint_;
  int required_mode_ = 0;
  mavlink::MavlinkUdpLink link_;
  mavlink::FrameWriter writer_;
  std::array<std::uint8_t, mavlink::kMaxFrameBytes> frame_{};
  std::size_t thruster_count_ = 0;
  bool opened_ = false;
  bool armed_ = false;
  bool send_failed_ = false;
  ArdusubAxes last_axes_;

  bool heartbeat_seen_ = false;
  Clock::time_point last_heartbeat_{};
  Clock::time_point last_heartbeat_sent_{};
  bool vehicle_armed_ = false;
  std::uint32_t vehicle_mode_ = 0;
  bool disarmed_under_us_ = false;
  bool mode_changed_ = false;
  bool arm_refused_ = false;
  std::uint64_t arm_acks_ = 0;  // COMMAND_ACKs of ARM_DISARM
  std::uint8_t arm_result_ = 0;
  ArdusubCounters counters_;
};

}  // namespace rovctl::drivers
