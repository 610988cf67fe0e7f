// The mock ArduSub's MAVLink face: a loopback UDP socket on an ephemeral port that takes what a
// ground station sends ArduSub (MANUAL_CONTROL, ARM_DISARM, SET_MESSAGE_INTERVAL), answers
// COMMAND_ACK and streams HEARTBEAT, ATTITUDE_QUATERNION, SCALED_PRESSURE2 and SYS_STATUS from the
// simulated vehicle. Stepped by its caller on the simulation's clock, never by a thread of its own.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <string>

#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"
#include "hal/interfaces/clock.hpp"
#include "hal/mock/mock_ardusub.hpp"

namespace rovctl::app {

struct MockArdusubEndpointCounters {
  std::uint64_t manual_control = 0;  // taken (from the GCS id, aimed at us)
  std::uint64_t rc_override = 0;     // RC_CHANNELS_OVERRIDE taken (the same rule)
  std::uint64_t ignored = 0;         // from another system id or aimed at another vehicle
  std::uint64_t commands = 0;        // COMMAND_LONG answered with a COMMAND_ACK
  std::uint64_t heartbeats_sent = 0;
  std::uint64_t attitude_sent = 0;    // ATTITUDE_QUATERNION
  std::uint64_t pressure_sent = 0;    // SCALED_PRESSURE2
  std::uint64_t sys_status_sent = 0;  // SYS_STATUS
};

class MockArdusubEndpoint {
 public:
  // ArduSub as system `system_id` (component 1), obeying ground station `gcs_system_id` only.
  MockArdusubEndpoint(hal::mock::MockArdusub& vehicle, const hal::Clock& clock, int gcs_system_id,
                      int system_id);

  // Binds 127.0.0.1 on a port the kernel picks; false and a message on failure.
  bool open(std::string& error);
  std::uint16_t port() const { return link_.local_port(); }

  // One step at the clock's now: takes everything that arrived, runs the vehicle's loop once,
  // then sends every stream and the HEARTBEAT that is due. No allocation.
  void service();

  // The requested interval of a streamed message (SET_MESSAGE_INTERVAL); negative: not streamed.
  std::chrono::nanoseconds interval(std::uint32_t message_id) const;
  const MockArdusubEndpointCounters& counters() const { return counters_; }
  // Frames the sensors' side of the bus should have taken by now (attitude, pressure, status).
  std::uint64_t sensor_frames_sent() const {
    return counters_.attitude_sent + counters_.pressure_sent + counters_.sys_status_sent;
  }

 private:
  struct Stream {
    std::uint32_t message_id = 0;
    std::chrono::nanoseconds interval{-1};
    std::chrono::nanoseconds next_due{0};
  };
  void take(const drivers::mavlink::Frame& f, std::chrono::nanoseconds now);
  void answer(const drivers::mavlink::CommandLong& c, std::uint8_t result, std::uint8_t to_system,
              std::uint8_t to_component);
  void send_stream(std::uint32_t message_id, std::chrono::nanoseconds now);
  template <typename Message>
  void send(const Message& m);

  hal::mock::MockArdusub& vehicle_;
  const hal::Clock& clock_;
  int gcs_system_id_;
  int system_id_;
  drivers::mavlink::MavlinkUdpLink link_;
  drivers::mavlink::FrameWriter writer_;
  std::array<std::uint8_t, drivers::mavlink::kMaxFrameBytes> frame_{};
  std::array<Stream, 3> streams_{};
  std::chrono::nanoseconds next_heartbeat_{0};
  MockArdusubEndpointCounters counters_;
};

}  // namespace rovctl::app
