// A non-blocking UDP endpoint for MAVLink: `udpin:ADDR:PORT` listens and answers whoever sent
// last (a BlueOS endpoint pointed at us), `udpout:ADDR:PORT` sends to a fixed peer.
#pragma once

#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "drivers/mavlink/mavlink_codec.hpp"

namespace rovctl::drivers::mavlink {

struct UdpEndpoint {
  enum class Mode { listen, send_to };
  Mode mode = Mode::listen;
  std::string address = "0.0.0.0";  // dotted IPv4
  std::uint16_t port = 14660;       // 0 with udpin: any free port (tests)
};

// Parses `udpin:ADDR:PORT` / `udpout:ADDR:PORT`; on failure false and a message that names
// `config_key` and what is wrong.
bool parse_udp_endpoint(std::string_view text, std::string_view config_key, UdpEndpoint& out,
                        std::string& error);

struct UdpLinkCounters {
  std::uint64_t datagrams_in = 0;
  std::uint64_t datagrams_out = 0;
  std::uint64_t send_would_block = 0;  // socket buffer full: datagram dropped
  std::uint64_t send_errors = 0;
  std::uint64_t receive_errors = 0;
  std::uint64_t unanswered_sends = 0;  // udpin before anyone has spoken to us
};

class MavlinkUdpLink {
 public:
  enum class Io { ok, would_block, no_peer, error };

  MavlinkUdpLink() = default;
  ~MavlinkUdpLink();
  MavlinkUdpLink(const MavlinkUdpLink&) = delete;
  MavlinkUdpLink& operator=(const MavlinkUdpLink&) = delete;

  // Opens the socket (bound for udpin, connected-less for udpout); false and a message naming
  // the endpoint on failure.
  bool open(const UdpEndpoint& endpoint, std::string& error);
  void close();
  bool is_open() const { return fd_ >= 0; }
  // The bound port (the kernel's choice when the endpoint asked for 0).
  std::uint16_t local_port() const;
  bool has_peer() const { return has_peer_; }

  // One datagram, without blocking.
  Io send(std::span<const std::uint8_t> datagram);
  // The next checked frame from the socket, without blocking. Each datagram is framed on its
  // own: a damaged frame at its end cannot swallow the next datagram.
  Io receive(Frame& frame);

  const UdpLinkCounters& counters() const { return counters_; }
  const ParserCounters& parser_counters() const { return parser_.counters(); }

 private:
  int fd_ = -1;
  UdpEndpoint endpoint_;
  sockaddr_in peer_{};
  bool has_peer_ = false;
  FrameParser parser_;
  std::array<std::uint8_t, 2048> datagram_{};
  std::size_t datagram_length_ = 0;
  std::size_t datagram_fed_ = 0;
  UdpLinkCounters counters_;
};

}  // namespace rovctl::drivers::mavlink
