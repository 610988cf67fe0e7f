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

namespace {

MavlinkLink::Io to_link_io(MavlinkUdpLink::Io io) {
  switch (io) {
    case MavlinkUdpLink::Io::ok:
      return MavlinkLink::Io::ok;
    case MavlinkUdpLink::Io::would_block:
      return MavlinkLink::Io::would_block;
    case MavlinkUdpLink::Io::no_peer:
      return MavlinkLink::Io::no_peer;
    case MavlinkUdpLink::Io::error:
      return MavlinkLink::Io::error;
  }
  return MavlinkLink::Io::error;
}

MavlinkLink::Io to_link_io(MavlinkSerialLink::Io io) {
  switch (io) {
    case MavlinkSerialLink::Io::ok:
      return MavlinkLink::Io::ok;
    case MavlinkSerialLink::Io::would_block:
      return MavlinkLink::Io::would_block;
    case MavlinkSerialLink::Io::error:
      return MavlinkLink::Io::error;
  }
  return MavlinkLink::Io::error;
}

}  // namespace

MavlinkLink::Io MavlinkLink::send(std::span<const std::uint8_t> frame) {
  return kind_ == LinkEndpoint::Kind::serial ? to_link_io(serial_.send(frame))
                                             : to_link_io(udp_.send(frame));
}

MavlinkLink::Io MavlinkLink::receive(Frame& frame) {
  return kind_ == LinkEndpoint::Kind::serial ? to_link_io(serial_.receive(frame))
                                             : to_link_io(udp_.receive(frame));
}

}  // namespace rovctl::drivers::mavlink
