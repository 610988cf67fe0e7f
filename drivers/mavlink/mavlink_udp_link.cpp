// UDP socket handling for the MAVLink link: non-blocking recvfrom/sendto, so the caller's loop
// never waits on the network.
#include "drivers/mavlink/mavlink_udp_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

namespace rovctl::drivers::mavlink {

bool parse_udp_endpoint(std::string_view text, std::string_view config_key, UdpEndpoint& out,
                        std::string& error) {
  const auto fail = [&](const std::string& why) {
    error = std::string(config_key) + ": '" + std::string(text) + "' " + why +
            " (expected udpin:ADDR:PORT or udpout:ADDR:PORT, e.g. udpin:0.0.0.0:14660)";
    return false;
  };
  const std::size_t first = text.find(':');
  const std::size_t last = text.rfind(':');
  if (first == std::string_view::npos || first == last) {
    return fail("is not MODE:ADDR:PORT");
  }
  const std::string_view mode = text.substr(0, first);
  const std::string_view address = text.substr(first + 1, last - first - 1);
  const std::string_view port = text.substr(last + 1);
  UdpEndpoint e;
  if (mode == "udpin") {
    e.mode = UdpEndpoint::Mode::listen;
  } else if (mode == "udpout") {
    e.mode = UdpEndpoint::Mode::send_to;
  } else {
    return fail("has an unknown mode '" + std::string(mode) + "'");
  }
  in_addr parsed{};
  if (address.empty() || inet_pton(AF_INET, std::string(address).c_str(), &parsed) != 1) {
    return fail("has an address that is not a dotted IPv4 address");
  }
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc{} || end != port.data() + port.size() || value > 65535) {
    return fail("has a port that is not a number in 0..65535");
  }
  if (value == 0 && e.mode == UdpEndpoint::Mode::send_to) {
    return fail("sends to port 0");
  }
  e.address = std::string(address);
  e.port = static_cast<std::uint16_t>(value);
  out = e;
  return true;
}

MavlinkUdpLink::~MavlinkUdpLink() { close(); }

bool MavlinkUdpLink::open(const UdpEndpoint& endpoint, std::string& error) {
  close();
  const std::string name =
      std::string(endpoint.mode == UdpEndpoint::Mode::listen ? "udpin:" : "udpout:") +
      endpoint.address + ":" + std::to_string(endpoint.port);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(endpoint.port);
  if (inet_pton(AF_INET, endpoint.address.c_str(), &address.sin_addr) != 1) {
    error = "MAVLink " + name + ": not an IPv4 address";
    return false;
  }
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    error = "MAVLink " + name + ": socket: " + std::strerror(errno);
    return false;
  }
  if (endpoint.mode == UdpEndpoint::Mode::listen) {
    const int yes = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
      error = "MAVLink " + name + ": bind: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    has_peer_ = false;
  } else {
    peer_ = address;
    has_peer_ = true;
  }
  fd_ = fd;
  endpoint_ = endpoint;
  parser_.reset();
  datagram_length_ = datagram_fed_ = 0;
  return true;
}

void MavlinkUdpLink::close() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  has_peer_ = false;
}

std::uint16_t MavlinkUdpLink::local_port() const {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (fd_ < 0 || ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    return 0;
  }
  return ntohs(address.sin_port);
}

MavlinkUdpLink::Io MavlinkUdpLink::send(std::span<const std::uint8_t> datagram) {
  if (fd_ < 0) {
    return Io::error;
  }
  if (!has_peer_) {
    ++counters_.unanswered_sends;
    return Io::no_peer;
  }
  const ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), MSG_DONTWAIT,
                             reinterpret_cast<const sockaddr*>(&peer_), sizeof peer_);
  if (n == static_cast<ssize_t>(datagram.size())) {
    ++counters_.datagrams_out;
    return Io::ok;
  }
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
    ++counters_.send_would_block;
    return Io::would_block;
  }
  // ECONNREFUSED: the peer's port was closed (an ICMP answer to an earlier datagram); the
  // link stays usable for when it comes back.
  ++counters_.send_errors;
  return Io::error;
}

MavlinkUdpLink::Io MavlinkUdpLink::receive(Frame& frame) {
  if (fd_ < 0) {
    return Io::error;
  }
  while (true) {
    if (datagram_fed_ < datagram_length_) {
      datagram_fed_ += parser_.feed(std::span<const std::uint8_t>(
          datagram_.data() + datagram_fed_, datagram_length_ - datagram_fed_));
    }
    if (parser_.next(frame)) {
      return Io::ok;
    }
    if (datagram_fed_ < datagram_length_) {
      continue;
    }
    // A frame never continues into the next datagram.
    if (parser_.finish(frame)) {
      return Io::ok;
    }
    sockaddr_in from{};
    socklen_t from_length = sizeof from;
    const ssize_t n = ::recvfrom(fd_, datagram_.data(), datagram_.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &from_length);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) {
        return Io::would_block;
      }
      if (errno == EINTR) {
        continue;
      }
      ++counters_.receive_errors;
      return Io::error;
    }
    ++counters_.datagrams_in;
    if (endpoint_.mode == UdpEndpoint::Mode::listen) {
      peer_ = from;
      has_peer_ = true;
    }
    parser_.reset();
    datagram_length_ = static_cast<std::size_t>(n);
    datagram_fed_ = 0;
  }
}

}  // namespace rovctl::drivers::mavlink
