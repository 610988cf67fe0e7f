// The MAVLink messages rovctl exchanges with ArduSub and the ground station, as plain structs
// whose wire() lists the fields once in v2 wire order (fields by size, extensions last); pack and
// unpack both run that list. No allocation.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "drivers/mavlink/mavlink_codec.hpp"
#include "drivers/mavlink/mavlink_payload.hpp"

namespace rovctl::drivers::mavlink {

// MAV_CMD values used with COMMAND_LONG.
constexpr std::uint16_t kCmdDoSetMode = 176;
constexpr std::uint16_t kCmdComponentArmDisarm = 400;
constexpr std::uint16_t kCmdRunPrearmChecks = 401;
constexpr std::uint16_t kCmdSetMessageInterval = 511;
// param2 of ARM_DISARM that forces arming/disarming past the pre-arm checks.
constexpr float kArmDisarmForceMagic = 21196.0F;
// DO_SET_MODE's param1 saying param2 is the autopilot's own custom_mode
// (MAV_MODE_FLAG_CUSTOM_MODE_ENABLED).
constexpr float kModeFlagCustomModeEnabled = 1.0F;
// HEARTBEAT.base_mode bit set while the vehicle is armed (MAV_MODE_FLAG_SAFETY_ARMED).
constexpr std::uint8_t kModeFlagSafetyArmed = 0x80;

struct Heartbeat {  // HEARTBEAT (0)
  static constexpr std::uint32_t kId = 0;
  std::uint32_t custom_mode = 0;   // autopilot-specific mode (ArduSub: 0 STABILIZE, 19 MANUAL...)
  std::uint8_t type = 0;           // MAV_TYPE
  std::uint8_t autopilot = 0;      // MAV_AUTOPILOT
  std::uint8_t base_mode = 0;      // MAV_MODE_FLAG bits
  std::uint8_t system_status = 0;  // MAV_STATE
  std::uint8_t mavlink_version = 3;

  bool operator==(const Heartbeat&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.custom_mode, m.type, m.autopilot, m.base_mode, m.system_status, m.mavlink_version);
  }
};

struct SysStatus {  // SYS_STATUS (1)
  static constexpr std::uint32_t kId = 1;
  std::uint32_t sensors_present = 0;  // MAV_SYS_STATUS_SENSOR bits
  std::uint32_t sensors_enabled = 0;
  std::uint32_t sensors_health = 0;
  std::uint16_t load_permille = 0;
  std::uint16_t voltage_battery_mv = 0;  // UINT16_MAX: unknown
  std::int16_t current_battery_ca = 0;   // centiamperes; -1: unknown
  std::uint16_t drop_rate_comm_cpct = 0;
  std::uint16_t errors_comm = 0;
  std::array<std::uint16_t, 4> errors_count{};
  std::int8_t battery_remaining_pct = 0;  // -1: unknown
  std::uint32_t sensors_present_extended = 0;
  std::uint32_t sensors_enabled_extended = 0;
  std::uint32_t sensors_health_extended = 0;

  bool operator==(const SysStatus&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.sensors_present, m.sensors_enabled, m.sensors_health, m.load_permille,
       m.voltage_battery_mv, m.current_battery_ca, m.drop_rate_comm_cpct, m.errors_comm,
       m.errors_count, m.battery_remaining_pct, m.sensors_present_extended,
       m.sensors_enabled_extended, m.sensors_health_extended);
  }
};

struct ParamRequestRead {  // PARAM_REQUEST_READ (20)
  static constexpr std::uint32_t kId = 20;
  std::int16_t param_index = -1;  // -1: look the parameter up by param_id
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::array<char, 16> param_id{};  // NUL-terminated only when shorter than 16

  bool operator==(const ParamRequestRead&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.param_index, m.target_system, m.target_component, m.param_id);
  }
};

struct ParamValue {  // PARAM_VALUE (22)
  static constexpr std::uint32_t kId = 22;
  float param_value = 0.0F;  // ArduPilot sends integers converted to float
  std::uint16_t param_count = 0;
  std::uint16_t param_index = 0;
  std::array<char, 16> param_id{};
  std::uint8_t param_type = 0;  // MAV_PARAM_TYPE

  bool operator==(const ParamValue&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.param_value, m.param_count, m.param_index, m.param_id, m.param_type);
  }
};

struct AttitudeQuaternion {  // ATTITUDE_QUATERNION (31)
  static constexpr std::uint32_t kId = 31;
  std::uint32_t time_boot_ms = 0;
  std::array<float, 4> q_ned_body{};  // w, x, y, z: body (FRD) relative to NED
  float rollspeed_rad_s = 0.0F;
  float pitchspeed_rad_s = 0.0F;
  float yawspeed_rad_s = 0.0F;
  std::array<float, 4> repr_offset_q{};  // extension

  bool operator==(const AttitudeQuaternion&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.time_boot_ms, m.q_ned_body, m.rollspeed_rad_s, m.pitchspeed_rad_s, m.yawspeed_rad_s,
       m.repr_offset_q);
  }
};

struct ManualControl {  // MANUAL_CONTROL (69)
  static constexpr std::uint32_t kId = 69;
  std::int16_t x = 0;  // forward, -1000..1000
  std::int16_t y = 0;  // lateral, -1000..1000
  std::int16_t z = 0;  // vertical; ArduSub: 0..1000 with 500 neutral
  std::int16_t r = 0;  // yaw, -1000..1000
  std::uint16_t buttons = 0;
  std::uint8_t target = 0;  // the vehicle's system id; 0 is ignored by ArduSub
  std::uint16_t buttons2 = 0;
  std::uint8_t enabled_extensions = 0;
  std::int16_t s = 0;
  std::int16_t t = 0;
  std::array<std::int16_t, 6> aux{};

  bool operator==(const ManualControl&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.x, m.y, m.z, m.r, m.buttons, m.target, m.buttons2, m.enabled_extensions, m.s, m.t, m.aux);
  }
};

struct RcChannelsOverride {  // RC_CHANNELS_OVERRIDE (70)
  static constexpr std::uint32_t kId = 70;
  // common.xml: on channels 1-8 UINT16_MAX leaves a channel as it is and 0 releases it to
  // the RC radio; on 9-18 both 0 and UINT16_MAX leave it, UINT16_MAX - 1 releases it.
  std::array<std::uint16_t, 18> channels_us{};
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;

  bool operator==(const RcChannelsOverride&) const = default;
  static void wire(auto& m, auto& io) {
    io(std::span(m.channels_us).template first<8>(), m.target_system, m.target_component,
       std::span(m.channels_us).template subspan<8>());
  }
};

struct VfrHud {  // VFR_HUD (74)
  static constexpr std::uint32_t kId = 74;
  float airspeed_m_s = 0.0F;
  float groundspeed_m_s = 0.0F;
  float alt_m = 0.0F;  // ArduSub: depth as a negative altitude
  float climb_m_s = 0.0F;
  std::int16_t heading_deg = 0;
  std::uint16_t throttle_pct = 0;

  bool operator==(const VfrHud&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.airspeed_m_s, m.groundspeed_m_s, m.alt_m, m.climb_m_s, m.heading_deg, m.throttle_pct);
  }
};

struct CommandLong {  // COMMAND_LONG (76)
  static constexpr std::uint32_t kId = 76;
  std::array<float, 7> params{};  // param1..param7
  std::uint16_t command = 0;      // MAV_CMD
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t confirmation = 0;

  bool operator==(const CommandLong&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.params, m.command, m.target_system, m.target_component, m.confirmation);
  }
};

struct CommandAck {  // COMMAND_ACK (77)
  static constexpr std::uint32_t kId = 77;
  std::uint16_t command = 0;
  std::uint8_t result = 0;  // MAV_RESULT
  std::uint8_t progress = 0;
  std::int32_t result_param2 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;

  bool operator==(const CommandAck&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.command, m.result, m.progress, m.result_param2, m.target_system, m.target_component);
  }
};

struct ScaledPressure2 {  // SCALED_PRESSURE2 (137)
  static constexpr std::uint32_t kId = 137;
  std::uint32_t time_boot_ms = 0;
  float press_abs_hpa = 0.0F;
  float press_diff_hpa = 0.0F;
  std::int16_t temperature_cdegc = 0;
  std::int16_t temperature_press_diff_cdegc = 0;

  bool operator==(const ScaledPressure2&) const = default;
  static void wire(auto& m, auto& io) {
    io(m.time_boot_ms, m.press_abs_hpa, m.press_diff_hpa, m.temperature_cdegc,
       m.temperature_press_diff_cdegc);
  }
};

struct NamedValueFloat {  // NAMED_VALUE_FLOAT (251)
  static constexpr std::uint32_t kId = 251;
  std::uint32_t time_boot_ms = 0;
  float value = 0.0F;
  std::array<char, 10> name{};

  bool operator==(const NamedValueFloat&) const = default;
  static void wire(auto& m, auto& io) { io(m.time_boot_ms, m.value, m.name); }
};

struct StatusText {  // STATUSTEXT (253)
  static constexpr std::uint32_t kId = 253;
  std::uint8_t severity = 0;  // MAV_SEVERITY: 0 EMERGENCY .. 7 DEBUG
  std::array<char, 50> text{};
  std::uint16_t id = 0;  // non-zero ties the chunks of a longer text together
  std::uint8_t chunk_seq = 0;

  bool operator==(const StatusText&) const = default;
  static void wire(auto& m, auto& io) { io(m.severity, m.text, m.id, m.chunk_seq); }
};

// A message struct above: its id and its fields in wire order (v2: base fields by type size,
// stable, extensions in declaration order after them), the one place each message's layout is
// written.
template <typename M>
concept WireMessage = requires(M& m, const M& c, detail::PayloadWriter& w,
                               detail::PayloadReader& r) {
  { M::kId } -> std::convertible_to<std::uint32_t>;
  M::wire(c, w);
  M::wire(m, r);
};

// pack writes the full message (extensions included) and returns its length; the frame encoder
// then cuts the trailing zeros. unpack reads a frame's zero-extended payload and is false when
// the frame carries another message.
template <WireMessage M>
std::size_t pack(const M& m, Payload& out) {
  detail::PayloadWriter w(out);
  M::wire(m, w);
  return w.done(M::kId);
}
template <WireMessage M>
bool unpack(const Frame& f, M& m) {
  if (f.header.message_id != M::kId) {
    return false;
  }
  detail::PayloadReader r(f.payload);
  M::wire(m, r);
  return true;
}

// One message as a frame from `writer` into `out`; the frame length, 0 if `out` is too small.
template <typename Message>
std::size_t write_message(FrameWriter& writer, const Message& m, std::span<std::uint8_t> out) {
  Payload payload{};
  const std::size_t n = pack(m, payload);
  return writer.write(Message::kId, std::span<const std::uint8_t>(payload.data(), n), out);
}

// COMMAND_LONG MAV_CMD_COMPONENT_ARM_DISARM (param1 1 arm / 0 disarm; force sets param2).
CommandLong arm_disarm(std::uint8_t target_system, std::uint8_t target_component, bool arm,
                       bool force);
// COMMAND_LONG MAV_CMD_DO_SET_MODE to the autopilot's `custom_mode` (ArduSub: STABILIZE 0, ...).
CommandLong do_set_mode(std::uint8_t target_system, std::uint8_t target_component,
                        std::uint32_t custom_mode);
// COMMAND_LONG MAV_CMD_RUN_PREARM_CHECKS: the autopilot reports failing checks as STATUSTEXT.
CommandLong run_prearm_checks(std::uint8_t target_system, std::uint8_t target_component);
// COMMAND_LONG MAV_CMD_SET_MESSAGE_INTERVAL: `interval_us` -1 stops the stream, 0 restores its
// default rate.
CommandLong set_message_interval(std::uint8_t target_system, std::uint8_t target_component,
                                 std::uint32_t message_id, float interval_us);

// A fixed char field from text, cut to fit (NUL-padded when shorter, as MAVLink expects).
template <std::size_t N>
void set_text(std::array<char, N>& field, std::string_view text) {
  field.fill('\0');
  const std::size_t n = text.size() < N ? text.size() : N;
  for (std::size_t i = 0; i < n; ++i) {
    field[i] = text[i];
  }
}
// The text of a fixed char field: up to the first NUL, or all N chars when it has none.
template <std::size_t N>
std::string_view text_of(const std::array<char, N>& field) {
  std::size_t n = 0;
  while (n < N && field[n] != '\0') {
    ++n;
  }
  return {field.data(), n};
}

}  // namespace rovctl::drivers::mavlink
