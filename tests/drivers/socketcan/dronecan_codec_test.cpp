// DroneCAN codec against vectors derived by hand from the specification and cross-checked by
// tests/drivers/socketcan/dronecan_vectors.py (pydronecan-style serialisation, binascii CRC).
#include "drivers/socketcan/dronecan_codec.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace rovctl::drivers::dronecan {
namespace {

std::vector<std::uint8_t> bytes_of(const CanFrame& f) {
  return {f.data.begin(), f.data.begin() + f.len};
}

TEST(DronecanCodec, SignaturesAndIds) {
  EXPECT_EQ(kRawCommandId, 1030);
  EXPECT_EQ(kRawCommandSignature, 0x217F5C87D7EC951DULL);
  EXPECT_EQ(kStatusId, 1034);
  EXPECT_EQ(kStatusSignature, 0xA9AF28AEA2FBB254ULL);
}

TEST(DronecanCodec, CrcIsCcittFalse) {
  const std::array<std::uint8_t, 9> check{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc16_ccitt_false(0xFFFF, check), 0x29B1);  // the catalogue's check value
}

TEST(DronecanCodec, CanIdLayout) {
  // priority 8 << 24 | 1030 << 8 | service 0 | node 10
  EXPECT_EQ(message_can_id(8, kRawCommandId, 10), 0x0804060AU);
  const CanIdFields f = parse_can_id(0x10040A14U);
  EXPECT_EQ(f.priority, 16);
  EXPECT_EQ(f.data_type_id, kStatusId);
  EXPECT_FALSE(f.service);
  EXPECT_EQ(f.source_node_id, 20);
  EXPECT_EQ(tail_byte(true, true, false, 0), 0xC0);
  EXPECT_EQ(tail_byte(false, false, true, 31), 0x3F);
}

// V1, by hand: int14 values go out low byte first, then the high 6 bits, each MSB first:
// 8191 -> 11111111 011111, -1 -> 11111111 111111, 0 -> 00000000 000000, 4096 -> 00000000 010000;
// regrouped into bytes: FF 7F FF F0 00 00 10. Seven bytes: a single frame, tail 0xC0 | tid.
TEST(DronecanCodec, RawCommandSingleFrameVector) {
  const std::array<std::int16_t, 4> cmd{8191, -1, 0, 4096};
  std::array<std::uint8_t, kRawCommandMaxBytes> payload{};
  const std::size_t len = encode_raw_command(cmd, payload);
  ASSERT_EQ(len, 7U);
  std::array<CanFrame, 4> frames{};
  ASSERT_EQ(make_transfer_frames(message_can_id(8, kRawCommandId, 10), kRawCommandSignature,
                                 {payload.data(), len}, 0, frames),
            1U);
  EXPECT_EQ(frames[0].id, 0x0804060AU);
  EXPECT_EQ(bytes_of(frames[0]),
            (std::vector<std::uint8_t>{0xFF, 0x7F, 0xFF, 0xF0, 0x00, 0x00, 0x10, 0xC0}));
}

// V2: eight commands = 112 bits = 14 bytes: multi-frame, transfer CRC first (low byte first).
TEST(DronecanCodec, RawCommandMultiFrameVector) {
  const std::array<std::int16_t, 8> cmd{0, 1000, -1000, 8191, -8191, 1, -1, 4095};
  std::array<std::uint8_t, kRawCommandMaxBytes> payload{};
  const std::size_t len = encode_raw_command(cmd, payload);
  ASSERT_EQ(len, 14U);
  EXPECT_EQ(transfer_crc(kRawCommandSignature, {payload.data(), len}), 0x5145);
  std::array<CanFrame, 4> frames{};
  ASSERT_EQ(make_transfer_frames(message_can_id(8, kRawCommandId, 10), kRawCommandSignature,
                                 {payload.data(), len}, 31, frames),
            3U);
  EXPECT_EQ(bytes_of(frames[0]),
            (std::vector<std::uint8_t>{0x45, 0x51, 0x00, 0x03, 0xA0, 0x31, 0x8F, 0x9F}));
  EXPECT_EQ(bytes_of(frames[1]),
            (std::vector<std::uint8_t>{0x3F, 0xDF, 0x01, 0x80, 0x04, 0x0F, 0xFF, 0x3F}));
  EXPECT_EQ(bytes_of(frames[2]), (std::vector<std::uint8_t>{0xFF, 0xCF, 0x5F}));
}

// V3: esc.Status, 110 bits in 14 bytes, from node 20 with priority 16 and transfer ID 7.
const std::vector<std::vector<std::uint8_t>> kStatusFrames{
    {0x03, 0x38, 0x05, 0x00, 0x00, 0x00, 0x00, 0x87},
    {0x4C, 0x00, 0x41, 0xB0, 0x5C, 0x24, 0xFA, 0x27},
    {0xD5, 0x0C, 0x47}};

CanFrame frame_of(std::uint32_t id, const std::vector<std::uint8_t>& data) {
  CanFrame f;
  f.id = id;
  f.len = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), f.data.begin());
  return f;
}

EscStatus v3_status() {
  EscStatus s;
  s.error_count = 5;
  s.voltage_v = 16.0F;
  s.current_a = 2.5F;
  s.temperature_k = 300.0F;
  s.rpm = -1500;
  s.power_rating_pct = 42;
  s.esc_index = 3;
  return s;
}

TEST(DronecanCodec, StatusVectorEncodes) {
  std::array<std::uint8_t, kStatusBytes> payload{};
  ASSERT_EQ(encode_status(v3_status(), payload), kStatusBytes);
  std::array<CanFrame, 4> frames{};
  ASSERT_EQ(
      make_transfer_frames(message_can_id(16, kStatusId, 20), kStatusSignature, payload, 7, frames),
      3U);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(frames[i].id, 0x10040A14U);
    EXPECT_EQ(bytes_of(frames[i]), kStatusFrames[i]) << "frame " << i;
  }
}

TEST(DronecanCodec, StatusVectorReassemblesAndDecodes) {
  TransferReassembler rx(kStatusId, kStatusSignature);
  EXPECT_FALSE(rx.accept(frame_of(0x10040A14U, kStatusFrames[0])));
  EXPECT_FALSE(rx.accept(frame_of(0x10040A14U, kStatusFrames[1])));
  ASSERT_TRUE(rx.accept(frame_of(0x10040A14U, kStatusFrames[2])));
  EXPECT_EQ(rx.source_node_id(), 20);
  EscStatus s;
  ASSERT_TRUE(decode_status(rx.payload(), s));
  EXPECT_EQ(s.error_count, 5U);
  EXPECT_FLOAT_EQ(s.voltage_v, 16.0F);
  EXPECT_FLOAT_EQ(s.current_a, 2.5F);
  EXPECT_FLOAT_EQ(s.temperature_k, 300.0F);
  EXPECT_EQ(s.rpm, -1500);
  EXPECT_EQ(s.power_rating_pct, 42);
  EXPECT_EQ(s.esc_index, 3);
}

TEST(DronecanCodec, ReassemblerRejectsCorruption) {
  TransferReassembler rx(kStatusId, kStatusSignature);
  auto corrupt = kStatusFrames[1];
  corrupt[3] ^= 0x01;  // one payload bit: only the transfer CRC can tell
  rx.accept(frame_of(0x10040A14U, kStatusFrames[0]));
  rx.accept(frame_of(0x10040A14U, corrupt));
  EXPECT_FALSE(rx.accept(frame_of(0x10040A14U, kStatusFrames[2])));
  EXPECT_EQ(rx.crc_errors, 1U);

  // A lost middle frame: the last frame's toggle is then wrong.
  rx.accept(frame_of(0x10040A14U, kStatusFrames[0]));
  EXPECT_FALSE(rx.accept(frame_of(0x10040A14U, kStatusFrames[2])));
  EXPECT_EQ(rx.toggle_errors, 1U);

  // A continuation without its start.
  EXPECT_FALSE(rx.accept(frame_of(0x10040A14U, kStatusFrames[1])));
  EXPECT_EQ(rx.missed_starts, 1U);

  // Another data type is not ours.
  EXPECT_FALSE(rx.accept(frame_of(message_can_id(16, kRawCommandId, 20), kStatusFrames[0])));
}

TEST(DronecanCodec, ReassemblerKeepsNodesApart) {
  TransferReassembler rx(kStatusId, kStatusSignature);
  std::array<std::uint8_t, kStatusBytes> payload{};
  EscStatus a = v3_status();
  a.esc_index = 1;
  encode_status(a, payload);
  std::array<CanFrame, 3> fa{};
  make_transfer_frames(message_can_id(16, kStatusId, 21), kStatusSignature, payload, 4, fa);
  EscStatus b = v3_status();
  b.esc_index = 2;
  b.rpm = 1234;
  encode_status(b, payload);
  std::array<CanFrame, 3> fb{};
  make_transfer_frames(message_can_id(16, kStatusId, 22), kStatusSignature, payload, 9, fb);
  // Interleaved frames of two ESC nodes.
  EXPECT_FALSE(rx.accept(fa[0]));
  EXPECT_FALSE(rx.accept(fb[0]));
  EXPECT_FALSE(rx.accept(fa[1]));
  EXPECT_FALSE(rx.accept(fb[1]));
  ASSERT_TRUE(rx.accept(fa[2]));
  EscStatus got;
  ASSERT_TRUE(decode_status(rx.payload(), got));
  EXPECT_EQ(got.esc_index, 1);
  ASSERT_TRUE(rx.accept(fb[2]));
  ASSERT_TRUE(decode_status(rx.payload(), got));
  EXPECT_EQ(got.esc_index, 2);
  EXPECT_EQ(got.rpm, 1234);
  EXPECT_EQ(rx.source_node_id(), 22);
}

TEST(DronecanCodec, RawCommandRoundTripAndSaturation) {
  const std::array<std::int16_t, 5> cmd{-8192, 8191, 12000, -12000, -3};
  std::array<std::uint8_t, kRawCommandMaxBytes> payload{};
  const std::size_t len = encode_raw_command(cmd, payload);
  ASSERT_EQ(len, 9U);  // 70 bits
  std::array<std::int16_t, kMaxRawCommands> out{};
  std::size_t count = 0;
  ASSERT_TRUE(decode_raw_command({payload.data(), len}, out, count));
  ASSERT_EQ(count, 5U);
  EXPECT_EQ(out[0], -8192);
  EXPECT_EQ(out[1], 8191);
  EXPECT_EQ(out[2], 8191);  // saturated, not wrapped
  EXPECT_EQ(out[3], -8192);
  EXPECT_EQ(out[4], -3);
  const std::array<std::int16_t, kMaxRawCommands + 1> too_many{};
  EXPECT_EQ(encode_raw_command(too_many, payload), 0U);
}

TEST(DronecanCodec, FractionScaling) {
  EXPECT_EQ(raw_command_from_fraction(1.0), 8191);
  EXPECT_EQ(raw_command_from_fraction(-1.0), -8191);
  EXPECT_EQ(raw_command_from_fraction(2.0), 8191);
  EXPECT_EQ(raw_command_from_fraction(0.5), 4096);
  EXPECT_EQ(raw_command_from_fraction(std::nan("")), 0);
}

TEST(DronecanCodec, Float16) {
  EXPECT_EQ(float16_from_float(1.0F), 0x3C00);
  EXPECT_EQ(float16_from_float(-2.0F), 0xC000);
  EXPECT_EQ(float16_from_float(65504.0F), 0x7BFF);
  EXPECT_EQ(float16_from_float(1e6F), 0x7C00);
  EXPECT_EQ(float16_from_float(300.0F), 0x5CB0);
  EXPECT_TRUE(std::isnan(float_from_float16(float16_from_float(NAN))));
  EXPECT_FLOAT_EQ(float_from_float16(0x0001), 5.9604645e-08F);
  EXPECT_FLOAT_EQ(float_from_float16(float16_from_float(16.25F)), 16.25F);
}

}  // namespace
}  // namespace rovctl::drivers::dronecan
