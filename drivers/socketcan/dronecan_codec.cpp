// DroneCAN bit packing follows libcanard/pydronecan: a scalar goes out least significant byte
// first, each byte (the last one possibly partial) most significant bit first.
#include "drivers/socketcan/dronecan_codec.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace rovctl::drivers::dronecan {
namespace {

void put_bits(std::span<std::uint8_t> buf, std::size_t& offset, std::uint64_t value,
              unsigned bits) {
  for (unsigned k = 0; 8 * k < bits; ++k) {
    const unsigned chunk = std::min(8U, bits - 8 * k);
    const unsigned byte = static_cast<unsigned>(value >> (8 * k)) & ((1U << chunk) - 1U);
    for (int b = static_cast<int>(chunk) - 1; b >= 0; --b, ++offset) {
      const auto mask = static_cast<std::uint8_t>(0x80U >> (offset % 8));
      if ((byte >> b) & 1U) {
        buf[offset / 8] = static_cast<std::uint8_t>(buf[offset / 8] | mask);
      } else {
        buf[offset / 8] = static_cast<std::uint8_t>(buf[offset / 8] & ~mask);
      }
    }
  }
}

std::uint64_t get_bits(std::span<const std::uint8_t> buf, std::size_t& offset, unsigned bits) {
  std::uint64_t value = 0;
  for (unsigned k = 0; 8 * k < bits; ++k) {
    const unsigned chunk = std::min(8U, bits - 8 * k);
    std::uint64_t byte = 0;
    for (unsigned b = 0; b < chunk; ++b, ++offset) {
      byte = (byte << 1) | ((buf[offset / 8] >> (7 - offset % 8)) & 1U);
    }
    value |= byte << (8 * k);
  }
  return value;
}

std::int64_t sign_extend(std::uint64_t value, unsigned bits) {
  const std::uint64_t sign = 1ULL << (bits - 1);
  return static_cast<std::int64_t>((value ^ sign)) - static_cast<std::int64_t>(sign);
}

std::size_t bytes_for_bits(std::size_t bits) { return (bits + 7) / 8; }

}  // namespace

std::uint32_t message_can_id(int priority, std::uint16_t data_type_id, int source_node_id) {
  return (static_cast<std::uint32_t>(priority & 0x1F) << 24) |
         (static_cast<std::uint32_t>(data_type_id) << 8) |
         static_cast<std::uint32_t>(source_node_id & 0x7F);
}

CanIdFields parse_can_id(std::uint32_t id) {
  CanIdFields f;
  f.priority = static_cast<std::uint8_t>((id >> 24) & 0x1F);
  f.service = ((id >> 7) & 1U) != 0;
  f.data_type_id = f.service ? static_cast<std::uint16_t>((id >> 16) & 0xFF)
                             : static_cast<std::uint16_t>((id >> 8) & 0xFFFF);
  f.source_node_id = static_cast<std::uint8_t>(id & 0x7F);
  return f;
}

std::uint8_t tail_byte(bool start, bool end, bool toggle, std::uint8_t transfer_id) {
  return static_cast<std::uint8_t>((start ? 0x80U : 0U) | (end ? 0x40U : 0U) |
                                   (toggle ? 0x20U : 0U) | (transfer_id & 0x1FU));
}

std::uint16_t crc16_ccitt_false(std::uint16_t crc, std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t byte : bytes) {
    crc = static_cast<std::uint16_t>(crc ^ (static_cast<unsigned>(byte) << 8));
    for (int i = 0; i < 8; ++i) {
      crc = (crc & 0x8000U) ? static_cast<std::uint16_t>((crc << 1) ^ 0x1021U)
                            : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

std::uint16_t transfer_crc(std::uint64_t signature, std::span<const std::uint8_t> payload) {
  std::array<std::uint8_t, 8> sig{};
  for (std::size_t i = 0; i < 8; ++i) sig[i] = static_cast<std::uint8_t>(signature >> (8 * i));
  return crc16_ccitt_false(crc16_ccitt_false(0xFFFF, sig), payload);
}

std::size_t make_transfer_frames(std::uint32_t can_id, std::uint64_t signature,
                                 std::span<const std::uint8_t> payload, std::uint8_t transfer_id,
                                 std::span<CanFrame> frames) {
  if (payload.size() <= 7) {
    if (frames.empty()) return 0;
    CanFrame& f = frames[0];
    f.id = can_id;
    std::copy(payload.begin(), payload.end(), f.data.begin());
    f.data[payload.size()] = tail_byte(true, true, false, transfer_id);
    f.len = static_cast<std::uint8_t>(payload.size() + 1);
    return 1;
  }
  const std::uint16_t crc = transfer_crc(signature, payload);
  const std::size_t total = payload.size() + 2;  // CRC, then payload, 7 bytes per frame
  const std::size_t count = (total + 6) / 7;
  if (frames.size() < count) return 0;
  std::size_t src = 0;
  for (std::size_t n = 0; n < count; ++n) {
    CanFrame& f = frames[n];
    f.id = can_id;
    std::size_t i = 0;
    if (n == 0) {
      f.data[0] = static_cast<std::uint8_t>(crc & 0xFF);
      f.data[1] = static_cast<std::uint8_t>(crc >> 8);
      i = 2;
    }
    for (; i < 7 && src < payload.size(); ++i) f.data[i] = payload[src++];
    f.data[i] = tail_byte(n == 0, n + 1 == count, (n % 2) == 1, transfer_id);
    f.len = static_cast<std::uint8_t>(i + 1);
  }
  return count;
}

std::int16_t raw_command_from_fraction(double thrust_fraction) {
  if (!std::isfinite(thrust_fraction)) return 0;
  const double clamped = std::clamp(thrust_fraction, -1.0, 1.0);
  return static_cast<std::int16_t>(std::lround(clamped * kRawCommandFullScale));
}

std::size_t encode_raw_command(std::span<const std::int16_t> commands,
                               std::span<std::uint8_t> payload) {
  if (commands.size() > kMaxRawCommands) return 0;
  const std::size_t len = bytes_for_bits(14 * commands.size());
  if (payload.size() < len) return 0;
  std::fill_n(payload.begin(), len, std::uint8_t{0});
  std::size_t offset = 0;
  for (const std::int16_t c : commands) {
    const int saturated = std::clamp<int>(c, -8192, 8191);  // DSDL "saturated int14"
    put_bits(payload, offset, static_cast<std::uint64_t>(saturated) & 0x3FFFU, 14);
  }
  return len;
}

bool decode_raw_command(std::span<const std::uint8_t> payload,
                        std::array<std::int16_t, kMaxRawCommands>& commands, std::size_t& count) {
  // Tail array: as many whole elements as the payload holds (padding is under 8 bits).
  count = payload.size() * 8 / 14;
  if (count > kMaxRawCommands || bytes_for_bits(14 * count) != payload.size()) return false;
  std::size_t offset = 0;
  for (std::size_t i = 0; i < count; ++i) {
    commands[i] = static_cast<std::int16_t>(sign_extend(get_bits(payload, offset, 14), 14));
  }
  return true;
}

std::size_t encode_status(const EscStatus& s, std::span<std::uint8_t> payload) {
  if (payload.size() < kStatusBytes) return 0;
  std::fill_n(payload.begin(), kStatusBytes, std::uint8_t{0});
  std::size_t offset = 0;
  put_bits(payload, offset, s.error_count, 32);
  put_bits(payload, offset, float16_from_float(s.voltage_v), 16);
  put_bits(payload, offset, float16_from_float(s.current_a), 16);
  put_bits(payload, offset, float16_from_float(s.temperature_k), 16);
  const std::int32_t rpm = std::clamp(s.rpm, -131072, 131071);  // saturated int18
  put_bits(payload, offset, static_cast<std::uint64_t>(rpm) & 0x3FFFFU, 18);
  put_bits(payload, offset, std::min<unsigned>(s.power_rating_pct, 127U), 7);
  put_bits(payload, offset, s.esc_index & 0x1FU, 5);
  return kStatusBytes;
}

bool decode_status(std::span<const std::uint8_t> payload, EscStatus& s) {
  if (payload.size() < kStatusBytes) return false;
  std::size_t offset = 0;
  s.error_count = static_cast<std::uint32_t>(get_bits(payload, offset, 32));
  s.voltage_v = float_from_float16(static_cast<std::uint16_t>(get_bits(payload, offset, 16)));
  s.current_a = float_from_float16(static_cast<std::uint16_t>(get_bits(payload, offset, 16)));
  s.temperature_k = float_from_float16(static_cast<std::uint16_t>(get_bits(payload, offset, 16)));
  s.rpm = static_cast<std::int32_t>(sign_extend(get_bits(payload, offset, 18), 18));
  s.power_rating_pct = static_cast<std::uint8_t>(get_bits(payload, offset, 7));
  s.esc_index = static_cast<std::uint8_t>(get_bits(payload, offset, 5));
  return true;
}

std::uint16_t float16_from_float(float value) {
  const std::uint32_t f = std::bit_cast<std::uint32_t>(value);
  const auto sign = static_cast<std::uint16_t>((f >> 16) & 0x8000U);
  const std::uint32_t abs = f & 0x7FFFFFFFU;
  if (abs >= 0x7F800000U) {  // inf or NaN
    return static_cast<std::uint16_t>(sign | (abs > 0x7F800000U ? 0x7E00U : 0x7C00U));
  }
  if (abs >= 0x477FF000U) return static_cast<std::uint16_t>(sign | 0x7C00U);  // rounds past max
  if (abs < 0x38800000U) {  // subnormal half (or zero)
    const float magnitude = std::bit_cast<float>(abs);
    return static_cast<std::uint16_t>(
        sign | static_cast<std::uint16_t>(std::nearbyint(magnitude * 16777216.0F)));  // / 2^-24
  }
  // Normal: rebias the exponent, round the 13 dropped mantissa bits to nearest even.
  const std::uint32_t rebias = abs - ((127U - 15U) << 23);
  const std::uint32_t half = rebias >> 13;
  const std::uint32_t rest = rebias & 0x1FFFU;
  const std::uint32_t rounded =
      half + ((rest > 0x1000U || (rest == 0x1000U && (half & 1U))) ? 1 : 0);
  return static_cast<std::uint16_t>(sign | rounded);
}

float float_from_float16(std::uint16_t h) {
  const std::uint32_t sign = static_cast<std::uint32_t>(h & 0x8000U) << 16;
  const std::uint32_t exponent = (h >> 10) & 0x1FU;
  const std::uint32_t mantissa = h & 0x3FFU;
  float magnitude = 0.0F;
  if (exponent == 0) {
    magnitude = static_cast<float>(mantissa) / 16777216.0F;
  } else if (exponent == 31) {
    magnitude = mantissa == 0 ? INFINITY : NAN;
  } else {
    magnitude = std::bit_cast<float>(((exponent + 127U - 15U) << 23) | (mantissa << 13));
  }
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(magnitude) | sign);
}

TransferReassembler::TransferReassembler(std::uint16_t data_type_id, std::uint64_t signature)
    : data_type_id_(data_type_id), signature_(signature) {}

bool TransferReassembler::accept(const CanFrame& frame) {
  const CanIdFields id = parse_can_id(frame.id);
  if (id.service || id.data_type_id != data_type_id_ || frame.len < 1 || frame.len > 8) {
    return false;
  }
  const std::uint8_t tail = frame.data[frame.len - 1U];
  const bool start = (tail & 0x80U) != 0;
  const bool end = (tail & 0x40U) != 0;
  const bool toggle = (tail & 0x20U) != 0;
  const auto tid = static_cast<std::uint8_t>(tail & 0x1FU);
  const std::size_t data_len = frame.len - 1U;
  State& s = states_[id.source_node_id];

  if (start && end) {  // single frame
    s.active = false;
    std::copy_n(frame.data.begin(), data_len, s.buf.begin());
    done_payload_ = s.buf.data();
    done_len_ = data_len;
    done_node_ = id.source_node_id;
    return true;
  }
  if (start) {
    if (data_len < 2 || toggle) {
      s.active = false;
      ++toggle_errors;
      return false;
    }
    s.active = true;
    s.toggle = true;  // expected on the next frame
    s.transfer_id = tid;
    s.crc = static_cast<std::uint16_t>(frame.data[0] | (frame.data[1] << 8));
    s.len = data_len - 2;
    std::copy_n(frame.data.begin() + 2, s.len, s.buf.begin());
    return false;
  }
  if (!s.active || tid != s.transfer_id) {
    ++missed_starts;
    return false;
  }
  if (toggle != s.toggle) {
    ++toggle_errors;
    s.active = false;
    return false;
  }
  if (s.len + data_len > s.buf.size()) {
    ++oversize;
    s.active = false;
    return false;
  }
  std::copy_n(frame.data.begin(), data_len, s.buf.begin() + static_cast<std::ptrdiff_t>(s.len));
  s.len += data_len;
  s.toggle = !s.toggle;
  if (!end) return false;
  s.active = false;
  if (transfer_crc(signature_, {s.buf.data(), s.len}) != s.crc) {
    ++crc_errors;
    return false;
  }
  done_payload_ = s.buf.data();
  done_len_ = s.len;
  done_node_ = id.source_node_id;
  return true;
}

}  // namespace rovctl::drivers::dronecan
