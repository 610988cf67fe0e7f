// MAVLink v2 framing: the message table recomputed from the definitions, frames produced by
// node-mavlink 2.3.0 decoded byte for byte, CRC failures, resync, truncation and signing.
#include "drivers/mavlink/mavlink_codec.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"
#include "malloc_counter.hpp"  // the one file of drivers_tests that installs the hooks

namespace rovctl::drivers::mavlink {
namespace {

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// The base fields of each message in v2 wire order (sorted by type size, as mavgen does) as
// "type name" or "type name[N]", copied from common.xml / minimal.xml, then the extensions.
struct Definition {
  const char* name;
  std::uint32_t id;
  std::vector<std::string> fields;
  std::vector<std::string> extensions;
};

std::size_t type_size(const std::string& type) {
  if (type == "uint64_t" || type == "int64_t" || type == "double") return 8;
  if (type == "uint32_t" || type == "int32_t" || type == "float") return 4;
  if (type == "uint16_t" || type == "int16_t") return 2;
  return 1;
}

struct Field {
  std::string type;
  std::string name;
  std::size_t count = 1;
};

Field parse_field(const std::string& text) {
  Field f;
  const std::size_t space = text.find(' ');
  f.type = text.substr(0, space);
  f.name = text.substr(space + 1);
  const std::size_t bracket = f.name.find('[');
  if (bracket != std::string::npos) {
    f.count = std::stoul(f.name.substr(bracket + 1));
    f.name = f.name.substr(0, bracket);
  }
  return f;
}

// mavgen's CRC_EXTRA: X.25 over "NAME " and, per base field in wire order, "type name " and
// the array length byte for arrays; the high and low bytes xor-ed.
std::uint8_t crc_extra_of(const Definition& d) {
  const auto add = [](std::uint16_t crc, const std::string& s) {
    return crc_x25(crc, std::span<const std::uint8_t>(
                            reinterpret_cast<const std::uint8_t*>(s.data()), s.size()));
  };
  std::uint16_t crc = add(0xFFFF, std::string(d.name) + " ");
  for (const std::string& text : d.fields) {
    const Field f = parse_field(text);
    crc = add(crc, f.type + " ");
    crc = add(crc, f.name + " ");
    if (f.count > 1) {
      crc = crc_x25(crc, static_cast<std::uint8_t>(f.count));
    }
  }
  return static_cast<std::uint8_t>((crc & 0xFFU) ^ (crc >> 8));
}

std::size_t length_of(const std::vector<std::string>& fields) {
  std::size_t n = 0;
  for (const std::string& text : fields) {
    const Field f = parse_field(text);
    n += type_size(f.type) * f.count;
  }
  return n;
}

const std::vector<Definition>& definitions() {
  static const std::vector<Definition> defs{
      {"HEARTBEAT",
       0,
       {"uint32_t custom_mode", "uint8_t type", "uint8_t autopilot", "uint8_t base_mode",
        "uint8_t system_status", "uint8_t mavlink_version"},
       {}},
      {"SYS_STATUS",
       1,
       {"uint32_t onboard_control_sensors_present", "uint32_t onboard_control_sensors_enabled",
        "uint32_t onboard_control_sensors_health", "uint16_t load", "uint16_t voltage_battery",
        "int16_t current_battery", "uint16_t drop_rate_comm", "uint16_t errors_comm",
        "uint16_t errors_count1", "uint16_t errors_count2", "uint16_t errors_count3",
        "uint16_t errors_count4", "int8_t battery_remaining"},
       {"uint32_t a", "uint32_t b", "uint32_t c"}},
      {"PARAM_REQUEST_READ",
       20,
       {"int16_t param_index", "uint8_t target_system", "uint8_t target_component",
        "char param_id[16]"},
       {}},
      {"PARAM_VALUE",
       22,
       {"float param_value", "uint16_t param_count", "uint16_t param_index", "char param_id[16]",
        "uint8_t param_type"},
       {}},
      {"ATTITUDE_QUATERNION",
       31,
       {"uint32_t time_boot_ms", "float q1", "float q2", "float q3", "float q4", "float rollspeed",
        "float pitchspeed", "float yawspeed"},
       {"float repr_offset_q[4]"}},
      {"MANUAL_CONTROL",
       69,
       {"int16_t x", "int16_t y", "int16_t z", "int16_t r", "uint16_t buttons", "uint8_t target"},
       {"uint16_t buttons2", "uint8_t enabled_extensions", "int16_t s", "int16_t t", "int16_t aux1",
        "int16_t aux2", "int16_t aux3", "int16_t aux4", "int16_t aux5", "int16_t aux6"}},
      {"RC_CHANNELS_OVERRIDE",
       70,
       {"uint16_t chan1_raw", "uint16_t chan2_raw", "uint16_t chan3_raw", "uint16_t chan4_raw",
        "uint16_t chan5_raw", "uint16_t chan6_raw", "uint16_t chan7_raw", "uint16_t chan8_raw",
        "uint8_t target_system", "uint8_t target_component"},
       {"uint16_t chan9_18[10]"}},
      {"VFR_HUD",
       74,
       {"float airspeed", "float groundspeed", "float alt", "float climb", "int16_t heading",
        "uint16_t throttle"},
       {}},
      {"COMMAND_LONG",
       76,
       {"float param1", "float param2", "float param3", "float param4", "float param5",
        "float param6", "float param7", "uint16_t command", "uint8_t target_system",
        "uint8_t target_component", "uint8_t confirmation"},
       {}},
      {"COMMAND_ACK",
       77,
       {"uint16_t command", "uint8_t result"},
       {"uint8_t progress", "int32_t result_param2", "uint8_t target_system",
        "uint8_t target_component"}},
      {"SCALED_PRESSURE2",
       137,
       {"uint32_t time_boot_ms", "float press_abs", "float press_diff", "int16_t temperature"},
       {"int16_t temperature_press_diff"}},
      {"NAMED_VALUE_FLOAT", 251, {"uint32_t time_boot_ms", "float value", "char name[10]"}, {}},
      {"STATUSTEXT",
       253,
       {"uint8_t severity", "char text[50]"},
       {"uint16_t id", "uint8_t chunk_seq"}},
  };
  return defs;
}

TEST(MavlinkCodec, TableMatchesTheDefinitions) {
  ASSERT_EQ(message_table().size(), definitions().size());
  for (const Definition& d : definitions()) {
    SCOPED_TRACE(d.name);
    const MessageInfo* info = find_message(d.id);
    ASSERT_NE(info, nullptr);
    EXPECT_STREQ(info->name, d.name);
    EXPECT_EQ(info->min_length, length_of(d.fields));
    EXPECT_EQ(info->max_length, length_of(d.fields) + length_of(d.extensions));
    EXPECT_EQ(info->crc_extra, crc_extra_of(d));
  }
  EXPECT_EQ(find_message(2), nullptr);
}

// Spot values as node-mavlink's generated MAGIC_NUMBERs (mavlink-mappings 1.0.21-20250824-1;
// the peer test compares all 13), so a wrong recomputation above cannot agree with a wrong table.
TEST(MavlinkCodec, KnownCrcExtras) {
  EXPECT_EQ(find_message(0)->crc_extra, 50);
  EXPECT_EQ(find_message(69)->crc_extra, 243);
  EXPECT_EQ(find_message(76)->crc_extra, 152);
  EXPECT_EQ(find_message(253)->crc_extra, 83);
}

TEST(MavlinkCodec, CrcIsMcrf4xx) {
  const std::string check = "123456789";
  EXPECT_EQ(crc_x25(0xFFFF, std::span<const std::uint8_t>(
                                reinterpret_cast<const std::uint8_t*>(check.data()), check.size())),
            0x6F91);  // the CRC catalogue's check value for CRC-16/MCRF4XX
}

std::vector<Frame> parse_all(const std::vector<std::uint8_t>& bytes, FrameParser& parser,
                             bool byte_at_a_time) {
  std::vector<Frame> frames;
  Frame f;
  std::size_t i = 0;
  while (i < bytes.size()) {
    const std::size_t chunk = byte_at_a_time ? 1 : bytes.size() - i;
    i += parser.feed(std::span<const std::uint8_t>(bytes.data() + i, chunk));
    while (parser.next(f)) {
      frames.push_back(f);
    }
  }
  return frames;
}

// node-mavlink 2.3.0: MavLinkProtocolV2(1, 1).serialize(heartbeat, 7) with type 12 (submarine),
// autopilot 3, base_mode 0xC9, custom_mode 19, system_status 4.
const char* const kNodeHeartbeat = "fd090000070101000000130000000c03c904032a38";
// SCALED_PRESSURE2 seq 200: 123456 ms, 1113.25 hPa, 12.34 degC; the zero extension is cut.
const char* const kNodePressure = "fd0e0000c8010189000040e2010000288b4400000000d204ef91";
// An all-zero COMMAND_ACK: node-mavlink cuts the payload to nothing.
const char* const kNodeEmptyAck = "fd0000000001014d00002f72";

TEST(MavlinkCodec, DecodesNodeMavlinkHeartbeatExactly) {
  FrameParser parser;
  const auto frames = parse_all(from_hex(kNodeHeartbeat), parser, true);
  ASSERT_EQ(frames.size(), 1U);
  const Frame& f = frames[0];
  EXPECT_EQ(f.header.sequence, 7);
  EXPECT_EQ(f.header.system_id, 1);
  EXPECT_EQ(f.header.component_id, 1);
  EXPECT_EQ(f.header.message_id, 0U);
  EXPECT_EQ(f.wire_length, 9);
  Heartbeat hb;
  ASSERT_TRUE(unpack(f, hb));
  EXPECT_EQ(hb.type, 12);
  EXPECT_EQ(hb.autopilot, 3);
  EXPECT_EQ(hb.base_mode, 0xC9);
  EXPECT_EQ(hb.custom_mode, 19U);
  EXPECT_EQ(hb.system_status, 4);
  EXPECT_EQ(hb.mavlink_version, 3);

  // And our encoder reproduces it byte for byte.
  FrameWriter writer(1, 1);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  for (int i = 0; i < 7; ++i) {
    ASSERT_GT(write_message(writer, hb, out), 0U);
  }
  const std::size_t n = write_message(writer, hb, out);
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.begin() + n), from_hex(kNodeHeartbeat));
}

TEST(MavlinkCodec, TruncatedPayloadIsZeroExtended) {
  FrameParser parser;
  const auto frames = parse_all(from_hex(kNodePressure), parser, false);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].wire_length, 14);
  EXPECT_EQ(frames[0].header.sequence, 200);
  ScaledPressure2 p;
  p.temperature_press_diff_cdegc = 99;  // must be overwritten with the zero of the cut field
  ASSERT_TRUE(unpack(frames[0], p));
  EXPECT_EQ(p.time_boot_ms, 123456U);
  EXPECT_FLOAT_EQ(p.press_abs_hpa, 1113.25F);
  EXPECT_EQ(p.temperature_cdegc, 1234);
  EXPECT_EQ(p.temperature_press_diff_cdegc, 0);

  const auto empty = parse_all(from_hex(kNodeEmptyAck), parser, true);
  ASSERT_EQ(empty.size(), 1U);
  EXPECT_EQ(empty[0].wire_length, 0);
  CommandAck ack;
  ack.command = 5;
  ASSERT_TRUE(unpack(empty[0], ack));
  EXPECT_EQ(ack.command, 0);
}

TEST(MavlinkCodec, EncoderCutsTrailingZerosButKeepsOneByte) {
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  FrameWriter writer(255, 190);
  StatusText text;
  text.severity = 2;
  set_text(text.text, "Leak");
  std::size_t n = write_message(writer, text, out);
  EXPECT_EQ(out[1], 5);  // severity + "Leak"
  EXPECT_EQ(n, kHeaderBytes + 5 + kChecksumBytes);
  n = write_message(writer, CommandAck{}, out);
  EXPECT_EQ(out[1], 1);  // as the C reference: never an empty payload
  EXPECT_EQ(n, kHeaderBytes + 1 + kChecksumBytes);
  EXPECT_EQ(writer.next_sequence(), 2);
}

TEST(MavlinkCodec, SequenceWrapsAndIdsAreStamped) {
  FrameWriter writer(255, 190);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  FrameParser parser;
  Frame f;
  for (int i = 0; i < 300; ++i) {
    const std::size_t n = write_message(writer, Heartbeat{}, out);
    ASSERT_EQ(parser.feed(std::span<const std::uint8_t>(out.data(), n)), n);
    ASSERT_TRUE(parser.next(f));
    EXPECT_EQ(f.header.sequence, i % 256);
    EXPECT_EQ(f.header.system_id, 255);
    EXPECT_EQ(f.header.component_id, 190);
  }
}

TEST(MavlinkCodec, UnknownIdAndOversizePayloadAreNotEncoded) {
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  const std::array<std::uint8_t, 10> payload{1};
  EXPECT_EQ(encode_frame(FrameHeader{0, 1, 1, 2}, payload, out), 0U);  // id 2 not in table
  EXPECT_EQ(encode_frame(FrameHeader{0, 1, 1, 0}, payload, out), 0U);  // HEARTBEAT is 9
  EXPECT_EQ(encode_frame(FrameHeader{0, 1, 1, 74}, payload, std::span(out).first(12)), 0U);
}

TEST(MavlinkCodec, CrcFailureIsRejected) {
  auto bytes = from_hex(kNodeHeartbeat);
  for (std::size_t i = 1; i < bytes.size(); ++i) {
    SCOPED_TRACE(i);
    auto damaged = bytes;
    damaged[i] ^= 0x10;
    // A damaged length byte makes the parser wait for more: the zeros let it decide.
    damaged.insert(damaged.end(), kMaxFrameBytes, 0);
    FrameParser parser;
    EXPECT_TRUE(parse_all(damaged, parser, true).empty());
    EXPECT_GE(parser.counters().crc_errors + parser.counters().unknown_ids +
                  parser.counters().bad_incompat_flags,
              1U);
  }
  // The CRC_EXTRA takes part: the same bytes under another id's seed fail.
  auto wrong_id = bytes;
  wrong_id[7] = 74;  // VFR_HUD, a known id with another CRC_EXTRA
  FrameParser parser;
  EXPECT_TRUE(parse_all(wrong_id, parser, false).empty());
  EXPECT_EQ(parser.counters().crc_errors, 1U);
}

TEST(MavlinkCodec, ResyncsAfterGarbageAndFalseStartBytes) {
  // Garbage with a false STX whose length byte claims 200 bytes, right before two real frames.
  std::vector<std::uint8_t> stream{0x00, 0x13, 0xFD, 0xC8, 0x00, 0x00, 0x00,
                                   0x01, 0x01, 0x00, 0x00, 0x00, 0x42, 0xFD};
  const auto hb = from_hex(kNodeHeartbeat);
  const auto sp = from_hex(kNodePressure);
  stream.insert(stream.end(), hb.begin(), hb.end());
  stream.insert(stream.end(), {0xFD, 0x09, 0xFF});  // a start byte with unknown incompat flags
  stream.insert(stream.end(), sp.begin(), sp.end());
  for (const bool byte_at_a_time : {true, false}) {
    SCOPED_TRACE(byte_at_a_time);
    FrameParser parser;
    const auto frames = parse_all(stream, parser, byte_at_a_time);
    // The false header is only proven wrong once its claimed 212 bytes are in: until then the
    // real frames wait in the window, and then come out instead of being swallowed.
    EXPECT_TRUE(frames.empty());
    std::vector<std::uint8_t> pad(kMaxFrameBytes, 0);
    auto more = parse_all(pad, parser, byte_at_a_time);
    std::vector<Frame> all = frames;
    all.insert(all.end(), more.begin(), more.end());
    ASSERT_EQ(all.size(), 2U);
    EXPECT_EQ(all[0].header.message_id, 0U);
    EXPECT_EQ(all[1].header.message_id, 137U);
    EXPECT_GE(parser.counters().crc_errors, 1U);
    EXPECT_EQ(parser.counters().frames, 2U);
  }
}

TEST(MavlinkCodec, FinishRescansAnIncompleteFrameAtTheEndOfInput) {
  // One datagram: a false STX claiming 200 bytes, then a whole frame. At the datagram's end the
  // false frame can never complete, and the real one behind it comes out.
  std::vector<std::uint8_t> datagram{0xFD, 0xC8, 0x00, 0x00, 0x00, 0x01, 0x01, 0x00, 0x00, 0x00};
  const auto hb = from_hex(kNodeHeartbeat);
  datagram.insert(datagram.end(), hb.begin(), hb.end());
  datagram.push_back(0xFD);  // and a lone start byte at the very end
  FrameParser parser;
  ASSERT_EQ(parser.feed(datagram), datagram.size());
  Frame f;
  EXPECT_FALSE(parser.next(f));
  ASSERT_TRUE(parser.finish(f));
  EXPECT_EQ(f.header.sequence, 7);
  EXPECT_FALSE(parser.finish(f));
  EXPECT_EQ(parser.buffered(), 0U);
  EXPECT_EQ(parser.counters().incomplete_frames, 2U);
}

TEST(MavlinkCodec, SignedFramesAreSkippedCleanly) {
  // The heartbeat re-signed: incompat flag 0x01, CRC recomputed, 13 signature bytes appended.
  auto hb = from_hex(kNodeHeartbeat);
  hb[2] = kIncompatSigned;
  const std::uint16_t crc =
      crc_x25(crc_x25(0xFFFF, std::span<const std::uint8_t>(hb.data() + 1, 9 + 9)), 50);
  hb[19] = static_cast<std::uint8_t>(crc & 0xFF);
  hb[20] = static_cast<std::uint8_t>(crc >> 8);
  hb.insert(hb.end(), 13, 0xAB);
  const auto plain = from_hex(kNodeHeartbeat);
  hb.insert(hb.end(), plain.begin(), plain.end());
  FrameParser parser;
  const auto frames = parse_all(hb, parser, true);
  ASSERT_EQ(frames.size(), 1U);  // only the unsigned one
  EXPECT_EQ(frames[0].header.sequence, 7);
  EXPECT_EQ(parser.counters().signed_skipped, 1U);
  EXPECT_EQ(parser.counters().crc_errors, 0U);
}

TEST(MavlinkCodec, ParserKeepsUpWithBackToBackFrames) {
  FrameWriter writer(1, 1);
  std::vector<std::uint8_t> stream;
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  StatusText t;
  t.text.fill('x');
  t.id = 7;
  t.chunk_seq = 1;
  for (int i = 0; i < 20; ++i) {
    const std::size_t n = write_message(writer, t, out);
    stream.insert(stream.end(), out.begin(), out.begin() + n);
  }
  FrameParser parser;
  const auto frames = parse_all(stream, parser, false);
  ASSERT_EQ(frames.size(), 20U);
  StatusText back;
  ASSERT_TRUE(unpack(frames[19], back));
  EXPECT_EQ(back.id, 7);
  EXPECT_EQ(back.chunk_seq, 1);
  EXPECT_EQ(text_of(back.text), std::string(50, 'x'));
}

// The codec will run next to the tick: encoding, parsing and unpacking must not touch the heap.
TEST(MavlinkCodec, EncodeParseAndUnpackAllocateNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "no malloc hooks under AddressSanitizer";
  }
  FrameWriter writer(255, 190);
  FrameParser parser;
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  Frame f;
  StatusText text;
  ManualControl manual;
  CommandLong command;
  const std::array<std::uint8_t, 5> garbage{0xFD, 0x40, 0x00, 0x13, 0x37};
  const std::uint64_t before = rovctl::testing::t_allocations;
  std::size_t frames = 0;
  for (int i = 0; i < 100; ++i) {
    set_text(text.text, "FAILSAFE camera lost");
    manual.x = static_cast<std::int16_t>(i);
    const std::size_t lengths[] = {write_message(writer, manual, out),
                                   write_message(writer, text, out),
                                   write_message(writer, arm_disarm(1, 1, true, false), out)};
    parser.feed(garbage);
    for (const std::size_t n : lengths) {
      ASSERT_GT(n, 0U);
    }
    const std::size_t n = write_message(writer, manual, out);
    parser.feed(std::span<const std::uint8_t>(out.data(), n));
    while (parser.next(f) || parser.finish(f)) {
      frames += unpack(f, manual) ? 1 : 0;
      unpack(f, text);
      unpack(f, command);
    }
  }
  EXPECT_EQ(rovctl::testing::t_allocations - before, 0U);
  EXPECT_EQ(frames, 100U);  // the allocation count above is of real work
}

// The link's steady state (send, receive, parse) is as allocation-free as the codec.
TEST(MavlinkUdpLink, SendAndReceiveAllocateNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) {
    GTEST_SKIP() << "no malloc hooks under AddressSanitizer";
  }
  std::string error;
  MavlinkUdpLink rx;
  ASSERT_TRUE(rx.open(UdpEndpoint{UdpEndpoint::Mode::listen, "127.0.0.1", 0}, error)) << error;
  MavlinkUdpLink tx;
  ASSERT_TRUE(
      tx.open(UdpEndpoint{UdpEndpoint::Mode::send_to, "127.0.0.1", rx.local_port()}, error));
  FrameWriter writer(255, 190);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  Frame f;
  Heartbeat hb;
  std::size_t received = 0;
  const std::uint64_t before = rovctl::testing::t_allocations;
  for (int i = 0; i < 50; ++i) {
    hb.custom_mode = static_cast<std::uint32_t>(i);
    ASSERT_EQ(tx.send({out.data(), write_message(writer, hb, out)}), MavlinkUdpLink::Io::ok);
    for (int spin = 0; spin < 100000 && rx.receive(f) != MavlinkUdpLink::Io::ok; ++spin) {
    }
    received += unpack(f, hb) && hb.custom_mode == static_cast<std::uint32_t>(i) ? 1 : 0;
    EXPECT_EQ(rx.receive(f), MavlinkUdpLink::Io::would_block);
  }
  EXPECT_EQ(rovctl::testing::t_allocations - before, 0U);
  EXPECT_EQ(received, 50U);
}

}  // namespace
}  // namespace rovctl::drivers::mavlink
