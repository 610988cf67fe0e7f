// One MAVLink link over whichever transport the config names.
#include "drivers/mavlink/mavlink_link.hpp"

namespace rovctl::drivers::mavlink {

bool parse_link_endpoint(std::string_view text, std::string_view config_key, LinkEndpoint& out,
                         std::string& error) {
  LinkEndpoint e;
  if (text.substr(0, 7) == "serial:") {
    e.kind = LinkEndpoint::Kind::serial;
    if (!parse_serial_endpoint(text, config_key, e.serial, error)) return false;
  } else {
    e.kind = LinkEndpoint::Kind::udp;
    if (!parse_udp_endpoint(text, config_key, e.udp, error)) {
      error += "; or serial:DEVICE:BAUD";
      return false;
    }
  }
  out = e;
  return true;
}

bool MavlinkLink::open(const LinkEndpoint& endpoint, std::string& error) {
  close();
  kind_ = endpoint.kind;
  return kind_ == LinkEndpoint::Kind::serial ? serial_.open(endpoint.serial, error)
                                             : udp_.open(endpoint.udp, error);
}

void MavlinkLink::close() {
  udp_.close();
  serial_.close();
}

bool MavlinkLink::is_open() const {
  return kind_ == LinkEndpoint::Kind::serial ? serial_.is_open() : udp_.is_open();
}

std::uint16_t MavlinkLink::local_port() const {
  return kind_ == LinkEndpoint::Kind::udp && udp_.is_open() ? udp_.local_port() : 0;
}

bool MavlinkLink::has_peer() const {
  return kind_ == LinkEndpoint::Kind::serial ? serial_.is_open() : udp_.has_peer();
}

MavlinkLink::Io MavlinkLink::send(std::span<const std::uint8_t> frame) {
  if (kind_ == LinkEndpoint::Kind::serial) {
    switch (serial_.send(frame)) {
      case MavlinkSerialLink::Io::ok:
        return Io::ok;
      case MavlinkSerialLink::Io::would_block:
        return Io::would_block;
      case MavlinkSerialLink::Io::error:
        return Io::error;
    }
    return Io::error;
  }
  switch (udp_.send(frame)) {
    case MavlinkUdpLink::Io::ok:
      return Io::ok;
    case MavlinkUdpLink::Io::would_block:
      return Io::would_block;
    case MavlinkUdpLink::Io::no_peer:
      return Io::no_peer;
    case MavlinkUdpLink::Io::error:
      return Io::error;
  }
  return Io::error;
}

MavlinkLink::Io MavlinkLink::receive(Frame& frame) {
  if (kind_ == LinkEndpoint::Kind::serial) {
    switch (serial_.receive(frame)) {
      case MavlinkSerialLink::Io::ok:
        return Io::ok;
      case MavlinkSerialLink::Io::would_block:
        return Io::would_block;
      case MavlinkSerialLink::Io::error:
        return Io::error;
    }
    return Io::error;
  }
  switch (udp_.receive(frame)) {
    case MavlinkUdpLink::Io::ok:
      return Io::ok;
    case MavlinkUdpLink::Io::would_block:
      return Io::would_block;
    case MavlinkUdpLink::Io::no_peer:
      return Io::no_peer;
    case MavlinkUdpLink::Io::error:
      return Io::error;
  }
  return Io::error;
}

}  // namespace rovctl::drivers::mavlink
