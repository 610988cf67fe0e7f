// MAVLink over loopback UDP: endpoint strings, udpin answering the last sender, udpout to a
// fixed peer, non-blocking receive, and per-datagram framing.
#include "drivers/mavlink/mavlink_udp_link.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "drivers/mavlink/mavlink_messages.hpp"

namespace rovctl::drivers::mavlink {
namespace {

TEST(MavlinkUdpEndpoint, ParsesBothModes) {
  UdpEndpoint e;
  std::string error;
  ASSERT_TRUE(parse_udp_endpoint("udpin:0.0.0.0:14660", "ardusub.link", e, error)) << error;
  EXPECT_EQ(e.mode, UdpEndpoint::Mode::listen);
  EXPECT_EQ(e.address, "0.0.0.0");
  EXPECT_EQ(e.port, 14660);
  ASSERT_TRUE(parse_udp_endpoint("udpout:192.168.2.1:14550", "ardusub.link", e, error)) << error;
  EXPECT_EQ(e.mode, UdpEndpoint::Mode::send_to);
  EXPECT_EQ(e.address, "192.168.2.1");
  EXPECT_EQ(e.port, 14550);
}

TEST(MavlinkUdpEndpoint, ErrorsNameTheKeyAndTheFault) {
  const struct {
    const char* text;
    const char* why;
  } cases[] = {
      {"udp:0.0.0.0:14660", "unknown mode 'udp'"},
      {"udpin:14660", "not MODE:ADDR:PORT"},
      {"udpin:bluerov:14660", "not a dotted IPv4"},
      {"udpin:0.0.0.0:70000", "port that is not a number"},
      {"udpin:0.0.0.0:14x", "port that is not a number"},
      {"udpin:0.0.0.0:", "port that is not a number"},
      {"udpout:127.0.0.1:0", "sends to port 0"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    UdpEndpoint e;
    e.port = 1;
    std::string error;
    EXPECT_FALSE(parse_udp_endpoint(c.text, "ardusub.link", e, error));
    EXPECT_NE(error.find("ardusub.link"), std::string::npos) << error;
    EXPECT_NE(error.find(c.why), std::string::npos) << error;
    EXPECT_EQ(e.port, 1);  // untouched on failure
  }
}

// Waits (in the test, not in the link) for a frame to arrive on loopback.
MavlinkUdpLink::Io receive_within(MavlinkUdpLink& link, Frame& f) {
  for (int i = 0; i < 200; ++i) {
    const MavlinkUdpLink::Io io = link.receive(f);
    if (io != MavlinkUdpLink::Io::would_block) {
      return io;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return MavlinkUdpLink::Io::would_block;
}

TEST(MavlinkUdpLink, UdpinAnswersTheLastSender) {
  std::string error;
  MavlinkUdpLink vehicle;
  ASSERT_TRUE(vehicle.open(UdpEndpoint{UdpEndpoint::Mode::listen, "127.0.0.1", 0}, error)) << error;
  const std::uint16_t port = vehicle.local_port();
  ASSERT_NE(port, 0);

  Frame f;
  EXPECT_EQ(vehicle.receive(f), MavlinkUdpLink::Io::would_block);  // returns at once, empty
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  FrameWriter us(255, 190);
  std::size_t n = write_message(us, Heartbeat{}, out);
  EXPECT_EQ(vehicle.send({out.data(), n}), MavlinkUdpLink::Io::no_peer);
  EXPECT_EQ(vehicle.counters().unanswered_sends, 1U);

  MavlinkUdpLink ardusub;
  ASSERT_TRUE(ardusub.open(UdpEndpoint{UdpEndpoint::Mode::send_to, "127.0.0.1", port}, error));
  FrameWriter them(1, 1);
  Heartbeat hb;
  hb.custom_mode = 19;
  n = write_message(them, hb, out);
  ASSERT_EQ(ardusub.send({out.data(), n}), MavlinkUdpLink::Io::ok);
  ASSERT_EQ(receive_within(vehicle, f), MavlinkUdpLink::Io::ok);
  EXPECT_EQ(f.header.system_id, 1);
  Heartbeat got;
  ASSERT_TRUE(unpack(f, got));
  EXPECT_EQ(got.custom_mode, 19U);
  EXPECT_TRUE(vehicle.has_peer());

  // The reply goes to the sender's ephemeral port.
  n = write_message(us, arm_disarm(1, 1, false, false), out);
  ASSERT_EQ(vehicle.send({out.data(), n}), MavlinkUdpLink::Io::ok);
  ASSERT_EQ(receive_within(ardusub, f), MavlinkUdpLink::Io::ok);
  EXPECT_EQ(f.header.system_id, 255);
  CommandLong c;
  ASSERT_TRUE(unpack(f, c));
  EXPECT_EQ(c.command, kCmdComponentArmDisarm);
}

TEST(MavlinkUdpLink, SeveralFramesInOneDatagramAndDamageStaysInItsDatagram) {
  std::string error;
  MavlinkUdpLink rx;
  ASSERT_TRUE(rx.open(UdpEndpoint{UdpEndpoint::Mode::listen, "127.0.0.1", 0}, error)) << error;
  MavlinkUdpLink tx;
  ASSERT_TRUE(
      tx.open(UdpEndpoint{UdpEndpoint::Mode::send_to, "127.0.0.1", rx.local_port()}, error));
  FrameWriter w(1, 1);
  std::array<std::uint8_t, 3 * kMaxFrameBytes> buf{};
  std::size_t n = write_message(w, Heartbeat{}, buf);
  n += write_message(w, VfrHud{0, 0, -3.5F, 0, 90, 0}, std::span(buf).subspan(n));
  ASSERT_EQ(tx.send({buf.data(), n}), MavlinkUdpLink::Io::ok);
  // A datagram cut short after a header claiming 200 bytes: must not eat the next datagram.
  const std::array<std::uint8_t, 12> broken{0xFD, 200, 0, 0, 9, 1, 1, 0, 0, 0, 1, 2};
  ASSERT_EQ(tx.send(broken), MavlinkUdpLink::Io::ok);
  // A false start byte in front of a frame in the same datagram: the frame still comes out.
  buf[0] = 0xFD;
  buf[1] = 100;
  std::fill(buf.begin() + 2, buf.begin() + 10, std::uint8_t{0});
  n = 10 + write_message(w, ScaledPressure2{1, 1013.25F, 0, 0, 0}, std::span(buf).subspan(10));
  ASSERT_EQ(tx.send({buf.data(), n}), MavlinkUdpLink::Io::ok);

  Frame f;
  ASSERT_EQ(receive_within(rx, f), MavlinkUdpLink::Io::ok);
  EXPECT_EQ(f.header.message_id, Heartbeat::kId);
  ASSERT_EQ(receive_within(rx, f), MavlinkUdpLink::Io::ok);
  EXPECT_EQ(f.header.message_id, VfrHud::kId);
  EXPECT_EQ(f.header.sequence, 1);
  ASSERT_EQ(receive_within(rx, f), MavlinkUdpLink::Io::ok);
  EXPECT_EQ(f.header.message_id, ScaledPressure2::kId);
  EXPECT_EQ(f.header.sequence, 2);
  EXPECT_EQ(rx.counters().datagrams_in, 3U);
  EXPECT_GE(rx.parser_counters().incomplete_frames, 2U);
}

TEST(MavlinkUdpLink, OpenFailureNamesTheEndpoint) {
  std::string error;
  MavlinkUdpLink a;
  ASSERT_TRUE(a.open(UdpEndpoint{UdpEndpoint::Mode::listen, "127.0.0.1", 0}, error));
  MavlinkUdpLink b;
  // An address this host does not own (TEST-NET-3) cannot be bound.
  EXPECT_FALSE(b.open(UdpEndpoint{UdpEndpoint::Mode::listen, "203.0.113.7", 14660}, error));
  EXPECT_NE(error.find("udpin:203.0.113.7:14660"), std::string::npos) << error;
  EXPECT_NE(error.find("bind"), std::string::npos) << error;
  EXPECT_FALSE(b.is_open());
}

}  // namespace
}  // namespace rovctl::drivers::mavlink
