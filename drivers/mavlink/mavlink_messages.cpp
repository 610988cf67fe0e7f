// Field orders follow the v2 wire rule (base fields sorted by type size, stable, extensions in
// declaration order after them) applied to common.xml; every value is little-endian.
#include "drivers/mavlink/mavlink_messages.hpp"

#include <bit>
#include <cassert>

namespace rovctl::drivers::mavlink {
namespace {

class Writer {
 public:
  explicit Writer(Payload& out) : out_(out) { out_.fill(0); }
  void u8(std::uint8_t v) { out_[n_++] = v; }
  void i8(std::int8_t v) { u8(static_cast<std::uint8_t>(v)); }
  void u16(std::uint16_t v) {
    u8(static_cast<std::uint8_t>(v & 0xFFU));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void i16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void u32(std::uint32_t v) {
    u16(static_cast<std::uint16_t>(v & 0xFFFFU));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  template <std::size_t N>
  void chars(const std::array<char, N>& text) {
    for (const char c : text) {
      u8(static_cast<std::uint8_t>(c));
    }
  }
  std::size_t done(std::uint32_t id) const {
    assert(find_message(id) != nullptr && n_ == find_message(id)->max_length);
    (void)id;
    return n_;
  }

 private:
  Payload& out_;
  std::size_t n_ = 0;
};

class Reader {
 public:
  explicit Reader(const Frame& f) : in_(f.payload) {}
  std::uint8_t u8() { return in_[n_++]; }
  std::int8_t i8() { return static_cast<std::int8_t>(u8()); }
  std::uint16_t u16() {
    const std::uint16_t lo = u8();
    return static_cast<std::uint16_t>(lo | (u8() << 8));
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::uint32_t u32() {
    const std::uint32_t lo = u16();
    return lo | (static_cast<std::uint32_t>(u16()) << 16);
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  float f32() { return std::bit_cast<float>(u32()); }
  template <std::size_t N>
  void chars(std::array<char, N>& text) {
    for (char& c : text) {
      c = static_cast<char>(u8());
    }
  }

 private:
  const Payload& in_;
  std::size_t n_ = 0;
};

}  // namespace

std::size_t pack(const Heartbeat& m, Payload& out) {
  Writer w(out);
  w.u32(m.custom_mode);
  w.u8(m.type);
  w.u8(m.autopilot);
  w.u8(m.base_mode);
  w.u8(m.system_status);
  w.u8(m.mavlink_version);
  return w.done(Heartbeat::kId);
}

bool unpack(const Frame& f, Heartbeat& m) {
  if (f.header.message_id != Heartbeat::kId) {
    return false;
  }
  Reader r(f);
  m.custom_mode = r.u32();
  m.type = r.u8();
  m.autopilot = r.u8();
  m.base_mode = r.u8();
  m.system_status = r.u8();
  m.mavlink_version = r.u8();
  return true;
}

std::size_t pack(const SysStatus& m, Payload& out) {
  Writer w(out);
  w.u32(m.sensors_present);
  w.u32(m.sensors_enabled);
  w.u32(m.sensors_health);
  w.u16(m.load_permille);
  w.u16(m.voltage_battery_mv);
  w.i16(m.current_battery_ca);
  w.u16(m.drop_rate_comm_cpct);
  w.u16(m.errors_comm);
  for (const std::uint16_t e : m.errors_count) {
    w.u16(e);
  }
  w.i8(m.battery_remaining_pct);
  w.u32(m.sensors_present_extended);
  w.u32(m.sensors_enabled_extended);
  w.u32(m.sensors_health_extended);
  return w.done(SysStatus::kId);
}

bool unpack(const Frame& f, SysStatus& m) {
  if (f.header.message_id != SysStatus::kId) {
    return false;
  }
  Reader r(f);
  m.sensors_present = r.u32();
  m.sensors_enabled = r.u32();
  m.sensors_health = r.u32();
  m.load_permille = r.u16();
  m.voltage_battery_mv = r.u16();
  m.current_battery_ca = r.i16();
  m.drop_rate_comm_cpct = r.u16();
  m.errors_comm = r.u16();
  for (std::uint16_t& e : m.errors_count) {
    e = r.u16();
  }
  m.battery_remaining_pct = r.i8();
  m.sensors_present_extended = r.u32();
  m.sensors_enabled_extended = r.u32();
  m.sensors_health_extended = r.u32();
  return true;
}

std::size_t pack(const ParamRequestRead& m, Payload& out) {
  Writer w(out);
  w.i16(m.param_index);
  w.u8(m.target_system);
  w.u8(m.target_component);
  w.chars(m.param_id);
  return w.done(ParamRequestRead::kId);
}

bool unpack(const Frame& f, ParamRequestRead& m) {
  if (f.header.message_id != ParamRequestRead::kId) {
    return false;
  }
  Reader r(f);
  m.param_index = r.i16();
  m.target_system = r.u8();
  m.target_component = r.u8();
  r.chars(m.param_id);
  return true;
}

std::size_t pack(const ParamValue& m, Payload& out) {
  Writer w(out);
  w.f32(m.param_value);
  w.u16(m.param_count);
  w.u16(m.param_index);
  w.chars(m.param_id);
  w.u8(m.param_type);
  return w.done(ParamValue::kId);
}

bool unpack(const Frame& f, ParamValue& m) {
  if (f.header.message_id != ParamValue::kId) {
    return false;
  }
  Reader r(f);
  m.param_value = r.f32();
  m.param_count = r.u16();
  m.param_index = r.u16();
  r.chars(m.param_id);
  m.param_type = r.u8();
  return true;
}

std::size_t pack(const AttitudeQuaternion& m, Payload& out) {
  Writer w(out);
  w.u32(m.time_boot_ms);
  for (const float q : m.q_ned_body) {
    w.f32(q);
  }
  w.f32(m.rollspeed_rad_s);
  w.f32(m.pitchspeed_rad_s);
  w.f32(m.yawspeed_rad_s);
  for (const float q : m.repr_offset_q) {
    w.f32(q);
  }
  return w.done(AttitudeQuaternion::kId);
}

bool unpack(const Frame& f, AttitudeQuaternion& m) {
  if (f.header.message_id != AttitudeQuaternion::kId) {
    return false;
  }
  Reader r(f);
  m.time_boot_ms = r.u32();
  for (float& q : m.q_ned_body) {
    q = r.f32();
  }
  m.rollspeed_rad_s = r.f32();
  m.pitchspeed_rad_s = r.f32();
  m.yawspeed_rad_s = r.f32();
  for (float& q : m.repr_offset_q) {
    q = r.f32();
  }
  return true;
}

std::size_t pack(const ManualControl& m, Payload& out) {
  Writer w(out);
  w.i16(m.x);
  w.i16(m.y);
  w.i16(m.z);
  w.i16(m.r);
  w.u16(m.buttons);
  w.u8(m.target);
  w.u16(m.buttons2);
  w.u8(m.enabled_extensions);
  w.i16(m.s);
  w.i16(m.t);
  for (const std::int16_t a : m.aux) {
    w.i16(a);
  }
  return w.done(ManualControl::kId);
}

bool unpack(const Frame& f, ManualControl& m) {
  if (f.header.message_id != ManualControl::kId) {
    return false;
  }
  Reader r(f);
  m.x = r.i16();
  m.y = r.i16();
  m.z = r.i16();
  m.r = r.i16();
  m.buttons = r.u16();
  m.target = r.u8();
  m.buttons2 = r.u16();
  m.enabled_extensions = r.u8();
  m.s = r.i16();
  m.t = r.i16();
  for (std::int16_t& a : m.aux) {
    a = r.i16();
  }
  return true;
}

std::size_t pack(const RcChannelsOverride& m, Payload& out) {
  Writer w(out);
  for (std::size_t i = 0; i < 8; ++i) {
    w.u16(m.channels_us[i]);
  }
  w.u8(m.target_system);
  w.u8(m.target_component);
  for (std::size_t i = 8; i < m.channels_us.size(); ++i) {
    w.u16(m.channels_us[i]);
  }
  return w.done(RcChannelsOverride::kId);
}

bool unpack(const Frame& f, RcChannelsOverride& m) {
  if (f.header.message_id != RcChannelsOverride::kId) {
    return false;
  }
  Reader r(f);
  for (std::size_t i = 0; i < 8; ++i) {
    m.channels_us[i] = r.u16();
  }
  m.target_system = r.u8();
  m.target_component = r.u8();
  for (std::size_t i = 8; i < m.channels_us.size(); ++i) {
    m.channels_us[i] = r.u16();
  }
  return true;
}

std::size_t pack(const VfrHud& m, Payload& out) {
  Writer w(out);
  w.f32(m.airspeed_m_s);
  w.f32(m.groundspeed_m_s);
  w.f32(m.alt_m);
  w.f32(m.climb_m_s);
  w.i16(m.heading_deg);
  w.u16(m.throttle_pct);
  return w.done(VfrHud::kId);
}

bool unpack(const Frame& f, VfrHud& m) {
  if (f.header.message_id != VfrHud::kId) {
    return false;
  }
  Reader r(f);
  m.airspeed_m_s = r.f32();
  m.groundspeed_m_s = r.f32();
  m.alt_m = r.f32();
  m.climb_m_s = r.f32();
  m.heading_deg = r.i16();
  m.throttle_pct = r.u16();
  return true;
}

std::size_t pack(const CommandLong& m, Payload& out) {
  Writer w(out);
  for (const float p : m.params) {
    w.f32(p);
  }
  w.u16(m.command);
  w.u8(m.target_system);
  w.u8(m.target_component);
  w.u8(m.confirmation);
  return w.done(CommandLong::kId);
}

bool unpack(const Frame& f, CommandLong& m) {
  if (f.header.message_id != CommandLong::kId) {
    return false;
  }
  Reader r(f);
  for (float& p : m.params) {
    p = r.f32();
  }
  m.command = r.u16();
  m.target_system = r.u8();
  m.target_component = r.u8();
  m.confirmation = r.u8();
  return true;
}

std::size_t pack(const CommandAck& m, Payload& out) {
  Writer w(out);
  w.u16(m.command);
  w.u8(m.result);
  w.u8(m.progress);
  w.i32(m.result_param2);
  w.u8(m.target_system);
  w.u8(m.target_component);
  return w.done(CommandAck::kId);
}

bool unpack(const Frame& f, CommandAck& m) {
  if (f.header.message_id != CommandAck::kId) {
    return false;
  }
  Reader r(f);
  m.command = r.u16();
  m.result = r.u8();
  m.progress = r.u8();
  m.result_param2 = r.i32();
  m.target_system = r.u8();
  m.target_component = r.u8();
  return true;
}

std::size_t pack(const ScaledPressure2& m, Payload& out) {
  Writer w(out);
  w.u32(m.time_boot_ms);
  w.f32(m.press_abs_hpa);
  w.f32(m.press_diff_hpa);
  w.i16(m.temperature_cdegc);
  w.i16(m.temperature_press_diff_cdegc);
  return w.done(ScaledPressure2::kId);
}

bool unpack(const Frame& f, ScaledPressure2& m) {
  if (f.header.message_id != ScaledPressure2::kId) {
    return false;
  }
  Reader r(f);
  m.time_boot_ms = r.u32();
  m.press_abs_hpa = r.f32();
  m.press_diff_hpa = r.f32();
  m.temperature_cdegc = r.i16();
  m.temperature_press_diff_cdegc = r.i16();
  return true;
}

std::size_t pack(const NamedValueFloat& m, Payload& out) {
  Writer w(out);
  w.u32(m.time_boot_ms);
  w.f32(m.value);
  w.chars(m.name);
  return w.done(NamedValueFloat::kId);
}

bool unpack(const Frame& f, NamedValueFloat& m) {
  if (f.header.message_id != NamedValueFloat::kId) {
    return false;
  }
  Reader r(f);
  m.time_boot_ms = r.u32();
  m.value = r.f32();
  r.chars(m.name);
  return true;
}

std::size_t pack(const StatusText& m, Payload& out) {
  Writer w(out);
  w.u8(m.severity);
  w.chars(m.text);
  w.u16(m.id);
  w.u8(m.chunk_seq);
  return w.done(StatusText::kId);
}

bool unpack(const Frame& f, StatusText& m) {
  if (f.header.message_id != StatusText::kId) {
    return false;
  }
  Reader r(f);
  m.severity = r.u8();
  r.chars(m.text);
  m.id = r.u16();
  m.chunk_seq = r.u8();
  return true;
}

CommandLong arm_disarm(std::uint8_t target_system, std::uint8_t target_component, bool arm,
                       bool force) {
  CommandLong c;
  c.command = kCmdComponentArmDisarm;
  c.target_system = target_system;
  c.target_component = target_component;
  c.params[0] = arm ? 1.0F : 0.0F;
  c.params[1] = force ? kArmDisarmForceMagic : 0.0F;
  return c;
}

CommandLong set_message_interval(std::uint8_t target_system, std::uint8_t target_component,
                                 std::uint32_t message_id, float interval_us) {
  CommandLong c;
  c.command = kCmdSetMessageInterval;
  c.target_system = target_system;
  c.target_component = target_component;
  c.params[0] = static_cast<float>(message_id);
  c.params[1] = interval_us;
  return c;
}

}  // namespace rovctl::drivers::mavlink
