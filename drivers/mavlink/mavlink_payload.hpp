// A MAVLink payload and the little-endian writer and reader that a message's wire() field list
// drives: the same list packs and unpacks, so the two directions cannot drift apart.
#pragma once

#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <span>

#include "drivers/mavlink/mavlink_codec.hpp"

namespace rovctl::drivers::mavlink {

using Payload = std::array<std::uint8_t, kMaxPayloadBytes>;

namespace detail {

// Writes the fields it is called with, in order; starts from a zeroed payload.
class PayloadWriter {
 public:
  explicit PayloadWriter(Payload& out) : out_(out) { out_.fill(0); }
  template <typename... T>
  void operator()(const T&... fields) {
    (put(fields), ...);
  }
  // The length written; in debug builds, checked against the message's full length.
  std::size_t done(std::uint32_t id) const {
    assert(find_message(id) != nullptr && n_ == find_message(id)->max_length);
    (void)id;
    return n_;
  }

 private:
  void put(std::uint8_t v) { out_[n_++] = v; }
  void put(std::int8_t v) { put(static_cast<std::uint8_t>(v)); }
  void put(char v) { put(static_cast<std::uint8_t>(v)); }
  void put(std::uint16_t v) {
    put(static_cast<std::uint8_t>(v & 0xFFU));
    put(static_cast<std::uint8_t>(v >> 8));
  }
  void put(std::int16_t v) { put(static_cast<std::uint16_t>(v)); }
  void put(std::uint32_t v) {
    put(static_cast<std::uint16_t>(v & 0xFFFFU));
    put(static_cast<std::uint16_t>(v >> 16));
  }
  void put(std::int32_t v) { put(static_cast<std::uint32_t>(v)); }
  void put(float v) { put(std::bit_cast<std::uint32_t>(v)); }
  template <typename T, std::size_t N>
  void put(const std::array<T, N>& values) {
    for (const T& v : values) {
      put(v);
    }
  }
  template <typename T, std::size_t N>
  void put(std::span<T, N> values) {
    for (const T& v : values) {
      put(v);
    }
  }

  Payload& out_;
  std::size_t n_ = 0;
};

// Reads the fields it is called with, in order, from a frame's zero-extended payload.
class PayloadReader {
 public:
  explicit PayloadReader(const Payload& in) : in_(in) {}
  template <typename... T>
  void operator()(T&&... fields) {
    (get(fields), ...);
  }

 private:
  std::uint8_t byte() { return in_[n_++]; }
  std::uint16_t u16() {
    const std::uint16_t lo = byte();
    return static_cast<std::uint16_t>(lo | (byte() << 8));
  }
  std::uint32_t u32() {
    const std::uint32_t lo = u16();
    return lo | (static_cast<std::uint32_t>(u16()) << 16);
  }
  void get(std::uint8_t& v) { v = byte(); }
  void get(std::int8_t& v) { v = static_cast<std::int8_t>(byte()); }
  void get(char& v) { v = static_cast<char>(byte()); }
  void get(std::uint16_t& v) { v = u16(); }
  void get(std::int16_t& v) { v = static_cast<std::int16_t>(u16()); }
  void get(std::uint32_t& v) { v = u32(); }
  void get(std::int32_t& v) { v = static_cast<std::int32_t>(u32()); }
  void get(float& v) { v = std::bit_cast<float>(u32()); }
  template <typename T, std::size_t N>
  void get(std::array<T, N>& values) {
    for (T& v : values) {
      get(v);
    }
  }
  template <typename T, std::size_t N>
  void get(std::span<T, N> values) {
    for (T& v : values) {
      get(v);
    }
  }

  const Payload& in_;
  std::size_t n_ = 0;
};

}  // namespace detail
}  // namespace rovctl::drivers::mavlink
