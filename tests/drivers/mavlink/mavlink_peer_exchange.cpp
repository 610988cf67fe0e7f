// rovctl's side of the node-mavlink peer test (mavlink_peer_test.mjs): decodes and checks what
// the peer sends, then sends the same messages for the peer to check. Exit 0 when all matched.
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <type_traits>
#include <variant>
#include <vector>

#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"

namespace mav = rovctl::drivers::mavlink;

namespace {

using AnyMessage =
    std::variant<mav::Heartbeat, mav::SysStatus, mav::ParamRequestRead, mav::ParamValue,
                 mav::AttitudeQuaternion, mav::ManualControl, mav::RcChannelsOverride, mav::VfrHud,
                 mav::CommandLong, mav::CommandAck, mav::ScaledPressure2, mav::NamedValueFloat,
                 mav::StatusText>;

// The same values as MESSAGES in mavlink_peer_test.mjs, in the same order.
std::vector<AnyMessage> exchanged_messages() {
  std::vector<AnyMessage> list;
  list.emplace_back(mav::Heartbeat{19, 12, 3, 0xC1, 4, 3});
  mav::SysStatus sys;
  sys.sensors_present = 0x0001FFFF;
  sys.sensors_enabled = 0x0000FF0F;
  sys.sensors_health = 0x0000F00F;
  sys.load_permille = 250;
  sys.voltage_battery_mv = 15800;
  sys.current_battery_ca = -1234;
  sys.errors_count = {1, 2, 3, 4};
  sys.battery_remaining_pct = 76;
  list.emplace_back(sys);
  mav::ParamRequestRead request;
  request.param_index = -1;
  request.target_system = 1;
  request.target_component = 1;
  mav::set_text(request.param_id, "FS_PILOT_INPUT");
  list.emplace_back(request);
  mav::ParamValue value;
  value.param_value = 3.0F;
  value.param_count = 873;
  value.param_index = 412;
  mav::set_text(value.param_id, "FS_PILOT_TIMEOUT");  // 16 chars: no terminator
  value.param_type = 9;
  list.emplace_back(value);
  mav::AttitudeQuaternion attitude;
  attitude.time_boot_ms = 123456;
  attitude.q_ned_body = {0.5F, -0.5F, 0.5F, 0.5F};
  attitude.rollspeed_rad_s = 0.125F;
  attitude.pitchspeed_rad_s = -0.25F;
  attitude.yawspeed_rad_s = 1.5F;
  list.emplace_back(attitude);
  mav::ManualControl manual;
  manual.x = -1000;
  manual.y = 1000;
  manual.z = 500;
  manual.r = -250;
  manual.target = 1;
  list.emplace_back(manual);
  mav::RcChannelsOverride rc;
  for (std::size_t i = 0; i < 8; ++i) {
    rc.channels_us[i] = static_cast<std::uint16_t>(1100 + 100 * i);
  }
  rc.channels_us[8] = 1500;
  rc.channels_us[9] = 65535;
  rc.target_system = 1;
  rc.target_component = 1;
  list.emplace_back(rc);
  list.emplace_back(mav::VfrHud{0.25F, 0.5F, -12.75F, -0.125F, 271, 40});
  list.emplace_back(mav::arm_disarm(1, 1, true, false));
  list.emplace_back(mav::set_message_interval(1, 1, mav::AttitudeQuaternion::kId, 33333.0F));
  list.emplace_back(mav::CommandAck{400, 0, 0, 0, 255, 190});
  list.emplace_back(mav::ScaledPressure2{123456, 2013.25F, 0.0F, 1234, 0});
  mav::NamedValueFloat named;
  named.time_boot_ms = 654321;
  named.value = -0.375F;
  mav::set_text(named.name, "lat_err_m");
  list.emplace_back(named);
  mav::StatusText text;
  text.severity = 2;
  mav::set_text(text.text, "Leak Detected");
  list.emplace_back(text);
  return list;
}

std::string hex_of(const AnyMessage& m) {
  return std::visit(
      [](const auto& message) {
        mav::Payload payload{};
        const std::size_t n = pack(message, payload);
        std::string s;
        char byte[3];
        for (std::size_t i = 0; i < n; ++i) {
          std::snprintf(byte, sizeof byte, "%02x", payload[i]);
          s += byte;
        }
        return s;
      },
      m);
}

bool is_end_marker(const mav::Frame& f) {
  mav::StatusText t;
  return mav::unpack(f, t) && mav::text_of(t.text) == "END";
}

}  // namespace

int main() {
  using namespace std::chrono_literals;
  mav::MavlinkUdpLink link;
  std::string error;
  if (!link.open(mav::UdpEndpoint{mav::UdpEndpoint::Mode::listen, "127.0.0.1", 0}, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 2;
  }
  for (const mav::MessageInfo& info : mav::message_table()) {
    std::printf("TABLE %s %u %u %u %u\n", info.name, static_cast<unsigned>(info.id),
                static_cast<unsigned>(info.min_length), static_cast<unsigned>(info.max_length),
                static_cast<unsigned>(info.crc_extra));
  }
  std::printf("PORT %u\n", static_cast<unsigned>(link.local_port()));
  std::fflush(stdout);

  const std::vector<AnyMessage> expected = exchanged_messages();
  int failures = 0;
  const auto fail = [&](const std::string& what) {
    std::printf("FAIL %s\n", what.c_str());
    ++failures;
  };

  // The peer's messages, in order, then its END marker.
  std::size_t received = 0;
  bool ended = false;
  int last_sequence = -1;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (!ended && std::chrono::steady_clock::now() < deadline) {
    mav::Frame f;
    const mav::MavlinkUdpLink::Io io = link.receive(f);
    if (io == mav::MavlinkUdpLink::Io::would_block) {
      std::this_thread::sleep_for(1ms);
      continue;
    }
    if (io != mav::MavlinkUdpLink::Io::ok) {
      fail("receive error");
      break;
    }
    if (f.header.system_id != 1 || f.header.component_id != 1) {
      fail("frame " + std::to_string(received) + " from " + std::to_string(f.header.system_id) +
           "/" + std::to_string(f.header.component_id) + ", expected 1/1");
    }
    if (last_sequence >= 0 && f.header.sequence != ((last_sequence + 1) & 0xFF)) {
      fail("sequence " + std::to_string(f.header.sequence) + " after " +
           std::to_string(last_sequence));
    }
    last_sequence = f.header.sequence;
    if (is_end_marker(f)) {
      ended = true;
      break;
    }
    if (received >= expected.size()) {
      fail("more messages than expected");
      continue;
    }
    const AnyMessage& want = expected[received];
    const bool same = std::visit(
        [&](const auto& w) {
          std::remove_cvref_t<decltype(w)> got;
          return mav::unpack(f, got) && got == w;
        },
        want);
    std::printf("RECV id=%u len=%u seq=%u %s\n", static_cast<unsigned>(f.header.message_id),
                static_cast<unsigned>(f.wire_length), static_cast<unsigned>(f.header.sequence),
                same ? "ok" : "MISMATCH");
    if (!same) {
      fail("message " + std::to_string(received) + " id " + std::to_string(f.header.message_id) +
           ": expected " + hex_of(want) + ", wire " + std::to_string(f.wire_length) + " bytes");
    }
    ++received;
  }
  if (!ended) {
    fail("no END marker from the peer");
  }
  if (received != expected.size()) {
    fail("received " + std::to_string(received) + " of " + std::to_string(expected.size()));
  }
  // The peer also sent one frame with a broken CRC, one signed frame and garbage in front of
  // its first frame: each must have been seen and refused.
  const mav::ParserCounters& c = link.parser_counters();
  std::printf(
      "COUNTERS frames=%llu crc_errors=%llu signed_skipped=%llu garbage_bytes=%llu "
      "incomplete=%llu\n",
      static_cast<unsigned long long>(c.frames), static_cast<unsigned long long>(c.crc_errors),
      static_cast<unsigned long long>(c.signed_skipped),
      static_cast<unsigned long long>(c.garbage_bytes),
      static_cast<unsigned long long>(c.incomplete_frames));
  if (c.crc_errors != 1) {
    fail("crc_errors " + std::to_string(c.crc_errors) + ", expected 1");
  }
  if (c.signed_skipped != 1) {
    fail("signed_skipped " + std::to_string(c.signed_skipped) + ", expected 1");
  }
  if (c.garbage_bytes == 0) {
    fail("no garbage bytes counted");
  }

  // Ours, to the address the peer sent from, then END.
  mav::FrameWriter writer(255, 190);
  std::array<std::uint8_t, mav::kMaxFrameBytes> out{};
  for (const AnyMessage& m : expected) {
    const std::size_t n =
        std::visit([&](const auto& message) { return write_message(writer, message, out); }, m);
    if (link.send({out.data(), n}) != mav::MavlinkUdpLink::Io::ok) {
      fail("send failed");
    }
  }
  mav::StatusText end;
  end.severity = 6;
  mav::set_text(end.text, "END");
  if (link.send({out.data(), write_message(writer, end, out)}) != mav::MavlinkUdpLink::Io::ok) {
    fail("send END failed");
  }
  std::printf("RESULT %s\n", failures == 0 ? "ok" : "failed");
  return failures == 0 ? 0 : 1;
}
