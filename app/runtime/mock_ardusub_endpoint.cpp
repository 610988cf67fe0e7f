// MAVLink in and out of the mock ArduSub, in step with the simulated clock.
#include "app/runtime/mock_ardusub_endpoint.hpp"

#include <cmath>

namespace rovctl::app {

namespace mav = drivers::mavlink;

namespace {
constexpr std::uint8_t kMavTypeSubmarine = 12;
constexpr std::uint8_t kMavAutopilotArdupilot = 3;
constexpr std::uint8_t kModeFlagCustomModeEnabled = 0x01;
constexpr std::uint8_t kMavStateActive = 4;
constexpr std::uint8_t kMavStateCritical = 5;
constexpr std::uint8_t kMavResultAccepted = 0;
constexpr std::uint8_t kMavResultUnsupported = 3;
constexpr std::uint8_t kComponentAutopilot = 1;
// A babbling peer cannot hold the simulation: at most this many frames per step.
constexpr int kMaxFramesPerService = 256;
}  // namespace

MockArdusubEndpoint::MockArdusubEndpoint(hal::mock::MockArdusub& vehicle, const hal::Clock& clock,
                                         int gcs_system_id, int system_id)
    : vehicle_(vehicle),
      clock_(clock),
      gcs_system_id_(gcs_system_id),
      system_id_(system_id),
      writer_(static_cast<std::uint8_t>(system_id), kComponentAutopilot) {
  // Not streamed until asked: ArduSub's default streams lack ATTITUDE_QUATERNION, and the bus
  // asks for all three at its own interval.
  streams_[0].message_id = mav::AttitudeQuaternion::kId;
  streams_[1].message_id = mav::ScaledPressure2::kId;
  streams_[2].message_id = mav::SysStatus::kId;
}

bool MockArdusubEndpoint::open(std::string& error) {
  mav::UdpEndpoint e;
  e.mode = mav::UdpEndpoint::Mode::listen;
  e.address = "127.0.0.1";
  e.port = 0;  // ephemeral: parallel trials never collide
  return link_.open(e, error);
}

std::chrono::nanoseconds MockArdusubEndpoint::interval(std::uint32_t message_id) const {
  for (const Stream& s : streams_) {
    if (s.message_id == message_id) return s.interval;
  }
  return std::chrono::nanoseconds{-1};
}

template <typename Message>
void MockArdusubEndpoint::send(const Message& m) {
  const std::size_t n = mav::write_message(writer_, m, frame_);
  if (n > 0) (void)link_.send(std::span<const std::uint8_t>(frame_.data(), n));
}

void MockArdusubEndpoint::answer(const mav::CommandLong& c, std::uint8_t result,
                                 std::uint8_t to_system, std::uint8_t to_component) {
  mav::CommandAck ack;
  ack.command = c.command;
  ack.result = result;
  ack.target_system = to_system;
  ack.target_component = to_component;
  send(ack);
  ++counters_.commands;
}

void MockArdusubEndpoint::take(const mav::Frame& f, std::chrono::nanoseconds now) {
  mav::ManualControl mc;
  mav::RcChannelsOverride rc;
  mav::CommandLong c;
  if (mav::unpack(f, rc)) {
    if (f.header.system_id != gcs_system_id_ || rc.target_system != system_id_) {
      ++counters_.ignored;
      return;
    }
    ++counters_.rc_override;
    vehicle_.rc_override(rc.channels_us, now);
  } else if (mav::unpack(f, mc)) {
    // ArduSub takes pilot input only from SYSID_MYGCS and only when aimed at itself.
    if (f.header.system_id != gcs_system_id_ || mc.target != system_id_) {
      ++counters_.ignored;
      return;
    }
    ++counters_.manual_control;
    vehicle_.pilot_input({mc.x, mc.y, mc.z, mc.r}, now);
  } else if (mav::unpack(f, c)) {
    if (c.target_system != system_id_) {
      ++counters_.ignored;
      return;
    }
    std::uint8_t result = kMavResultUnsupported;
    if (c.command == mav::kCmdComponentArmDisarm) {
      result = vehicle_.arm(c.params[0] == 1.0F, now) ? kMavResultAccepted : 4;
    } else if (c.command == mav::kCmdDoSetMode && c.params[0] == mav::kModeFlagCustomModeEnabled) {
      vehicle_.set_mode(static_cast<std::uint32_t>(std::lround(c.params[1])));
      result = kMavResultAccepted;
    } else if (c.command == mav::kCmdSetMessageInterval) {
      const auto id = static_cast<std::uint32_t>(std::lround(c.params[0]));
      const float us = c.params[1];
      for (Stream& s : streams_) {
        if (s.message_id != id) continue;
        // -1 stops a stream; 0 restores its default, which for these is off in the mock.
        s.interval = us > 0.0F ? std::chrono::nanoseconds(std::llround(us * 1000.0))
                               : std::chrono::nanoseconds{-1};
        s.next_due = now;
        result = kMavResultAccepted;
      }
    }
    answer(c, result, f.header.system_id, f.header.component_id);
  }
}

void MockArdusubEndpoint::send_stream(std::uint32_t message_id, std::chrono::nanoseconds now) {
  const auto boot_ms = static_cast<std::uint32_t>(now.count() / 1'000'000);
  if (message_id == mav::AttitudeQuaternion::kId) {
    const Eigen::Quaterniond q = vehicle_.q_ned_body();
    const Eigen::Vector3d w = vehicle_.omega_body_radps();
    mav::AttitudeQuaternion a;
    a.time_boot_ms = boot_ms;
    a.q_ned_body = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
                    static_cast<float>(q.z())};
    a.rollspeed_rad_s = static_cast<float>(w.x());
    a.pitchspeed_rad_s = static_cast<float>(w.y());
    a.yawspeed_rad_s = static_cast<float>(w.z());
    send(a);
    ++counters_.attitude_sent;
  } else if (message_id == mav::ScaledPressure2::kId) {
    mav::ScaledPressure2 p;
    p.time_boot_ms = boot_ms;
    p.press_abs_hpa = static_cast<float>(vehicle_.pressure_hpa());
    p.temperature_cdegc = 1500;
    send(p);
    ++counters_.pressure_sent;
  } else if (message_id == mav::SysStatus::kId) {
    mav::SysStatus s;
    s.voltage_battery_mv =
        static_cast<std::uint16_t>(std::lround(vehicle_.battery_voltage_v() * 1000.0));
    s.current_battery_ca = -1;
    s.battery_remaining_pct = static_cast<std::int8_t>(vehicle_.battery_remaining_pct());
    send(s);
    ++counters_.sys_status_sent;
  }
}

void MockArdusubEndpoint::service() {
  const std::chrono::nanoseconds now = clock_.now();
  for (int i = 0; i < kMaxFramesPerService; ++i) {
    mav::Frame f;
    if (link_.receive(f) != mav::MavlinkUdpLink::Io::ok) break;
    take(f, now);
  }
  vehicle_.update(now);
  if (!link_.has_peer()) return;  // nobody has spoken to us yet
  for (Stream& s : streams_) {
    if (s.interval.count() <= 0 || now < s.next_due) continue;
    send_stream(s.message_id, now);
    // On the grid of the interval; after a gap longer than it, one message and back on the grid.
    s.next_due += s.interval * ((now - s.next_due) / s.interval + 1);
  }
  if (now >= next_heartbeat_) {
    mav::Heartbeat hb;
    hb.type = kMavTypeSubmarine;
    hb.autopilot = kMavAutopilotArdupilot;
    hb.base_mode = static_cast<std::uint8_t>(kModeFlagCustomModeEnabled |
                                             (vehicle_.armed() ? mav::kModeFlagSafetyArmed : 0));
    hb.custom_mode = vehicle_.mode();
    hb.system_status = vehicle_.pilot_failsafe() ? kMavStateCritical : kMavStateActive;
    send(hb);
    ++counters_.heartbeats_sent;
    const auto period = std::chrono::duration_cast<std::chrono::nanoseconds>(
        std::chrono::duration<double, std::milli>(vehicle_.params().heartbeat_period_ms));
    next_heartbeat_ = now + period;
  }
}

}  // namespace rovctl::app
