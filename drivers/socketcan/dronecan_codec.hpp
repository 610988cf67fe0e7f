// DroneCAN (UAVCAN v0) on classic CAN, pure encode/decode without I/O: CAN ID, tail byte,
// single/multi-frame transfers with the transfer CRC, uavcan.equipment.esc.RawCommand and Status.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rovctl::drivers::dronecan {

// Data type IDs and signatures from the DroneCAN DSDL (uavcan/equipment/esc/1030.RawCommand.uavcan,
// 1034.Status.uavcan). The signatures were recomputed from the normalised DSDL text with
// CRC-64-WE (as pydronecan does) and match libcanard's generated headers.
constexpr std::uint16_t kRawCommandId = 1030;
constexpr std::uint64_t kRawCommandSignature = 0x217F5C87D7EC951DULL;
constexpr std::uint16_t kStatusId = 1034;
constexpr std::uint64_t kStatusSignature = 0xA9AF28AEA2FBB254ULL;

constexpr std::size_t kMaxRawCommands = 20;      // int14[<=20] cmd
constexpr std::size_t kRawCommandMaxBytes = 35;  // 20 * 14 bits, tail-array optimised
constexpr std::size_t kStatusBytes = 14;         // 110 bits
constexpr std::int16_t kRawCommandFullScale = 8191;
constexpr std::size_t kMaxTransferBytes = 64;  // largest transfer the reassembler keeps

// One classic CAN frame; `id` is the 29-bit extended identifier without any flag bits.
struct CanFrame {
  std::uint32_t id = 0;
  std::uint8_t len = 0;
  std::array<std::uint8_t, 8> data{};
};

// Message frame CAN ID: priority (5 bits) << 24 | data type ID (16) << 8 | service=0 (bit 7) |
// source node ID (7 bits).
std::uint32_t message_can_id(int priority, std::uint16_t data_type_id, int source_node_id);

struct CanIdFields {
  std::uint8_t priority = 0;
  std::uint16_t data_type_id = 0;  // messages only
  bool service = false;
  std::uint8_t source_node_id = 0;
};
CanIdFields parse_can_id(std::uint32_t id);

// Tail byte: start of transfer (bit 7), end of transfer (bit 6), toggle (bit 5), transfer ID (0-4).
std::uint8_t tail_byte(bool start, bool end, bool toggle, std::uint8_t transfer_id);

// CRC-16-CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection, no final xor), continued from `crc`.
std::uint16_t crc16_ccitt_false(std::uint16_t crc, std::span<const std::uint8_t> bytes);
// The transfer CRC: CRC-16-CCITT-FALSE over the data type signature (8 bytes, little-endian),
// then the payload.
std::uint16_t transfer_crc(std::uint64_t signature, std::span<const std::uint8_t> payload);

// Splits one transfer into frames as libcanard does: a payload of up to 7 bytes is a single
// frame; a longer one starts with the transfer CRC (low byte first) and alternates the toggle bit
// from 0. Returns the number of frames, 0 when `frames` is too small.
std::size_t make_transfer_frames(std::uint32_t can_id, std::uint64_t signature,
                                 std::span<const std::uint8_t> payload, std::uint8_t transfer_id,
                                 std::span<CanFrame> frames);

// Thrust fraction [-1, 1] to a RawCommand setpoint in [-8191, 8191]; NaN is neutral.
std::int16_t raw_command_from_fraction(double thrust_fraction);

// RawCommand: int14 setpoints, saturated to [-8192, 8191], with the tail-array optimisation (the
// last field's array has no length prefix). Returns the payload length, 0 if it does not fit.
std::size_t encode_raw_command(std::span<const std::int16_t> commands,
                               std::span<std::uint8_t> payload);
// Element count follows from the payload length (what an ESC does); false if malformed.
bool decode_raw_command(std::span<const std::uint8_t> payload,
                        std::array<std::int16_t, kMaxRawCommands>& commands, std::size_t& count);

struct EscStatus {
  std::uint32_t error_count = 0;
  float voltage_v = 0.0F;
  float current_a = 0.0F;
  float temperature_k = 0.0F;
  std::int32_t rpm = 0;  // int18
  std::uint8_t power_rating_pct = 0;
  std::uint8_t esc_index = 0;
};
std::size_t encode_status(const EscStatus& status, std::span<std::uint8_t> payload);
bool decode_status(std::span<const std::uint8_t> payload, EscStatus& status);

// IEEE 754 binary16 conversions (round to nearest even), as DroneCAN's float16.
std::uint16_t float16_from_float(float value);
float float_from_float16(std::uint16_t half);

// Reassembles transfers of one message type from any source node (state per node, no heap).
class TransferReassembler {
 public:
  TransferReassembler(std::uint16_t data_type_id, std::uint64_t signature);

  // Feeds one frame; true when it completes a transfer (then payload()/source_node_id()).
  // Frames of other types and service frames are ignored.
  bool accept(const CanFrame& frame);
  std::span<const std::uint8_t> payload() const { return {done_payload_, done_len_}; }
  std::uint8_t source_node_id() const { return done_node_; }

  std::uint64_t crc_errors = 0;
  std::uint64_t toggle_errors = 0;
  std::uint64_t missed_starts = 0;
  std::uint64_t oversize = 0;

 private:
  struct State {
    bool active = false;
    bool toggle = false;
    std::uint8_t transfer_id = 0;
    std::uint16_t crc = 0;
    std::size_t len = 0;
    std::array<std::uint8_t, kMaxTransferBytes> buf{};
  };
  std::uint16_t data_type_id_;
  std::uint64_t signature_;
  std::array<State, 128> states_{};
  const std::uint8_t* done_payload_ = nullptr;
  std::size_t done_len_ = 0;
  std::uint8_t done_node_ = 0;
};

}  // namespace rovctl::drivers::dronecan
