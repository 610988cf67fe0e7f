// A fake ArduSub for tests: a thread on loopback UDP (or the leader side of a pseudo-terminal, as
// a serial ArduSub) speaking MAVLink through rovctl's codec, beating, acknowledging ARM_DISARM and
// streaming what it is told to.
#pragma once

#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"

namespace rovctl::drivers::testing {

using namespace std::chrono_literals;
namespace mav = mavlink;

struct Received {
  mav::FrameHeader header;
  mav::ManualControl manual;
  mav::CommandLong command;
  mav::RcChannelsOverride rc_override;
  bool is_manual = false;
  bool is_rc_override = false;
  bool is_command = false;
  bool is_heartbeat = false;
};

// ArduSub as far as the bus sees it: HEARTBEAT every heartbeat_period, ACKs ARM_DISARM (unless
// told to refuse), reports what it was told to report.
class FakeArduSub {
 public:
  FakeArduSub() {
    std::string error;
    mav::UdpEndpoint e;
    e.address = "127.0.0.1";
    e.port = 0;
    if (!link_.open(e, error)) throw std::runtime_error(error);
    thread_ = std::thread([this] { run(); });
  }
  // On a serial line: `leader_fd` is the leader side of a pseudo-terminal (raw, non-blocking),
  // whose follower the bus opens as `serial:PATH:BAUD`. Not owned.
  explicit FakeArduSub(int leader_fd) : serial_fd_(leader_fd) {
    thread_ = std::thread([this] { run(); });
  }
  ~FakeArduSub() {
    stop_ = true;
    thread_.join();
  }
  std::uint16_t port() const { return link_.local_port(); }

  std::atomic<bool> beating{true};
  std::atomic<bool> armed{false};
  std::atomic<std::uint32_t> mode{0};
  std::atomic<bool> refuse_arm{false};   // with a "PreArm: Check mag field" STATUSTEXT first
  std::atomic<bool> refuse_mode{false};  // DO_SET_MODE answered FAILED, the mode unchanged
  std::atomic<bool> streaming{false};    // ATTITUDE_QUATERNION and SCALED_PRESSURE2 with each beat
  std::atomic<bool> attitude{true};      // while streaming: ATTITUDE_QUATERNION among them

  std::vector<Received> received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  // Waits (the test, not the bus) until `pred` holds on what arrived.
  bool wait_for(const std::function<bool(const std::vector<Received>&)>& pred,
                std::chrono::milliseconds limit = 5000ms) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      if (pred(received())) return true;
      std::this_thread::sleep_for(2ms);
    }
    return false;
  }

 private:
  template <typename M>
  void send(const M& m) {
    std::array<std::uint8_t, mav::kMaxFrameBytes> out{};
    const std::size_t n = mav::write_message(writer_, m, out);
    if (serial_fd_ >= 0) {
      (void)::write(serial_fd_, out.data(), n);
    } else {
      (void)link_.send(std::span<const std::uint8_t>(out.data(), n));
    }
  }
  // The reason ArduSub gives for refusing an arm (MAV_SEVERITY_CRITICAL, as its pre-arm texts).
  void send_prearm_failure() {
    mav::StatusText t;
    t.severity = 2;
    mav::set_text(t.text, "PreArm: Check mag field");
    send(t);
  }
  bool receive(mav::Frame& f) {
    if (serial_fd_ < 0) return link_.receive(f) == mav::MavlinkUdpLink::Io::ok;
    while (!parser_.next(f)) {
      std::array<std::uint8_t, 256> in{};
      const ssize_t n = ::read(serial_fd_, in.data(), in.size());
      if (n <= 0) return false;
      parser_.feed(std::span<const std::uint8_t>(in.data(), static_cast<std::size_t>(n)));
    }
    return true;
  }
  // A serial line has its peer from the start; UDP once the bus has spoken.
  bool has_peer() const { return serial_fd_ >= 0 || link_.has_peer(); }
  void run() {
    auto next_beat = std::chrono::steady_clock::now();
    while (!stop_) {
      mav::Frame f;
      while (receive(f)) {
        Received r;
        r.header = f.header;
        mav::Heartbeat hb;
        r.is_manual = mav::unpack(f, r.manual);
        r.is_command = mav::unpack(f, r.command);
        r.is_rc_override = mav::unpack(f, r.rc_override);
        r.is_heartbeat = mav::unpack(f, hb);
        if (r.is_command && r.command.command == mav::kCmdRunPrearmChecks) {
          mav::CommandAck ack;
          ack.command = r.command.command;
          send(ack);
          if (refuse_arm) send_prearm_failure();
        }
        if (r.is_command && r.command.command == mav::kCmdDoSetMode) {
          if (!refuse_mode) mode = static_cast<std::uint32_t>(r.command.params[1]);
          mav::CommandAck ack;
          ack.command = r.command.command;
          ack.result = refuse_mode ? 4 : 0;
          send(ack);
        }
        if (r.is_command && r.command.command == mav::kCmdComponentArmDisarm) {
          const bool accept = !refuse_arm || r.command.params[0] == 0.0F;
          if (accept) armed = r.command.params[0] == 1.0F;
          if (!accept) send_prearm_failure();
          mav::CommandAck ack;
          ack.command = r.command.command;
          ack.result = accept ? 0 : 4;  // MAV_RESULT_ACCEPTED / FAILED
          ack.target_system = f.header.system_id;
          ack.target_component = f.header.component_id;
          send(ack);
        }
        std::lock_guard<std::mutex> lock(mutex_);
        received_.push_back(r);
      }
      const auto now = std::chrono::steady_clock::now();
      if (beating && has_peer() && now >= next_beat) {
        mav::Heartbeat hb;
        hb.type = 12;      // MAV_TYPE_SUBMARINE
        hb.autopilot = 3;  // MAV_AUTOPILOT_ARDUPILOTMEGA
        hb.base_mode = armed ? mav::kModeFlagSafetyArmed : 0;
        hb.custom_mode = mode;
        send(hb);
        if (streaming && attitude) {
          mav::AttitudeQuaternion a;
          a.q_ned_body = {0.0F, 1.0F, 0.0F, 0.0F};  // upside down about x
          send(a);
        }
        if (streaming) {
          mav::ScaledPressure2 p;
          p.press_abs_hpa = 1113.25F;
          send(p);
        }
        next_beat = now + 20ms;
      }
      std::this_thread::sleep_for(1ms);
    }
  }

  mav::MavlinkUdpLink link_;
  int serial_fd_ = -1;
  mav::FrameParser parser_;
  mav::FrameWriter writer_{1, 1};
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex mutex_;
  std::vector<Received> received_;
};

}  // namespace rovctl::drivers::testing
