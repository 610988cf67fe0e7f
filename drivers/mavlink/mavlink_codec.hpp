// MAVLink v2 framing without I/O: the frame layout, the X.25 CRC seeded with each message's
// CRC_EXTRA, an encoder that numbers frames, and a parser that resyncs on garbage.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rovctl::drivers::mavlink {

constexpr std::uint8_t kStx = 0xFD;
constexpr std::size_t kHeaderBytes = 10;  // STX, len, incompat, compat, seq, sys, comp, msgid[3]
constexpr std::size_t kChecksumBytes = 2;
constexpr std::size_t kSignatureBytes = 13;
constexpr std::size_t kMaxPayloadBytes = 255;
constexpr std::size_t kMaxFrameBytes =
    kHeaderBytes + kMaxPayloadBytes + kChecksumBytes + kSignatureBytes;
constexpr std::uint8_t kIncompatSigned = 0x01;

// What the codec knows of a message: v2 wire length without extensions (min) and with them
// (max), and the CRC_EXTRA seed derived from its definition (common.xml / minimal.xml).
struct MessageInfo {
  std::uint32_t id = 0;
  std::uint8_t min_length = 0;
  std::uint8_t max_length = 0;
  std::uint8_t crc_extra = 0;
  const char* name = "";
};

// Every message rovctl speaks; the unit tests recompute each entry from the definitions.
std::span<const MessageInfo> message_table();
// nullptr for an id outside the table.
const MessageInfo* find_message(std::uint32_t id);

// CRC-16/MCRF4XX as MAVLink's crc_accumulate (X.25 polynomial, reflected, init 0xFFFF).
std::uint16_t crc_x25(std::uint16_t crc, std::uint8_t byte);
std::uint16_t crc_x25(std::uint16_t crc, std::span<const std::uint8_t> bytes);

struct FrameHeader {
  std::uint8_t sequence = 0;
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint32_t message_id = 0;
};

// One unsigned v2 frame into `out`: trailing zero bytes of `payload` are cut as v2 allows (one
// byte is kept, as the C reference does). Returns the frame length, 0 when the id is not in the
// table, the payload is longer than the message or `out` is too small.
std::size_t encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload,
                         std::span<std::uint8_t> out);

// A decoded frame; `payload` is zero past `wire_length`, so a truncated payload reads as the
// full message with zeros, as v2 requires.
struct Frame {
  FrameHeader header;
  std::uint8_t wire_length = 0;
  std::uint8_t compat_flags = 0;
  std::array<std::uint8_t, kMaxPayloadBytes> payload{};
};

// Numbers the frames one sender emits (sequence wraps at 256) under fixed system and
// component ids.
class FrameWriter {
 public:
  FrameWriter(std::uint8_t system_id, std::uint8_t component_id)
      : system_id_(system_id), component_id_(component_id) {}

  // As encode_frame; the sequence advances only when a frame was written.
  std::size_t write(std::uint32_t message_id, std::span<const std::uint8_t> payload,
                    std::span<std::uint8_t> out);
  std::uint8_t next_sequence() const { return sequence_; }
  std::uint8_t system_id() const { return system_id_; }
  std::uint8_t component_id() const { return component_id_; }

 private:
  std::uint8_t system_id_;
  std::uint8_t component_id_;
  std::uint8_t sequence_ = 0;
};

struct ParserCounters {
  std::uint64_t frames = 0;
  std::uint64_t garbage_bytes = 0;       // bytes skipped while looking for a start byte
  std::uint64_t crc_errors = 0;          // known id, checksum wrong: resynced after its STX
  std::uint64_t unknown_ids = 0;         // id outside the table (no CRC_EXTRA to check it)
  std::uint64_t signed_skipped = 0;      // well-formed signed frames, dropped (no signing)
  std::uint64_t bad_incompat_flags = 0;  // incompatibility flags we do not understand
  std::uint64_t incomplete_frames = 0;   // start bytes whose frame the input ended inside
};

// Reassembles frames from a byte stream in a fixed window. A start byte whose frame fails its
// checks costs one byte, and the search resumes right after it, so a false STX in garbage
// cannot swallow the real frame that follows. Feed bytes (one at a time or a datagram) and
// call next() until it returns false.
class FrameParser {
 public:
  // Takes as many bytes as the window holds; returns how many were taken. Never fewer than
  // the whole span once next() has been drained.
  std::size_t feed(std::span<const std::uint8_t> bytes);
  // The next complete, checked frame, if any.
  bool next(Frame& frame);
  // As next() at the end of the input (a datagram's end): a frame still incomplete never will
  // be, so its start byte is dropped and the search goes on in the bytes after it. Leaves the
  // window empty when it returns false.
  bool finish(Frame& frame);
  // Drops what is buffered (e.g. at a datagram boundary, where a frame cannot continue).
  void reset() { begin_ = end_ = 0; }
  std::size_t buffered() const { return end_ - begin_; }
  const ParserCounters& counters() const { return counters_; }

 private:
  void drop(std::size_t count) { begin_ += count; }
  std::array<std::uint8_t, 2 * kMaxFrameBytes> window_{};
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  ParserCounters counters_;
};

}  // namespace rovctl::drivers::mavlink
