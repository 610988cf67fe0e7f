// MAVLink v2 framing after the protocol's serialization page and the C reference
// (mavlink_helpers.h): CRC over header bytes 1..9 and the payload, then CRC_EXTRA.
#include "drivers/mavlink/mavlink_codec.hpp"

#include <algorithm>
#include <cstring>

namespace rovctl::drivers::mavlink {
namespace {

// From message_definitions/v1.0/common.xml and minimal.xml (mavlink/mavlink master): lengths
// are the sums of the field sizes, CRC_EXTRA as mavgen computes it.
constexpr std::array<MessageInfo, 13> kMessages{{
    {0, 9, 9, 50, "HEARTBEAT"},
    {1, 31, 43, 124, "SYS_STATUS"},
    {20, 20, 20, 214, "PARAM_REQUEST_READ"},
    {22, 25, 25, 220, "PARAM_VALUE"},
    {31, 32, 48, 246, "ATTITUDE_QUATERNION"},
    {69, 11, 30, 243, "MANUAL_CONTROL"},
    {70, 18, 38, 124, "RC_CHANNELS_OVERRIDE"},
    {74, 20, 20, 20, "VFR_HUD"},
    {76, 33, 33, 152, "COMMAND_LONG"},
    {77, 3, 10, 143, "COMMAND_ACK"},
    {137, 14, 16, 195, "SCALED_PRESSURE2"},
    {251, 18, 18, 170, "NAMED_VALUE_FLOAT"},
    {253, 51, 54, 83, "STATUSTEXT"},
}};

std::uint16_t frame_crc(const std::uint8_t* frame, std::size_t payload_length,
                        std::uint8_t crc_extra) {
  const std::uint16_t crc =
      crc_x25(0xFFFF, std::span<const std::uint8_t>(frame + 1, kHeaderBytes - 1 + payload_length));
  return crc_x25(crc, crc_extra);
}

}  // namespace

std::span<const MessageInfo> message_table() { return kMessages; }

const MessageInfo* find_message(std::uint32_t id) {
  for (const MessageInfo& info : kMessages) {
    if (info.id == id) {
      return &info;
    }
  }
  return nullptr;
}

std::uint16_t crc_x25(std::uint16_t crc, std::uint8_t byte) {
  auto tmp = static_cast<std::uint8_t>(byte ^ (crc & 0xFFU));
  tmp = static_cast<std::uint8_t>(tmp ^ (tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

std::uint16_t crc_x25(std::uint16_t crc, std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t byte : bytes) {
    crc = crc_x25(crc, byte);
  }
  return crc;
}

std::size_t encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload,
                         std::span<std::uint8_t> out) {
  const MessageInfo* info = find_message(header.message_id);
  if (info == nullptr || payload.size() > info->max_length) {
    return 0;
  }
  std::size_t length = payload.size();
  while (length > 1 && payload[length - 1] == 0) {
    --length;
  }
  const std::size_t total = kHeaderBytes + length + kChecksumBytes;
  if (out.size() < total) {
    return 0;
  }
  out[0] = kStx;
  out[1] = static_cast<std::uint8_t>(length);
  out[2] = 0;
  out[3] = 0;
  out[4] = header.sequence;
  out[5] = header.system_id;
  out[6] = header.component_id;
  out[7] = static_cast<std::uint8_t>(header.message_id & 0xFFU);
  out[8] = static_cast<std::uint8_t>((header.message_id >> 8) & 0xFFU);
  out[9] = static_cast<std::uint8_t>((header.message_id >> 16) & 0xFFU);
  if (length > 0) {
    std::memcpy(&out[kHeaderBytes], payload.data(), length);
  }
  const std::uint16_t crc = frame_crc(out.data(), length, info->crc_extra);
  out[kHeaderBytes + length] = static_cast<std::uint8_t>(crc & 0xFFU);
  out[kHeaderBytes + length + 1] = static_cast<std::uint8_t>(crc >> 8);
  return total;
}

std::size_t FrameWriter::write(std::uint32_t message_id, std::span<const std::uint8_t> payload,
                               std::span<std::uint8_t> out) {
  const FrameHeader header{sequence_, system_id_, component_id_, message_id};
  const std::size_t n = encode_frame(header, payload, out);
  if (n > 0) {
    sequence_ = static_cast<std::uint8_t>(sequence_ + 1);
  }
  return n;
}

std::size_t FrameParser::feed(std::span<const std::uint8_t> bytes) {
  if (end_ + bytes.size() > window_.size() && begin_ > 0) {
    std::memmove(window_.data(), window_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t taken = std::min(bytes.size(), window_.size() - end_);
  if (taken > 0) {
    std::memcpy(window_.data() + end_, bytes.data(), taken);
    end_ += taken;
  }
  return taken;
}

bool FrameParser::next(Frame& frame) {
  while (true) {
    while (begin_ < end_ && window_[begin_] != kStx) {
      ++begin_;
      ++counters_.garbage_bytes;
    }
    const std::size_t available = end_ - begin_;
    if (available < kHeaderBytes) {
      return false;
    }
    const std::uint8_t* p = window_.data() + begin_;
    const std::uint8_t length = p[1];
    const std::uint8_t incompat = p[2];
    if ((incompat & ~kIncompatSigned) != 0) {
      ++counters_.bad_incompat_flags;
      drop(1);
      continue;
    }
    const std::uint32_t message_id = static_cast<std::uint32_t>(p[7]) |
                                     (static_cast<std::uint32_t>(p[8]) << 8) |
                                     (static_cast<std::uint32_t>(p[9]) << 16);
    const MessageInfo* info = find_message(message_id);
    if (info == nullptr) {
      // Without its CRC_EXTRA the frame cannot be checked, so its length cannot be trusted
      // either: skip the start byte only.
      ++counters_.unknown_ids;
      drop(1);
      continue;
    }
    const bool is_signed = (incompat & kIncompatSigned) != 0;
    const std::size_t total =
        kHeaderBytes + length + kChecksumBytes + (is_signed ? kSignatureBytes : 0);
    if (available < total) {
      return false;
    }
    const std::uint16_t wire_crc =
        static_cast<std::uint16_t>(p[kHeaderBytes + length] | (p[kHeaderBytes + length + 1] << 8));
    if (wire_crc != frame_crc(p, length, info->crc_extra)) {
      ++counters_.crc_errors;
      drop(1);
      continue;
    }
    if (is_signed) {
      ++counters_.signed_skipped;
      drop(total);
      continue;
    }
    frame.header = FrameHeader{p[4], p[5], p[6], message_id};
    frame.wire_length = length;
    frame.compat_flags = p[3];
    std::memcpy(frame.payload.data(), p + kHeaderBytes, length);
    std::fill(frame.payload.begin() + length, frame.payload.end(), std::uint8_t{0});
    drop(total);
    ++counters_.frames;
    return true;
  }
}

bool FrameParser::finish(Frame& frame) {
  while (buffered() > 0) {
    if (next(frame)) {
      return true;
    }
    if (buffered() > 0) {
      ++counters_.incomplete_frames;
      drop(1);
    }
  }
  reset();
  return false;
}

}  // namespace rovctl::drivers::mavlink
