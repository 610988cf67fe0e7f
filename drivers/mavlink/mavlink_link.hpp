// The MAVLink link the ArduSub bus talks over, as its `link` setting names it: a UDP endpoint
// (`udpin:`/`udpout:`, BlueOS's router) or a serial port (`serial:`, ArduSub wired directly).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "drivers/mavlink/mavlink_codec.hpp"
#include "drivers/mavlink/mavlink_serial_link.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"

namespace rovctl::drivers::mavlink {

struct LinkEndpoint {
  enum class Kind { udp, serial };
  Kind kind = Kind::udp;
  UdpEndpoint udp;
  SerialEndpoint serial;
};

// Parses `udpin:ADDR:PORT`, `udpout:ADDR:PORT` or `serial:DEVICE:BAUD`; on failure false and a
// message that names `config_key` and what is wrong.
bool parse_link_endpoint(std::string_view text, std::string_view config_key, LinkEndpoint& out,
                         std::string& error);

class MavlinkLink {
 public:
  enum class Io { ok, would_block, no_peer, error };

  bool open(const LinkEndpoint& endpoint, std::string& error);
  void close();
  bool is_open() const;
  // The bound UDP port; 0 on a serial port.
  std::uint16_t local_port() const;
  // Whom to send to is known (always on a serial port).
  bool has_peer() const;

  Io send(std::span<const std::uint8_t> frame);
  Io receive(Frame& frame);

 private:
  LinkEndpoint::Kind kind_ = LinkEndpoint::Kind::udp;
  MavlinkUdpLink udp_;
  MavlinkSerialLink serial_;
};

}  // namespace rovctl::drivers::mavlink
