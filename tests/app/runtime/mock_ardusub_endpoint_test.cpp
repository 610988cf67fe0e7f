// The mock ArduSub over real loopback UDP, stepped on the virtual clock: it answers arm/disarm,
// streams at the requested interval, obeys only the GCS id, and rovctl's own ArduSub driver and
// sensors fly the simulated vehicle through it.
#include "app/runtime/mock_ardusub_endpoint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "app/runtime/stepped_ardusub_bus.hpp"
#include "hal/mock/sim_clock.hpp"

namespace rovctl::app {
namespace {

namespace mav = drivers::mavlink;
using std::chrono::milliseconds;

struct Peer : ::testing::Test {
  hal::mock::SimParams params = [] {
    hal::mock::SimParams p;
    p.thrusters.time_constant_s = 0.0;
    p.current.random_sigma_mps.setZero();
    return p;
  }();
  hal::mock::SimulatedWorld world{params, hal::VehicleGeometry{}, hal::DockingStation{}};
  hal::mock::SimClock clock{world, hal::mock::SimClock::Mode::virtual_time};
  hal::mock::MockArdusub ardusub{world, params.ardusub};
  MockArdusubEndpoint peer{ardusub, clock, 255, 1};
  mav::MavlinkUdpLink gcs;
  mav::FrameWriter writer{255, 190};

  void SetUp() override {
    ardusub.set_mode(hal::mock::kArdusubModeStabilize);
    std::string error;
    ASSERT_TRUE(peer.open(error)) << error;
    mav::UdpEndpoint e;
    e.mode = mav::UdpEndpoint::Mode::send_to;
    e.address = "127.0.0.1";
    e.port = peer.port();
    ASSERT_TRUE(gcs.open(e, error)) << error;
  }
  template <typename M>
  void send(const M& m, mav::FrameWriter& from) {
    std::array<std::uint8_t, mav::kMaxFrameBytes> out{};
    const std::size_t n = mav::write_message(from, m, out);
    ASSERT_EQ(gcs.send(std::span<const std::uint8_t>(out.data(), n)), mav::MavlinkUdpLink::Io::ok);
  }
  template <typename M>
  void send(const M& m) {
    send(m, writer);
  }
  // Everything that arrived at the GCS so far, counted per message id.
  std::map<std::uint32_t, int> drain(mav::CommandAck* last_ack = nullptr) {
    std::map<std::uint32_t, int> n;
    mav::Frame f;
    while (gcs.receive(f) == mav::MavlinkUdpLink::Io::ok) {
      EXPECT_EQ(f.header.system_id, 1);
      EXPECT_EQ(f.header.component_id, 1);
      ++n[f.header.message_id];
      if (last_ack != nullptr) (void)mav::unpack(f, *last_ack);
    }
    return n;
  }
};

TEST_F(Peer, ArmAndDisarmAreAcknowledgedAndTaken) {
  send(mav::arm_disarm(1, 1, true, false));
  peer.service();
  mav::CommandAck ack;
  auto got = drain(&ack);
  EXPECT_EQ(got[mav::CommandAck::kId], 1);
  EXPECT_EQ(ack.command, mav::kCmdComponentArmDisarm);
  EXPECT_EQ(ack.result, 0);
  EXPECT_TRUE(ardusub.armed());
  EXPECT_EQ(got[mav::Heartbeat::kId], 1);  // the first beat goes out once it knows the GCS
  send(mav::arm_disarm(1, 1, false, false));
  peer.service();
  drain();
  EXPECT_FALSE(ardusub.armed());
}

TEST_F(Peer, StreamsAtTheRequestedIntervalOnTheVirtualClock) {
  send(mav::set_message_interval(1, 1, mav::AttitudeQuaternion::kId, 100'000.0F));  // 100 ms
  send(mav::set_message_interval(1, 1, mav::ScaledPressure2::kId, 250'000.0F));
  for (int ms = 0; ms < 2000; ms += 10) {
    clock.sleep_until(milliseconds(ms));
    peer.service();
  }
  auto got = drain();
  EXPECT_EQ(peer.interval(mav::AttitudeQuaternion::kId), milliseconds(100));
  EXPECT_EQ(got[mav::AttitudeQuaternion::kId], 20);
  EXPECT_EQ(got[mav::ScaledPressure2::kId], 8);
  EXPECT_EQ(got[mav::SysStatus::kId], 0);  // never asked for
  EXPECT_EQ(got[mav::Heartbeat::kId], 2);  // 1 Hz
  EXPECT_EQ(got[mav::CommandAck::kId], 2);
}

TEST_F(Peer, ManualControlOnlyFromTheGcsIdAndAimedAtTheVehicle) {
  send(mav::arm_disarm(1, 1, true, false));
  mav::ManualControl mc;
  mc.x = 600;
  mc.z = 500;
  mc.target = 1;
  mav::FrameWriter stranger(42, 190);
  send(mc, stranger);
  mc.target = 0;
  send(mc);
  peer.service();
  EXPECT_EQ(peer.counters().ignored, 2u);
  EXPECT_DOUBLE_EQ(ardusub.demanded_wrench()(0), 0.0);
  mc.target = 1;
  send(mc);
  peer.service();
  EXPECT_EQ(peer.counters().manual_control, 1u);
  EXPECT_GT(ardusub.demanded_wrench()(0), 10.0);
}

// rovctl's own driver and sensors against the peer, stepped as `rovctl sim` steps them.
TEST_F(Peer, TheArdusubDriverArmsThrustsAndReadsTheStreamedAttitude) {
  drivers::ArdusubParams p;
  p.link = "udpout:127.0.0.1:" + std::to_string(peer.port());
  drivers::ArdusubThrusterBus bus(p, world.vehicle().thrusters);
  drivers::ArdusubSensorParams sp;
  sp.stream_interval_ms = 33;
  drivers::ArdusubSensors sensors(sp, clock);
  bus.attach(sensors);
  bus.set_wait_hook([this] { peer.service(); });
  SteppedArdusubBus stepped(bus, peer, &sensors);
  std::string error;
  ASSERT_TRUE(stepped.open(error)) << error;
  ASSERT_EQ(stepped.arm(true), hal::BusStatus::ok);
  EXPECT_TRUE(ardusub.armed());
  // 20 N forward from the allocator's fractions: the driver's map, ArduSub's axes, its mixer.
  hal::ThrusterCommand forward;
  forward.count = world.vehicle().thrusters.thrusters.size();
  const drivers::ArdusubWrenchMap map(world.vehicle().thrusters, p.scale, p.pilot_gain);
  for (std::size_t i = 0; i < forward.count; ++i) forward.thrust_fraction[i] = 0.0;
  forward.thrust_fraction[0] = forward.thrust_fraction[1] = 0.3;  // the Heavy's forward pair
  hal::SensorReadings r;
  for (int tick = 1; tick <= 30; ++tick) {
    clock.sleep_until(milliseconds(33 * tick));
    hal::ThrusterTelemetry tel;
    ASSERT_EQ(stepped.read(tel), hal::BusStatus::ok);
    ASSERT_TRUE(sensors.read(r));
    ASSERT_EQ(stepped.write(forward), hal::BusStatus::ok);
  }
  EXPECT_TRUE(r.attitude_valid);
  EXPECT_TRUE(r.depth_valid);
  EXPECT_LT(r.q_world_body.angularDistance(world.state().q_world_body), 1e-3);
  EXPECT_NEAR(r.depth_m, world.state().position_world_m.z(), 0.01);
  EXPECT_EQ(sensors.published(), peer.sensor_frames_sent());
  EXPECT_EQ(peer.counters().manual_control, bus.counters().manual_control_sent);
  EXPECT_GT(map.wrench(forward)(0), 5.0);
  EXPECT_GT(world.truth().thrust_wrench_body(0), 5.0);
  EXPECT_GT(world.state().velocity_body_mps().x(), 0.05);
  stepped.close();
  EXPECT_FALSE(ardusub.armed()) << "neutral and disarm on the way out";
}

}  // namespace
}  // namespace rovctl::app
