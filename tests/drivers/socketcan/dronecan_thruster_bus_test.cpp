// DroneCAN thruster bus over the socket path: a socketpair(AF_UNIX, SOCK_SEQPACKET) carrying
// struct can_frame stands in for the CAN bus, the test plays the ESCs on the other end.
#include "drivers/socketcan/dronecan_thruster_bus.hpp"

#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <vector>

namespace rovctl::drivers {
namespace {

using dronecan::CanFrame;

class DronecanBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds_), 0) << std::strerror(errno);
    params_.node_id = 10;
    params_.priority = 8;
    params_.max_consecutive_failures = 3;
  }
  void TearDown() override {
    if (fds_[1] >= 0) ::close(fds_[1]);
  }

  std::unique_ptr<DronecanThrusterBus> make_bus(std::size_t thrusters) {
    CanSocket s;
    s.adopt(fds_[0], "socketpair");
    fds_[0] = -1;
    return std::make_unique<DronecanThrusterBus>(params_, thrusters, std::move(s));
  }

  // Everything the bus sent so far, as struct can_frame.
  std::vector<can_frame> drain() {
    std::vector<can_frame> out;
    can_frame cf{};
    while (::recv(fds_[1], &cf, sizeof(cf), MSG_DONTWAIT) == static_cast<ssize_t>(sizeof(cf))) {
      out.push_back(cf);
    }
    return out;
  }

  void send_raw(canid_t id, const std::vector<std::uint8_t>& data) {
    can_frame cf{};
    cf.can_id = id;
    cf.can_dlc = static_cast<std::uint8_t>(data.size());
    std::memcpy(cf.data, data.data(), data.size());
    ASSERT_EQ(::send(fds_[1], &cf, sizeof(cf), 0), static_cast<ssize_t>(sizeof(cf)));
  }

  void send_status(const dronecan::EscStatus& s, int node, std::uint8_t tid) {
    std::array<std::uint8_t, dronecan::kStatusBytes> payload{};
    dronecan::encode_status(s, payload);
    std::array<CanFrame, 3> frames{};
    const std::size_t n =
        dronecan::make_transfer_frames(dronecan::message_can_id(16, dronecan::kStatusId, node),
                                       dronecan::kStatusSignature, payload, tid, frames);
    for (std::size_t i = 0; i < n; ++i) {
      send_raw(frames[i].id | CAN_EFF_FLAG,
               {frames[i].data.begin(), frames[i].data.begin() + frames[i].len});
    }
  }

  // Reassembles the RawCommand transfers in `frames`; returns the commands of each.
  static std::vector<std::vector<std::int16_t>> commands_in(const std::vector<can_frame>& frames,
                                                            std::vector<int>* tids = nullptr) {
    dronecan::TransferReassembler rx(dronecan::kRawCommandId, dronecan::kRawCommandSignature);
    std::vector<std::vector<std::int16_t>> out;
    for (const can_frame& cf : frames) {
      EXPECT_NE(cf.can_id & CAN_EFF_FLAG, 0U);
      EXPECT_EQ(cf.can_id & CAN_EFF_MASK, 0x0804060AU);  // priority 8, RawCommand, node 10
      CanFrame f;
      f.id = cf.can_id & CAN_EFF_MASK;
      f.len = cf.can_dlc;
      std::memcpy(f.data.data(), cf.data, cf.can_dlc);
      if (!rx.accept(f)) continue;
      std::array<std::int16_t, dronecan::kMaxRawCommands> cmd{};
      std::size_t count = 0;
      EXPECT_TRUE(dronecan::decode_raw_command(rx.payload(), cmd, count));
      out.emplace_back(cmd.begin(), cmd.begin() + static_cast<std::ptrdiff_t>(count));
      if (tids != nullptr) tids->push_back(cf.data[cf.can_dlc - 1] & 0x1F);
    }
    EXPECT_EQ(rx.crc_errors + rx.toggle_errors + rx.missed_starts, 0U);
    return out;
  }

  int fds_[2] = {-1, -1};
  DronecanParams params_;
};

hal::ThrusterCommand dronecan_command_of(std::vector<double> f) {
  hal::ThrusterCommand c;
  for (std::size_t i = 0; i < f.size(); ++i) c.thrust_fraction[i] = f[i];
  c.count = f.size();
  return c;
}

TEST_F(DronecanBusTest, NeutralAtOpenArmingAndCommands) {
  auto bus = make_bus(8);
  std::string error;
  ASSERT_TRUE(bus->open(error)) << error;
  const hal::ThrusterCommand cmd =
      dronecan_command_of({0.5, -0.25, 1.0, -1.0, 0.0, 2.0, NAN, 0.001});
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::ok);  // disarmed: neutral whatever is asked
  EXPECT_EQ(bus->arm(true), hal::BusStatus::ok);
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::ok);
  EXPECT_EQ(bus->arm(false), hal::BusStatus::ok);
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::ok);

  std::vector<int> tids;
  const auto transfers = commands_in(drain(), &tids);
  ASSERT_EQ(transfers.size(), 6U);  // open, write, arm, write, disarm, write
  const std::vector<std::int16_t> neutral(8, 0);
  EXPECT_EQ(transfers[0], neutral);
  EXPECT_EQ(transfers[1], neutral);
  EXPECT_EQ(transfers[2], neutral);
  EXPECT_EQ(transfers[3], (std::vector<std::int16_t>{4096, -2048, 8191, -8191, 0, 8191, 0, 8}));
  EXPECT_EQ(transfers[4], neutral);
  EXPECT_EQ(transfers[5], neutral);
  EXPECT_EQ(tids, (std::vector<int>{0, 1, 2, 3, 4, 5}));

  bus->close();
  const auto after_close = commands_in(drain());
  ASSERT_EQ(after_close.size(), 1U);
  EXPECT_EQ(after_close[0], neutral);
  bus->close();  // twice is fine
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::fault);
}

TEST_F(DronecanBusTest, ExactBytesOnTheWire) {
  auto bus = make_bus(4);
  std::string error;
  ASSERT_TRUE(bus->open(error)) << error;
  ASSERT_EQ(bus->arm(true), hal::BusStatus::ok);
  drain();
  // The fractions of vector V1 ([8191, -1, 0, 4096]); third transfer -> transfer ID 2.
  ASSERT_EQ(bus->write(dronecan_command_of({1.0, -1.0 / 8191.0, 0.0, 4096.0 / 8191.0})),
            hal::BusStatus::ok);
  const auto frames = drain();
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].can_id, 0x0804060AU | CAN_EFF_FLAG);
  ASSERT_EQ(frames[0].can_dlc, 8);
  const std::vector<std::uint8_t> got(frames[0].data, frames[0].data + 8);
  EXPECT_EQ(got, (std::vector<std::uint8_t>{0xFF, 0x7F, 0xFF, 0xF0, 0x00, 0x00, 0x10, 0xC2}));
}

TEST_F(DronecanBusTest, StatusBecomesTelemetry) {
  auto bus = make_bus(4);
  std::string error;
  ASSERT_TRUE(bus->open(error)) << error;
  hal::ThrusterTelemetry t;
  EXPECT_EQ(bus->read(t), hal::BusStatus::degraded);  // nothing heard yet
  EXPECT_FALSE(t.valid);
  EXPECT_EQ(t.fault_flags[0] & dronecan_fault::kStale, dronecan_fault::kStale);

  for (std::uint8_t esc = 0; esc < 4; ++esc) {
    dronecan::EscStatus s;
    s.esc_index = esc;
    s.rpm = -1500 + 1000 * esc;
    send_status(s, 20 + esc, esc);
  }
  dronecan::EscStatus raised;  // ESC 2 reports a new error
  raised.esc_index = 2;
  raised.rpm = 500;
  raised.error_count = 7;
  send_status(raised, 22, 9);
  EXPECT_EQ(bus->read(t), hal::BusStatus::ok);
  EXPECT_TRUE(t.valid);
  ASSERT_EQ(t.count, 4U);
  EXPECT_DOUBLE_EQ(t.speed_rpm[0], -1500.0);
  EXPECT_DOUBLE_EQ(t.speed_rpm[3], 1500.0);
  EXPECT_EQ(t.fault_flags[0], 0);
  EXPECT_EQ(t.fault_flags[2], dronecan_fault::kErrorCount);
  EXPECT_EQ(bus->counters().status_received, 5U);
}

TEST_F(DronecanBusTest, BusOffIsAFaultUntilRestart) {
  auto bus = make_bus(4);
  std::string error;
  ASSERT_TRUE(bus->open(error)) << error;
  send_raw(CAN_ERR_FLAG | CAN_ERR_BUSOFF, std::vector<std::uint8_t>(CAN_ERR_DLC, 0));
  std::vector<std::uint8_t> passive(CAN_ERR_DLC, 0);
  passive[1] = CAN_ERR_CRTL_TX_PASSIVE;
  send_raw(CAN_ERR_FLAG | CAN_ERR_CRTL, passive);
  hal::ThrusterTelemetry t;
  EXPECT_EQ(bus->read(t), hal::BusStatus::fault);
  EXPECT_EQ(bus->write(dronecan_command_of({0, 0, 0, 0})), hal::BusStatus::fault);
  EXPECT_EQ(bus->can_counters().error_frames, 2U);
  EXPECT_EQ(bus->can_counters().bus_off_events, 1U);
  EXPECT_EQ(bus->can_counters().error_passive, 1U);
  send_raw(CAN_ERR_FLAG | CAN_ERR_RESTARTED, std::vector<std::uint8_t>(CAN_ERR_DLC, 0));
  bus->read(t);
  EXPECT_EQ(bus->write(dronecan_command_of({0, 0, 0, 0})), hal::BusStatus::ok);
}

TEST_F(DronecanBusTest, LostBusFaultsAfterConsecutiveFailures) {
  auto bus = make_bus(4);
  std::string error;
  ASSERT_TRUE(bus->open(error)) << error;
  ::close(fds_[1]);  // the bus is gone: every send fails
  fds_[1] = -1;
  const hal::ThrusterCommand cmd = dronecan_command_of({0.1, 0.1, 0.1, 0.1});
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::degraded);
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::degraded);
  EXPECT_EQ(bus->write(cmd), hal::BusStatus::fault);
  EXPECT_EQ(bus->counters().failed_ticks, 3U);
  EXPECT_GE(bus->can_counters().send_errors, 3U);
}

TEST(DronecanBusOpen, MissingInterfaceIsNamed) {
  DronecanParams p;
  p.interface = "rovctl_nocan0";
  DronecanThrusterBus bus(p, 8);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("rovctl_nocan0"), std::string::npos) << error;
  EXPECT_EQ(bus.write(dronecan_command_of({0.2})), hal::BusStatus::fault);
}

// On a kernel with SocketCAN and a vcan0 (modprobe vcan; ip link add vcan0 type vcan;
// ip link set vcan0 up): the bus and a second raw socket on the same virtual bus.
TEST(DronecanBusVcan, FramesReachAnotherSocket) {
  CanSocket peer;
  std::string error;
  if (!peer.open("vcan0", error)) GTEST_SKIP() << "no usable vcan0 here: " << error;
  DronecanParams p;
  p.interface = "vcan0";
  p.node_id = 10;
  p.priority = 8;
  DronecanThrusterBus bus(p, 8);
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  ASSERT_EQ(bus.write(dronecan_command_of({0.5, 0, 0, 0, 0, 0, 0, -0.5})), hal::BusStatus::ok);
  dronecan::TransferReassembler rx(dronecan::kRawCommandId, dronecan::kRawCommandSignature);
  int transfers = 0;
  std::array<std::int16_t, dronecan::kMaxRawCommands> cmd{};
  std::size_t count = 0;
  for (int i = 0; i < 1000 && transfers < 3; ++i) {
    CanFrame f;
    const CanSocket::Io r = peer.receive(f);
    if (r == CanSocket::Io::would_block) {
      ::usleep(1000);
      continue;
    }
    ASSERT_EQ(r, CanSocket::Io::ok);
    if (rx.accept(f)) {
      ++transfers;
      ASSERT_TRUE(dronecan::decode_raw_command(rx.payload(), cmd, count));
    }
  }
  ASSERT_EQ(transfers, 3);  // open, arm, write
  ASSERT_EQ(count, 8U);
  EXPECT_EQ(cmd[0], 4096);
  EXPECT_EQ(cmd[7], -4096);
}

}  // namespace
}  // namespace rovctl::drivers
