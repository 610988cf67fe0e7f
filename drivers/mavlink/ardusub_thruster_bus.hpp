// ThrusterBus on ArduSub over MAVLink: the allocator's fractions leave as one MANUAL_CONTROL
// (wrench mode) or one RC_CHANNELS_OVERRIDE (thrusters mode) per command from the GCS id ArduSub
// obeys, arming is MAV_CMD_COMPONENT_ARM_DISARM
// with its COMMAND_ACK, and ArduSub's HEARTBEAT is the bus's health (link, armed, mode). It owns
// the link, so it also feeds ArduSub's sensors (ArdusubSensors) when they are attached.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "drivers/mavlink/ardusub_params.hpp"
#include "drivers/mavlink/ardusub_rc_override_map.hpp"
#include "drivers/mavlink/ardusub_sensors.hpp"
#include "drivers/mavlink/ardusub_wrench_map.hpp"
#include "drivers/mavlink/gcs_status.hpp"
#include "drivers/mavlink/mavlink_codec.hpp"
#include "drivers/mavlink/mavlink_link.hpp"
#include "drivers/mavlink/mavlink_messages.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::drivers {

// Why the bus reports a fault; none while it does not.
enum class ArdusubFault {
  none,
  link_lost,
  stream_silent,
  disarmed_under_us,
  mode_changed,
  arm_refused
};
const char* to_string(ArdusubFault f);

struct ArdusubCounters {
  std::uint64_t manual_control_sent = 0;
  std::uint64_t rc_override_sent = 0;
  std::uint64_t heartbeats_sent = 0;
  std::uint64_t heartbeats_received = 0;  // from ArduSub (vehicle system and component id)
  std::uint64_t attitude_received = 0;    // ATTITUDE_QUATERNION
  std::uint64_t pressure_received = 0;    // SCALED_PRESSURE2
  std::uint64_t sys_status_received = 0;  // SYS_STATUS
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

  // Opens the socket and waits (start-up, at most link_timeout_ms) for ArduSub's HEARTBEAT, then
  // with sensors attached (at most link_timeout_ms more) for their attitude and depth.
  bool open(std::string& error) override;
  // Sends neutral, then ARM_DISARM, and waits at most ack_timeout_ms for its COMMAND_ACK. Runs
  // on the bus I/O thread (BusIoThread), never on the tick. Arming needs the link and the
  // configured flight mode: when ArduSub is in another (it boots in MANUAL) it is asked with
  // DO_SET_MODE first and must show the mode in its HEARTBEAT within ack_timeout_ms. A refusal
  // says why in fault_reason() (ArduSub's COMMAND_ACK result and its "PreArm:" STATUSTEXT).
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

  // After open(), not from the tick (`rovctl check`): ArduSub's parameter `id` by
  // PARAM_REQUEST_READ, answered by PARAM_VALUE; waits ack_timeout_ms per try, 3 tries (UDP);
  // none when ArduSub does not answer.
  std::optional<float> read_parameter(std::string_view id);
  // Send to answer of the last read_parameter() ArduSub answered (the link's round trip).
  std::optional<std::chrono::milliseconds> last_round_trip() const { return round_trip_; }

  // After open(), not from the tick (`rovctl check`): what arrived from ArduSub over `window`,
  // the link drained meanwhile, per second.
  struct ArrivalRates {
    double heartbeat_hz = 0.0;
    double attitude_hz = 0.0;
    double pressure_hz = 0.0;
    double sys_status_hz = 0.0;
  };
  ArrivalRates measure_arrivals(std::chrono::milliseconds window);
  // After open(), not from the tick (`rovctl check`): MAV_CMD_RUN_PREARM_CHECKS, which has ArduSub
  // run the checks arming would and report failures as "PreArm:" STATUSTEXT. The first failure
  // it reported within ack_timeout_ms of its COMMAND_ACK (empty: none); none when it did not
  // acknowledge the command.
  std::optional<std::string> run_prearm_checks();
  // ArduSub's custom_mode in its last HEARTBEAT.
  std::uint32_t vehicle_mode() const { return vehicle_mode_; }

  // rovctl's status to the ground station (null when gcs_status.enabled is false): fed by the
  // tick and the event logger, framed and sent by whichever thread runs this bus's I/O.
  GcsStatus* gcs_status() { return gcs_.get(); }

  std::uint16_t local_port() const { return link_.local_port(); }
  ArdusubFault fault() const;
  // The last fault status() reported, told apart and with its figures ("ArduSub silent: no
  // ATTITUDE_QUATERNION for 260 ms", "ArduSub refused arm: ... PreArm: ...").
  const char* fault_reason() const override {
    return fault_reason_.load(std::memory_order_acquire);
  }
  const ArdusubCounters& counters() const { return counters_; }
  bool armed() const { return armed_; }
  // The axes of the last MANUAL_CONTROL sent (wrench mode).
  const ArdusubAxes& last_axes() const { return last_axes_; }
  // The last RC_CHANNELS_OVERRIDE sent (thrusters mode).
  const mavlink::RcChannelsOverride& last_rc_override() const { return last_rc_override_; }

 private:
  using Clock = std::chrono::steady_clock;
  void pump();
  void wait_a_little();
  bool send_manual_control(const ArdusubAxes& axes);
  bool send_rc_override(const mavlink::RcChannelsOverride& m);
  // The command in the configured mode (neutral while disarmed).
  bool send_command(const hal::ThrusterCommand& command);
  bool send_neutral();
  bool send_heartbeat();
  bool send_arm(bool armed, Clock::duration wait);
  template <typename Message>
  bool send(const Message& m);
  hal::BusStatus status();

  bool request_streams();
  // Asks for the configured flight mode unless ArduSub shows it; true once its HEARTBEAT does.
  bool set_flight_mode();
  // Writes the reason for `f` (with its figures) where fault_reason() points; only on a change.
  void explain(ArdusubFault f, Clock::time_point now);
  void explain_refusal(const char* what);

  ArdusubParams params_;
  bool thrusters_mode_ = false;
  ArdusubWrenchMap map_;
  ArdusubRcOverrideMap rc_map_;
  ArdusubSensors* sensors_ = nullptr;
  std::unique_ptr<GcsStatus> gcs_;
  std::function<void()> wait_hook_;
  mavlink::LinkEndpoint endpoint_;
  int required_mode_ = 0;
  mavlink::MavlinkLink link_;
  mavlink::FrameWriter writer_;
  std::array<std::uint8_t, mavlink::kMaxFrameBytes> frame_{};
  std::size_t thruster_count_ = 0;
  bool opened_ = false;
  bool armed_ = false;
  bool send_failed_ = false;
  ArdusubAxes last_axes_;
  mavlink::RcChannelsOverride last_rc_override_;

  bool heartbeat_seen_ = false;
  Clock::time_point last_heartbeat_{};
  Clock::time_point last_heartbeat_sent_{};
  bool vehicle_armed_ = false;
  std::uint32_t vehicle_mode_ = 0;
  bool disarmed_under_us_ = false;
  bool mode_changed_ = false;
  bool arm_refused_ = false;
  Clock::time_point last_attitude_{};   // ATTITUDE_QUATERNION's last arrival
  std::array<char, 51> prearm_text_{};  // ArduSub's last "PreArm:"/"Arm:" STATUSTEXT
  ArdusubFault explained_ = ArdusubFault::none;
  // Written where status() runs (the bus I/O thread), read by the tick: two buffers, so the one
  // the tick may be reading is never the one being written.
  std::array<std::array<char, 160>, 2> reasons_{};
  std::size_t next_reason_ = 0;
  std::atomic<const char*> fault_reason_{nullptr};
  std::array<char, 16> awaited_param_{};  // read_parameter()'s id while it waits
  bool param_answered_ = false;
  float param_value_ = 0.0F;
  std::optional<std::chrono::milliseconds> round_trip_;
  std::uint64_t arm_acks_ = 0;  // COMMAND_ACKs of ARM_DISARM
  std::uint8_t arm_result_ = 0;
  std::uint64_t mode_acks_ = 0;  // COMMAND_ACKs of DO_SET_MODE
  std::uint8_t mode_result_ = 0;
  bool mode_answered_ = false;  // the last DO_SET_MODE got a COMMAND_ACK
  ArdusubCounters counters_;
};

}  // namespace rovctl::drivers
