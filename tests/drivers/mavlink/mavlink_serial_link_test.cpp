// MAVLink over a serial port, tested on a pseudo-terminal (the machine has no serial ArduSub):
// endpoint strings, frames split across reads, garbage between frames, whole-frame writes, and the
// link string that picks UDP or serial.
#include "drivers/mavlink/mavlink_serial_link.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <thread>
#include <vector>

#include "drivers/mavlink/mavlink_link.hpp"
#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/pty_pair.hpp"

namespace rovctl::drivers::mavlink {
namespace {

TEST(MavlinkSerialEndpoint, ParsesDeviceAndBaud) {
  SerialEndpoint e;
  std::string error;
  ASSERT_TRUE(parse_serial_endpoint("serial:/dev/ttyACM0:115200", "ardusub.link", e, error))
      << error;
  EXPECT_EQ(e.device, "/dev/ttyACM0");
  EXPECT_EQ(e.baud, 115200U);
  ASSERT_TRUE(parse_serial_endpoint("serial:/dev/serial/by-id/usb-ArduPilot_Pixhawk:921600",
                                    "ardusub.link", e, error));
  EXPECT_EQ(e.device, "/dev/serial/by-id/usb-ArduPilot_Pixhawk");
}

TEST(MavlinkSerialEndpoint, ErrorsNameTheKeyAndTheFault) {
  const struct {
    const char* text;
    const char* why;
  } cases[] = {
      {"serial:/dev/ttyACM0", "no baud rate"},
      {"serial:/dev/ttyACM0:115201", "not one of 9600"},
      {"serial:/dev/ttyACM0:fast", "not one of 9600"},
      {"serial:ttyACM0:115200", "not a path"},
      {"serial::115200", "not a path"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    SerialEndpoint e;
    std::string error;
    EXPECT_FALSE(parse_serial_endpoint(c.text, "ardusub.link", e, error));
    EXPECT_NE(error.find("ardusub.link"), std::string::npos) << error;
    EXPECT_NE(error.find(c.why), std::string::npos) << error;
  }
}

TEST(MavlinkLinkEndpoint, TheLinkStringPicksUdpOrSerial) {
  LinkEndpoint e;
  std::string error;
  ASSERT_TRUE(parse_link_endpoint("serial:/dev/ttyUSB0:57600", "k", e, error)) << error;
  EXPECT_EQ(e.kind, LinkEndpoint::Kind::serial);
  EXPECT_EQ(e.serial.baud, 57600U);
  ASSERT_TRUE(parse_link_endpoint("udpin:0.0.0.0:14660", "k", e, error)) << error;
  EXPECT_EQ(e.kind, LinkEndpoint::Kind::udp);
  EXPECT_FALSE(parse_link_endpoint("tcp:1.2.3.4:5760", "k", e, error));
  EXPECT_NE(error.find("serial:DEVICE:BAUD"), std::string::npos) << error;
}

TEST(MavlinkSerialLink, OpenErrorsNameTheDevice) {
  MavlinkSerialLink link;
  std::string error;
  EXPECT_FALSE(link.open(SerialEndpoint{"/dev/rovctl-no-such-port", 115200}, error));
  EXPECT_NE(error.find("/dev/rovctl-no-such-port: cannot open"), std::string::npos) << error;
  EXPECT_FALSE(link.open(SerialEndpoint{"/dev/null", 115200}, error));
  EXPECT_NE(error.find("/dev/null: not a serial port"), std::string::npos) << error;
  EXPECT_FALSE(link.is_open());
}

using testing::PtyPair;

MavlinkSerialLink::Io receive_within(MavlinkSerialLink& link, Frame& f) {
  for (int i = 0; i < 500; ++i) {
    const MavlinkSerialLink::Io io = link.receive(f);
    if (io != MavlinkSerialLink::Io::would_block) return io;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return MavlinkSerialLink::Io::would_block;
}

TEST(MavlinkSerialLink, FramesSplitAcrossReadsAndGarbageBetweenThemComeOutWhole) {
  PtyPair pty;
  if (!pty.ok()) GTEST_SKIP() << "no pseudo-terminal on this machine (openpty failed)";
  MavlinkSerialLink link;
  std::string error;
  ASSERT_TRUE(link.open(SerialEndpoint{pty.path, 115200}, error)) << error;
  Frame f;
  EXPECT_EQ(link.receive(f), MavlinkSerialLink::Io::would_block);  // at once, empty

  FrameWriter ardusub(1, 1);
  std::array<std::uint8_t, 3 * kMaxFrameBytes> buf{};
  Heartbeat hb;
  hb.custom_mode = 19;
  std::size_t n = write_message(ardusub, hb, buf);
  // The first frame arrives in two pieces, as a UART delivers it.
  ASSERT_EQ(::write(pty.leader, buf.data(), 5), 5);
  EXPECT_EQ(link.receive(f), MavlinkSerialLink::Io::would_block);
  ASSERT_EQ(::write(pty.leader, buf.data() + 5, n - 5), static_cast<ssize_t>(n - 5));
  ASSERT_EQ(receive_within(link, f), MavlinkSerialLink::Io::ok);
  Heartbeat got;
  ASSERT_TRUE(unpack(f, got));
  EXPECT_EQ(got.custom_mode, 19U);
  // Line noise, then a frame: the parser resyncs on the start byte.
  const std::array<std::uint8_t, 6> noise{0x00, 0xFD, 0x13, 0x55, 0xAA, 0x01};
  n = write_message(ardusub, ScaledPressure2{1, 1113.8F, 0, 1500, 0}, buf);
  std::vector<std::uint8_t> stream(noise.begin(), noise.end());
  stream.insert(stream.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  ASSERT_EQ(::write(pty.leader, stream.data(), stream.size()), static_cast<ssize_t>(stream.size()));
  ASSERT_EQ(receive_within(link, f), MavlinkSerialLink::Io::ok);
  ScaledPressure2 p;
  ASSERT_TRUE(unpack(f, p));
  EXPECT_FLOAT_EQ(p.press_abs_hpa, 1113.8F);
}

TEST(MavlinkSerialLink, SendsWholeFramesTheLeaderSideDecodes) {
  PtyPair pty;
  if (!pty.ok()) GTEST_SKIP() << "no pseudo-terminal on this machine (openpty failed)";
  MavlinkLink link;
  LinkEndpoint e;
  std::string error;
  ASSERT_TRUE(parse_link_endpoint("serial:" + pty.path + ":115200", "k", e, error)) << error;
  ASSERT_TRUE(link.open(e, error)) << error;
  EXPECT_TRUE(link.has_peer());
  EXPECT_EQ(link.local_port(), 0);
  FrameWriter us(255, 190);
  std::array<std::uint8_t, kMaxFrameBytes> out{};
  for (int i = 0; i < 3; ++i) {
    const std::size_t n = write_message(us, arm_disarm(1, 1, i == 0, false), out);
    ASSERT_EQ(link.send({out.data(), n}), MavlinkLink::Io::ok);
  }
  FrameParser parser;
  std::array<std::uint8_t, 512> in{};
  int frames = 0;
  for (int i = 0; i < 500 && frames < 3; ++i) {
    const ssize_t r = ::read(pty.leader, in.data(), in.size());
    if (r > 0) {
      parser.feed({in.data(), static_cast<std::size_t>(r)});
      Frame f;
      while (parser.next(f)) {
        CommandLong c;
        ASSERT_TRUE(unpack(f, c));
        EXPECT_EQ(f.header.system_id, 255);
        EXPECT_EQ(f.header.sequence, frames);
        EXPECT_EQ(c.params[0], frames == 0 ? 1.0F : 0.0F);
        ++frames;
      }
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  EXPECT_EQ(frames, 3);
}

}  // namespace
}  // namespace rovctl::drivers::mavlink
