// A non-blocking serial port for MAVLink (`serial:/dev/ttyACM0:115200`): ArduSub's USB or TELEM
// port wired straight to the onboard computer, without BlueOS's router in between.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "drivers/mavlink/mavlink_codec.hpp"

namespace rovctl::drivers::mavlink {

struct SerialEndpoint {
  std::string device;           // e.g. /dev/ttyACM0, /dev/serial/by-id/...
  std::uint32_t baud = 115200;  // one of the standard rates (termios)
};

// Parses `serial:DEVICE:BAUD`; on failure false and a message naming `config_key`.
bool parse_serial_endpoint(std::string_view text, std::string_view config_key, SerialEndpoint& out,
                           std::string& error);

struct SerialLinkCounters {
  std::uint64_t bytes_in = 0;
  std::uint64_t frames_out = 0;
  std::uint64_t send_would_block = 0;  // the port's buffer full: the whole frame dropped
  std::uint64_t send_errors = 0;
  std::uint64_t receive_errors = 0;
};

class MavlinkSerialLink {
 public:
  enum class Io { ok, would_block, error };

  MavlinkSerialLink() = default;
  ~MavlinkSerialLink();
  MavlinkSerialLink(const MavlinkSerialLink&) = delete;
  MavlinkSerialLink& operator=(const MavlinkSerialLink&) = delete;

  // Opens the device raw (8N1, no flow control) at the baud rate; false and a message naming
  // the device on failure.
  bool open(const SerialEndpoint& endpoint, std::string& error);
  void close();
  bool is_open() const { return fd_ >= 0; }

  // One frame, without blocking: written whole or not at all (a half frame would cost the peer
  // the next one too).
  Io send(std::span<const std::uint8_t> frame);
  // The next checked frame from the byte stream, without blocking.
  Io receive(Frame& frame);

  const SerialLinkCounters& counters() const { return counters_; }
  const ParserCounters& parser_counters() const { return parser_.counters(); }

 private:
  int fd_ = -1;
  FrameParser parser_;
  std::array<std::uint8_t, 512> chunk_{};
  std::size_t chunk_length_ = 0;
  std::size_t chunk_fed_ = 0;
  SerialLinkCounters counters_;
};

}  // namespace rovctl::drivers::mavlink
