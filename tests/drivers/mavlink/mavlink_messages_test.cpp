// MAVLink messages: every message round-trips through its frame with all fields distinct, and
// the byte offsets of a few fields match the v2 wire order of common.xml.
#include "drivers/mavlink/mavlink_messages.hpp"

#include <gtest/gtest.h>

namespace rovctl::drivers::mavlink {
namespace {

template <typename Message>
Message round_trip(const Message& m, std::size_t* wire_length = nullptr) {
  FrameWriter writer(255, 190);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  const std::size_t n = write_message(writer, m, out);
  EXPECT_GT(n, 0U);
  FrameParser parser;
  EXPECT_EQ(parser.feed(std::span<const std::uint8_t>(out.data(), n)), n);
  Frame f;
  EXPECT_TRUE(parser.next(f));
  EXPECT_EQ(f.header.message_id, Message::kId);
  if (wire_length != nullptr) {
    *wire_length = f.wire_length;
  }
  Message back;
  EXPECT_TRUE(unpack(f, back));
  return back;
}

TEST(MavlinkMessages, PackLengthIsTheFullMessage) {
  Payload p{};
  EXPECT_EQ(pack(Heartbeat{}, p), find_message(Heartbeat::kId)->max_length);
  EXPECT_EQ(pack(SysStatus{}, p), find_message(SysStatus::kId)->max_length);
  EXPECT_EQ(pack(ParamRequestRead{}, p), find_message(ParamRequestRead::kId)->max_length);
  EXPECT_EQ(pack(ParamValue{}, p), find_message(ParamValue::kId)->max_length);
  EXPECT_EQ(pack(AttitudeQuaternion{}, p), find_message(AttitudeQuaternion::kId)->max_length);
  EXPECT_EQ(pack(ManualControl{}, p), find_message(ManualControl::kId)->max_length);
  EXPECT_EQ(pack(RcChannelsOverride{}, p), find_message(RcChannelsOverride::kId)->max_length);
  EXPECT_EQ(pack(VfrHud{}, p), find_message(VfrHud::kId)->max_length);
  EXPECT_EQ(pack(CommandLong{}, p), find_message(CommandLong::kId)->max_length);
  EXPECT_EQ(pack(CommandAck{}, p), find_message(CommandAck::kId)->max_length);
  EXPECT_EQ(pack(ScaledPressure2{}, p), find_message(ScaledPressure2::kId)->max_length);
  EXPECT_EQ(pack(NamedValueFloat{}, p), find_message(NamedValueFloat::kId)->max_length);
  EXPECT_EQ(pack(StatusText{}, p), find_message(StatusText::kId)->max_length);
}

TEST(MavlinkMessages, HeartbeatRoundTrip) {
  Heartbeat m{0x01020304, 12, 3, 0xC1, 4, 3};
  const Heartbeat b = round_trip(m);
  EXPECT_EQ(b.custom_mode, 0x01020304U);
  EXPECT_EQ(b.type, 12);
  EXPECT_EQ(b.autopilot, 3);
  EXPECT_EQ(b.base_mode, 0xC1);
  EXPECT_EQ(b.system_status, 4);
  EXPECT_EQ(b.mavlink_version, 3);
}

TEST(MavlinkMessages, SysStatusRoundTrip) {
  SysStatus m;
  m.sensors_present = 0x11111111;
  m.sensors_enabled = 0x22222222;
  m.sensors_health = 0x33333333;
  m.load_permille = 456;
  m.voltage_battery_mv = 15800;
  m.current_battery_ca = -1234;
  m.drop_rate_comm_cpct = 7;
  m.errors_comm = 8;
  m.errors_count = {9, 10, 11, 12};
  m.battery_remaining_pct = -1;
  m.sensors_present_extended = 13;
  m.sensors_enabled_extended = 14;
  m.sensors_health_extended = 15;
  const SysStatus b = round_trip(m);
  EXPECT_EQ(b.sensors_present, 0x11111111U);
  EXPECT_EQ(b.sensors_enabled, 0x22222222U);
  EXPECT_EQ(b.sensors_health, 0x33333333U);
  EXPECT_EQ(b.load_permille, 456);
  EXPECT_EQ(b.voltage_battery_mv, 15800);
  EXPECT_EQ(b.current_battery_ca, -1234);
  EXPECT_EQ(b.drop_rate_comm_cpct, 7);
  EXPECT_EQ(b.errors_comm, 8);
  EXPECT_EQ(b.errors_count, (std::array<std::uint16_t, 4>{9, 10, 11, 12}));
  EXPECT_EQ(b.battery_remaining_pct, -1);
  EXPECT_EQ(b.sensors_present_extended, 13U);
  EXPECT_EQ(b.sensors_enabled_extended, 14U);
  EXPECT_EQ(b.sensors_health_extended, 15U);
}

TEST(MavlinkMessages, ParamRoundTrips) {
  ParamRequestRead r;
  r.target_system = 1;
  r.target_component = 1;
  set_text(r.param_id, "FS_PILOT_TIMEOUT");  // exactly 16 chars: no terminator on the wire
  const ParamRequestRead rb = round_trip(r);
  EXPECT_EQ(rb.param_index, -1);
  EXPECT_EQ(rb.target_system, 1);
  EXPECT_EQ(rb.target_component, 1);
  EXPECT_EQ(text_of(rb.param_id), "FS_PILOT_TIMEOUT");

  ParamValue v;
  v.param_value = 3.0F;
  v.param_count = 900;
  v.param_index = 65535;
  set_text(v.param_id, "RC_OVERRIDE_TIME");
  v.param_type = 9;  // MAV_PARAM_TYPE_REAL32
  const ParamValue vb = round_trip(v);
  EXPECT_EQ(vb.param_value, 3.0F);
  EXPECT_EQ(vb.param_count, 900);
  EXPECT_EQ(vb.param_index, 65535);
  EXPECT_EQ(text_of(vb.param_id), "RC_OVERRIDE_TIME");
  EXPECT_EQ(vb.param_type, 9);
}

TEST(MavlinkMessages, AttitudeQuaternionRoundTripAndTruncation) {
  AttitudeQuaternion m;
  m.time_boot_ms = 987654;
  m.q_ned_body = {0.9F, 0.1F, -0.2F, 0.3F};
  m.rollspeed_rad_s = 0.01F;
  m.pitchspeed_rad_s = -0.02F;
  m.yawspeed_rad_s = 0.5F;
  std::size_t wire = 0;
  const AttitudeQuaternion b = round_trip(m, &wire);
  EXPECT_EQ(wire, 32U);  // repr_offset_q all zero: cut
  EXPECT_EQ(b.time_boot_ms, 987654U);
  EXPECT_EQ(b.q_ned_body, m.q_ned_body);
  EXPECT_EQ(b.rollspeed_rad_s, 0.01F);
  EXPECT_EQ(b.pitchspeed_rad_s, -0.02F);
  EXPECT_EQ(b.yawspeed_rad_s, 0.5F);
  EXPECT_EQ(b.repr_offset_q, (std::array<float, 4>{}));
}

TEST(MavlinkMessages, ManualControlRoundTripAndWireOrder) {
  ManualControl m;
  m.x = -1000;
  m.y = 250;
  m.z = 500;
  m.r = 1000;
  m.buttons = 0x8001;
  m.target = 1;
  m.buttons2 = 2;
  m.enabled_extensions = 3;
  m.s = -4;
  m.t = 5;
  m.aux = {6, 7, 8, 9, 10, -11};
  const ManualControl b = round_trip(m);
  EXPECT_EQ(b.x, -1000);
  EXPECT_EQ(b.y, 250);
  EXPECT_EQ(b.z, 500);
  EXPECT_EQ(b.r, 1000);
  EXPECT_EQ(b.buttons, 0x8001);
  EXPECT_EQ(b.target, 1);
  EXPECT_EQ(b.buttons2, 2);
  EXPECT_EQ(b.enabled_extensions, 3);
  EXPECT_EQ(b.s, -4);
  EXPECT_EQ(b.t, 5);
  EXPECT_EQ(b.aux, m.aux);

  Payload p{};
  pack(m, p);
  EXPECT_EQ(p[0], 0x18);  // x = -1000 = 0xFC18, little-endian
  EXPECT_EQ(p[1], 0xFC);
  EXPECT_EQ(p[10], 1);  // target after the five int16/uint16 fields
}

TEST(MavlinkMessages, RcChannelsOverrideKeepsTargetsBetweenChannelBlocks) {
  RcChannelsOverride m;
  for (std::size_t i = 0; i < m.channels_us.size(); ++i) {
    m.channels_us[i] = static_cast<std::uint16_t>(1100 + 10 * i);
  }
  m.target_system = 1;
  m.target_component = 1;
  const RcChannelsOverride b = round_trip(m);
  EXPECT_EQ(b.channels_us, m.channels_us);
  EXPECT_EQ(b.target_system, 1);
  EXPECT_EQ(b.target_component, 1);
  Payload p{};
  pack(m, p);
  EXPECT_EQ(p[16], 1);                    // target_system right after chan8
  EXPECT_EQ(p[18] | (p[19] << 8), 1180);  // chan9 first of the extensions
}

TEST(MavlinkMessages, VfrHudAndPressureRoundTrip) {
  VfrHud h{0.5F, 0.25F, -12.5F, -0.1F, 271, 40};
  const VfrHud hb = round_trip(h);
  EXPECT_EQ(hb.airspeed_m_s, 0.5F);
  EXPECT_EQ(hb.groundspeed_m_s, 0.25F);
  EXPECT_EQ(hb.alt_m, -12.5F);
  EXPECT_EQ(hb.climb_m_s, -0.1F);
  EXPECT_EQ(hb.heading_deg, 271);
  EXPECT_EQ(hb.throttle_pct, 40);

  ScaledPressure2 s{1000, 2250.5F, 1.5F, -150, 77};
  const ScaledPressure2 sb = round_trip(s);
  EXPECT_EQ(sb.time_boot_ms, 1000U);
  EXPECT_EQ(sb.press_abs_hpa, 2250.5F);
  EXPECT_EQ(sb.press_diff_hpa, 1.5F);
  EXPECT_EQ(sb.temperature_cdegc, -150);
  EXPECT_EQ(sb.temperature_press_diff_cdegc, 77);
}

TEST(MavlinkMessages, CommandsRoundTrip) {
  const CommandLong arm = round_trip(arm_disarm(1, 1, true, true));
  EXPECT_EQ(arm.command, 400);
  EXPECT_EQ(arm.params[0], 1.0F);
  EXPECT_EQ(arm.params[1], 21196.0F);
  EXPECT_EQ(arm.target_system, 1);
  EXPECT_EQ(arm.target_component, 1);
  const CommandLong disarm = round_trip(arm_disarm(1, 1, false, false));
  EXPECT_EQ(disarm.params[0], 0.0F);
  EXPECT_EQ(disarm.params[1], 0.0F);

  CommandLong interval = set_message_interval(1, 1, AttitudeQuaternion::kId, 33333.0F);
  interval.confirmation = 2;
  interval.params[6] = 7.5F;
  const CommandLong ib = round_trip(interval);
  EXPECT_EQ(ib.command, 511);
  EXPECT_EQ(ib.params[0], 31.0F);
  EXPECT_EQ(ib.params[1], 33333.0F);
  EXPECT_EQ(ib.params[6], 7.5F);
  EXPECT_EQ(ib.confirmation, 2);

  CommandAck a{511, 4, 50, -7, 255, 190};
  const CommandAck ab = round_trip(a);
  EXPECT_EQ(ab.command, 511);
  EXPECT_EQ(ab.result, 4);
  EXPECT_EQ(ab.progress, 50);
  EXPECT_EQ(ab.result_param2, -7);
  EXPECT_EQ(ab.target_system, 255);
  EXPECT_EQ(ab.target_component, 190);
}

TEST(MavlinkMessages, TextMessagesRoundTrip) {
  NamedValueFloat n;
  n.time_boot_ms = 42;
  n.value = -0.125F;
  set_text(n.name, "lat_err_m_toolong");  // cut to 10
  const NamedValueFloat nb = round_trip(n);
  EXPECT_EQ(nb.time_boot_ms, 42U);
  EXPECT_EQ(nb.value, -0.125F);
  EXPECT_EQ(text_of(nb.name), "lat_err_m_");

  StatusText s;
  s.severity = 2;
  set_text(s.text, "FAILSAFE camera lost -> back out");
  s.id = 3;
  s.chunk_seq = 1;
  const StatusText sb = round_trip(s);
  EXPECT_EQ(sb.severity, 2);
  EXPECT_EQ(text_of(sb.text), "FAILSAFE camera lost -> back out");
  EXPECT_EQ(sb.id, 3);
  EXPECT_EQ(sb.chunk_seq, 1);
}

TEST(MavlinkMessages, UnpackRefusesAnotherMessage) {
  FrameWriter writer(1, 1);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  const std::size_t n = write_message(writer, Heartbeat{}, out);
  FrameParser parser;
  parser.feed(std::span<const std::uint8_t>(out.data(), n));
  Frame f;
  ASSERT_TRUE(parser.next(f));
  ManualControl m;
  EXPECT_FALSE(unpack(f, m));
}

}  // namespace
}  // namespace rovctl::drivers::mavlink
