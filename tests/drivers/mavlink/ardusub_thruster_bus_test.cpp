// The ArduSub thruster bus against a fake ArduSub on loopback UDP (a thread speaking MAVLink
// through the same codec): ids, neutral before arming, the arm handshake, scaled axes, the
// faults read from ArduSub's HEARTBEAT, and neutral + disarm on close.
#include "drivers/mavlink/ardusub_thruster_bus.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

#include "drivers/mavlink/fake_ardusub.hpp"
#include "drivers/mavlink/mavlink_messages.hpp"
#include "drivers/mavlink/mavlink_udp_link.hpp"
#include "drivers/mavlink/pty_pair.hpp"
// The hooks live in mavlink_codec_test.cpp, in the same binary.
#define ROVCTL_MALLOC_HOOKS_ELSEWHERE 1
#include "malloc_counter.hpp"

namespace rovctl::drivers {
namespace {

using namespace std::chrono_literals;
namespace mav = mavlink;
using drivers::testing::FakeArduSub;
using drivers::testing::Received;

ArdusubParams params_for(const FakeArduSub& peer) {
  ArdusubParams p;
  p.link = "udpout:127.0.0.1:" + std::to_string(peer.port());
  p.link_timeout_ms = 300;  // the fake beats at 50 Hz
  p.ack_timeout_ms = 1000;  // generous under load; the fake answers at once
  p.pilot_gain = 1.0;
  return p;
}

hal::ThrusterCommand all_forward(double f) {
  hal::ThrusterCommand c;
  c.count = 8;
  for (std::size_t i = 0; i < 4; ++i) c.thrust_fraction[i] = f;
  return c;
}

// Polls write() (as the I/O thread does each command) until it reports `want`.
hal::BusStatus write_until(ArdusubThrusterBus& bus, hal::BusStatus want,
                           std::chrono::milliseconds limit = 5000ms) {
  const auto end = std::chrono::steady_clock::now() + limit;
  hal::BusStatus s = bus.write(all_forward(0.2));
  while (s != want && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(5ms);
    s = bus.write(all_forward(0.2));
  }
  return s;
}

// Allocations over 50 of the I/O thread's cycles (a command written, telemetry read), 1 ms apart.
std::uint64_t allocations_over_50_cycles(ArdusubThrusterBus& bus) {
  const hal::ThrusterCommand c = all_forward(0.3);
  hal::ThrusterTelemetry t;
  const std::uint64_t before = rovctl::testing::t_allocations;
  for (int i = 0; i < 50; ++i) {
    (void)bus.write(c);
    (void)bus.read(t);
    std::this_thread::sleep_for(1ms);
  }
  return rovctl::testing::t_allocations - before;
}

TEST(ArdusubThrusterBus, OpenWaitsForArduSubThenSendsNeutralAsTheGcs) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_GE(bus.counters().heartbeats_received, 1U);
  ASSERT_TRUE(peer.wait_for([](const auto& r) {
    for (const Received& x : r) {
      if (x.is_manual) return true;
    }
    return false;
  }));
  for (const Received& x : peer.received()) {
    if (x.header.system_id == 1 && x.header.component_id == 191) continue;  // the GCS status
    EXPECT_EQ(x.header.system_id, 255);
    EXPECT_EQ(x.header.component_id, 190);
    if (x.is_manual) {
      EXPECT_EQ(x.manual.target, 1);
      EXPECT_EQ(x.manual.x, 0);
      EXPECT_EQ(x.manual.y, 0);
      EXPECT_EQ(x.manual.z, 500);
      EXPECT_EQ(x.manual.r, 0);
    }
  }
}

TEST(ArdusubThrusterBus, OpenWithoutArduSubFailsNamingTheLink) {
  FakeArduSub peer;
  peer.beating = false;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("no HEARTBEAT from ArduSub (system 1"), std::string::npos) << error;
  EXPECT_NE(error.find("udpout:127.0.0.1:"), std::string::npos) << error;
}

TEST(ArdusubThrusterBus, DisarmedSendsNeutralArmedSendsTheScaledWrench) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
  EXPECT_EQ(bus.last_axes(), (ArdusubAxes{0, 0, 500, 0}));

  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  EXPECT_TRUE(peer.armed);
  EXPECT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
  const long x = std::lround(1000.0 * 4.0 * std::sqrt(0.5) * 0.5 * 51.5 / 130.0);
  EXPECT_EQ(bus.last_axes(), (ArdusubAxes{static_cast<std::int16_t>(x), 0, 500, 0}));
  ASSERT_TRUE(peer.wait_for([x](const auto& r) {
    for (const Received& m : r) {
      if (m.is_manual && m.manual.x == x) return true;
    }
    return false;
  }));
  // The arm request: COMMAND_LONG ARM_DISARM to ArduSub's ids, param1 = 1, not forced.
  bool saw_arm = false;
  for (const Received& m : peer.received()) {
    if (m.is_command && m.command.command == mav::kCmdComponentArmDisarm) {
      saw_arm = true;
      EXPECT_EQ(m.command.target_system, 1);
      EXPECT_EQ(m.command.target_component, 1);
      EXPECT_EQ(m.command.params[0], 1.0F);
      EXPECT_EQ(m.command.params[1], 0.0F);
    }
  }
  EXPECT_TRUE(saw_arm);
}

TEST(ArdusubThrusterBus, RefusedArmingIsAFault) {
  FakeArduSub peer;
  peer.refuse_arm = true;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.arm(true), hal::BusStatus::fault);
  EXPECT_EQ(bus.fault(), ArdusubFault::arm_refused);
  EXPECT_FALSE(bus.armed());
  // ArduSub's own words reach rovctl's error: its result and its PreArm STATUSTEXT.
  ASSERT_NE(bus.fault_reason(), nullptr);
  EXPECT_STREQ(bus.fault_reason(), "ArduSub refused arm (MAV_RESULT 4): PreArm: Check mag field");
  EXPECT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::fault);
  EXPECT_EQ(bus.last_axes(), (ArdusubAxes{0, 0, 500, 0}));
}

class SteadyClock final : public hal::Clock {
 public:
  std::chrono::nanoseconds now() const override {
    return std::chrono::steady_clock::now().time_since_epoch();
  }
  void sleep_until(std::chrono::nanoseconds) override {}
};

// `rovctl check` asks ArduSub what would refuse an arm, without arming.
TEST(ArdusubThrusterBus, PrearmChecksReportArduSubsFailureWithoutArming) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.run_prearm_checks(), std::optional<std::string>(""));
  peer.refuse_arm = true;
  EXPECT_EQ(bus.run_prearm_checks(), std::optional<std::string>("PreArm: Check mag field"));
  EXPECT_FALSE(peer.armed);
}

// ArduSub boots in MANUAL: rovctl asks for its flight mode (DO_SET_MODE, custom mode) before
// it arms, and arms only once ArduSub took it.
TEST(ArdusubThrusterBus, BootedInManualItSetsTheFlightModeThenArms) {
  FakeArduSub peer;
  peer.mode = 19;  // MANUAL, ArduSub's mode at boot
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.arm(true), hal::BusStatus::ok);
  EXPECT_EQ(peer.mode, 0u);  // STABILIZE, the configured flight_mode
  EXPECT_TRUE(peer.armed);
  int set_mode_at = -1, arm_at = -1, i = 0;
  for (const Received& m : peer.received()) {
    if (m.is_command && m.command.command == mav::kCmdDoSetMode && set_mode_at < 0) {
      set_mode_at = i;
      EXPECT_EQ(m.command.params[0], 1.0F);  // MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
      EXPECT_EQ(m.command.params[1], 0.0F);
    }
    if (m.is_command && m.command.command == mav::kCmdComponentArmDisarm && arm_at < 0) arm_at = i;
    ++i;
  }
  ASSERT_GE(set_mode_at, 0) << "no DO_SET_MODE";
  EXPECT_LT(set_mode_at, arm_at) << "the mode first, then the arm";
  EXPECT_EQ(write_until(bus, hal::BusStatus::ok, 200ms), hal::BusStatus::ok);
}

TEST(ArdusubThrusterBus, AModeArduSubRefusesIsARefusalThatSaysSo) {
  FakeArduSub peer;
  peer.mode = 19;
  peer.refuse_mode = true;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.arm(true), hal::BusStatus::fault);
  EXPECT_FALSE(peer.armed);  // never asked
  EXPECT_EQ(bus.fault(), ArdusubFault::arm_refused);
  ASSERT_NE(bus.fault_reason(), nullptr);
  EXPECT_STREQ(bus.fault_reason(),
               "ArduSub stayed in mode 19 after DO_SET_MODE stabilize (0), refused");
}

// ArduSub gone silent: its attitude stream (asked at the tick's pace) stops long before the 1 Hz
// HEARTBEAT can tell, and the bus says so with the figure.
TEST(ArdusubThrusterBus, AnAttitudeStreamThatStopsIsSilentWithinItsTimeout) {
  FakeArduSub peer;
  peer.streaming = true;
  SteadyClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  ArdusubParams params = params_for(peer);
  params.link_timeout_ms = 1500;
  params.stream_timeout_ms = 200;
  ArdusubThrusterBus bus(params, hal::ThrusterLayout::bluerov2_heavy());
  bus.attach(sensors);
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  EXPECT_EQ(write_until(bus, hal::BusStatus::ok, 200ms), hal::BusStatus::ok);
  peer.attitude = false;  // HEARTBEAT and pressure go on
  const auto stopped = std::chrono::steady_clock::now();
  EXPECT_EQ(write_until(bus, hal::BusStatus::fault, 2000ms), hal::BusStatus::fault);
  const auto after = std::chrono::steady_clock::now() - stopped;
  EXPECT_EQ(bus.fault(), ArdusubFault::stream_silent);
  EXPECT_GE(after, 150ms);
  EXPECT_LT(after, 500ms) << "silence is told by the stream, not the heartbeat";
  ASSERT_NE(bus.fault_reason(), nullptr);
  const std::string why = bus.fault_reason();
  EXPECT_EQ(why.rfind("ArduSub silent: no ATTITUDE_QUATERNION for ", 0), 0u) << why;
  EXPECT_NE(why.find("(limit 200 ms; HEARTBEAT"), std::string::npos) << why;
}

TEST(ArdusubThrusterBus, LostHeartbeatIsAFault) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  peer.beating = false;
  EXPECT_EQ(write_until(bus, hal::BusStatus::fault), hal::BusStatus::fault);
  EXPECT_EQ(bus.fault(), ArdusubFault::link_lost);
  ASSERT_NE(bus.fault_reason(), nullptr);
  EXPECT_NE(std::string(bus.fault_reason()).find("ArduSub link lost: no HEARTBEAT for "),
            std::string::npos)
      << bus.fault_reason();
}

TEST(ArdusubThrusterBus, ArduSubDisarmingUnderUsIsAFaultUntilRearmed) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  peer.armed = false;  // e.g. its pilot-input failsafe
  EXPECT_EQ(write_until(bus, hal::BusStatus::fault), hal::BusStatus::fault);
  EXPECT_EQ(bus.fault(), ArdusubFault::disarmed_under_us);
  peer.armed = true;  // latched: a later armed HEARTBEAT does not clear it
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(bus.write(all_forward(0.1)), hal::BusStatus::fault);
  EXPECT_EQ(bus.arm(true), hal::BusStatus::ok);
}

TEST(ArdusubThrusterBus, ModeChangedUnderUsIsAFault) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  peer.mode = 9;  // SURFACE
  EXPECT_EQ(write_until(bus, hal::BusStatus::fault), hal::BusStatus::fault);
  EXPECT_EQ(bus.fault(), ArdusubFault::mode_changed);
}

TEST(ArdusubThrusterBus, CloseSendsNeutralThenDisarm) {
  FakeArduSub peer;
  {
    ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
    std::string error;
    ASSERT_TRUE(bus.open(error)) << error;
    ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
    ASSERT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
    bus.close();
    bus.close();  // idempotent
  }
  EXPECT_FALSE(peer.armed);
  const std::vector<Received> r = peer.received();
  std::size_t last_manual = r.size();
  std::size_t last_disarm = r.size();
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r[i].is_manual) last_manual = i;
    if (r[i].is_command && r[i].command.params[0] == 0.0F) last_disarm = i;
  }
  ASSERT_LT(last_manual, r.size());
  ASSERT_LT(last_disarm, r.size());
  EXPECT_LT(last_manual, last_disarm);
  EXPECT_EQ(r[last_manual].manual.x, 0);
  EXPECT_EQ(r[last_manual].manual.z, 500);
}

TEST(ArdusubThrusterBus, FeedsAttachedSensorsAndRequestsTheirStreams) {
  FakeArduSub peer;
  peer.streaming = true;
  SteadyClock clock;
  ArdusubSensorParams sp;
  sp.stream_interval_ms = 40;
  sp.stale_ms = 2000;
  ArdusubSensors sensors(sp, clock);
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  bus.attach(sensors);
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  hal::SensorReadings r;
  const auto end = std::chrono::steady_clock::now() + 5s;
  while (!(sensors.read(r) && r.attitude_valid && r.depth_valid) &&
         std::chrono::steady_clock::now() < end) {
    (void)bus.write(all_forward(0.0));  // the I/O thread's cycle drains the socket
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(r.attitude_valid);
  EXPECT_NEAR(std::abs(r.q_world_body.x()), 1.0, 1e-6);
  ASSERT_TRUE(r.depth_valid);
  EXPECT_NEAR(r.depth_m, 100.0 / 1025.0 / 9.80665 * 100.0, 1e-3);
  ASSERT_TRUE(peer.wait_for([](const auto& rx) {
    int n = 0;
    for (const Received& m : rx)
      n += m.is_command && m.command.command == mav::kCmdSetMessageInterval;
    return n == 3;
  }));
  std::vector<std::uint32_t> requested;
  for (const Received& m : peer.received()) {
    if (m.is_command && m.command.command == mav::kCmdSetMessageInterval) {
      requested.push_back(static_cast<std::uint32_t>(m.command.params[0]));
      EXPECT_EQ(m.command.params[1], 40000.0F);
    }
  }
  EXPECT_EQ(requested, (std::vector<std::uint32_t>{31, 137, 1}));
}

// Armed before the streams arrive, the first tick would find no readings: open() waits for them
// and fails, naming them, when ArduSub beats but never streams.
TEST(ArdusubThrusterBus, OpenWithSensorsWaitsForAttitudeAndDepth) {
  FakeArduSub peer;  // beats, does not stream
  SteadyClock clock;
  ArdusubSensors sensors(ArdusubSensorParams{}, clock);
  ArdusubParams params = params_for(peer);
  params.link_timeout_ms = 1100;
  ArdusubThrusterBus bus(params, hal::ThrusterLayout::bluerov2_heavy());
  bus.attach(sensors);
  std::string error;
  EXPECT_FALSE(bus.open(error));
  EXPECT_NE(error.find("ATTITUDE_QUATERNION and SCALED_PRESSURE2"), std::string::npos) << error;

  peer.streaming = true;
  // The sensors outlive the bus that feeds them (attach()'s contract): its close() still pumps.
  ArdusubSensors fed(ArdusubSensorParams{}, clock);
  ArdusubThrusterBus streamed(params, hal::ThrusterLayout::bluerov2_heavy());
  streamed.attach(fed);
  ASSERT_TRUE(streamed.open(error)) << error;
  hal::SensorReadings r;
  ASSERT_TRUE(fed.read(r));  // the first tick after open() has its readings
  EXPECT_TRUE(r.attitude_valid && r.depth_valid);
}

ArdusubParams thrusters_mode(const FakeArduSub& peer) {
  ArdusubParams p = params_for(peer);
  p.mode = "thrusters";
  return p;
}

bool saw_rc_channel(const std::vector<Received>& r, std::size_t channel, std::uint16_t us) {
  for (const Received& m : r) {
    if (m.is_rc_override && m.rc_override.channels_us[channel] == us) return true;
  }
  return false;
}

TEST(ArdusubThrusterBus, ThrustersModeSendsEachFractionAsPwmOnlyWhileArmed) {
  FakeArduSub peer;
  ArdusubThrusterBus bus(thrusters_mode(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  EXPECT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
  EXPECT_EQ(bus.last_rc_override().channels_us[0], 1500);  // disarmed: neutral

  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  hal::ThrusterCommand c = all_forward(0.5);
  c.thrust_fraction[4] = -0.25;
  EXPECT_EQ(bus.write(c), hal::BusStatus::ok);
  ASSERT_TRUE(peer.wait_for([](const auto& r) { return saw_rc_channel(r, 4, 1400); }));
  for (const Received& m : peer.received()) {
    EXPECT_FALSE(m.is_manual) << "MANUAL_CONTROL would overwrite channels 1-6";
    if (!m.is_rc_override || m.rc_override.channels_us[4] != 1400) continue;
    EXPECT_EQ(m.header.system_id, 255);
    EXPECT_EQ(m.header.component_id, 190);
    EXPECT_EQ(m.rc_override.target_system, 1);
    EXPECT_EQ(m.rc_override.target_component, 1);
    for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(m.rc_override.channels_us[i], 1700) << i;
    for (std::size_t i = 5; i < 8; ++i) EXPECT_EQ(m.rc_override.channels_us[i], 1500) << i;
    for (std::size_t i = 8; i < 18; ++i) EXPECT_EQ(m.rc_override.channels_us[i], 0) << i;
  }
  c.thrust_fraction[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(bus.write(c), hal::BusStatus::ok);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(bus.last_rc_override().channels_us[i], 1500);
}

TEST(ArdusubThrusterBus, ThrustersModeCloseSendsNeutralPwmThenDisarm) {
  FakeArduSub peer;
  {
    ArdusubThrusterBus bus(thrusters_mode(peer), hal::ThrusterLayout::bluerov2_heavy());
    std::string error;
    ASSERT_TRUE(bus.open(error)) << error;
    ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
    ASSERT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
    ASSERT_TRUE(peer.wait_for([](const auto& r) { return saw_rc_channel(r, 0, 1700); }));
  }  // the destructor closes
  EXPECT_FALSE(peer.armed);
  const std::vector<Received> r = peer.received();
  std::size_t last_rc = r.size();
  std::size_t last_disarm = r.size();
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r[i].is_rc_override) last_rc = i;
    if (r[i].is_command && r[i].command.command == mav::kCmdComponentArmDisarm &&
        r[i].command.params[0] == 0.0F) {
      last_disarm = i;
    }
  }
  ASSERT_LT(last_rc, r.size());
  ASSERT_LT(last_disarm, r.size());
  EXPECT_LT(last_rc, last_disarm);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(r[last_rc].rc_override.channels_us[i], 1500);
}

TEST(ArdusubThrusterBus, ThrustersModeWriteAllocatesNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) GTEST_SKIP() << "no malloc hooks under ASan";
  FakeArduSub peer;
  ArdusubThrusterBus bus(thrusters_mode(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  const std::uint64_t sent_before = bus.counters().rc_override_sent;
  EXPECT_EQ(allocations_over_50_cycles(bus), 0U);
  EXPECT_EQ(bus.counters().rc_override_sent - sent_before, 50U);
}

// ArduSub's serial port wired to the computer (serial:DEVICE:BAUD): the same handshake, commands
// and final disarm as over UDP, here on a pseudo-terminal.
TEST(ArdusubThrusterBus, OverASerialLineArmsCommandsAndDisarms) {
  testing::PtyPair pty;
  if (!pty.ok()) GTEST_SKIP() << "no pseudo-terminal on this machine (openpty failed)";
  {
    FakeArduSub peer(pty.leader);
    ArdusubParams p;
    p.link = "serial:" + pty.path + ":115200";
    p.link_timeout_ms = 300;
    p.ack_timeout_ms = 1000;
    p.pilot_gain = 1.0;
    {
      ArdusubThrusterBus bus(p, hal::ThrusterLayout::bluerov2_heavy());
      std::string error;
      ASSERT_TRUE(bus.open(error)) << error;
      ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
      EXPECT_TRUE(peer.armed);
      EXPECT_EQ(bus.write(all_forward(0.5)), hal::BusStatus::ok);
      ASSERT_TRUE(peer.wait_for([](const std::vector<Received>& r) {
        for (const Received& m : r) {
          if (m.is_manual && m.manual.x > 0 && m.header.system_id == 255) return true;
        }
        return false;
      }));
    }  // the destructor closes: neutral, then disarm
    EXPECT_FALSE(peer.armed);
  }
}

TEST(ArdusubThrusterBus, WriteAndReadAllocateNothing) {
  if (!rovctl::testing::malloc_hooks_installed()) GTEST_SKIP() << "no malloc hooks under ASan";
  FakeArduSub peer;
  ArdusubThrusterBus bus(params_for(peer), hal::ThrusterLayout::bluerov2_heavy());
  std::string error;
  ASSERT_TRUE(bus.open(error)) << error;
  ASSERT_EQ(bus.arm(true), hal::BusStatus::ok);
  EXPECT_EQ(allocations_over_50_cycles(bus), 0U);
  hal::ThrusterTelemetry t;  // no per-thruster telemetry through ArduSub
  (void)bus.read(t);
  EXPECT_FALSE(t.valid);
  EXPECT_EQ(t.count, 8U);
}

}  // namespace
}  // namespace rovctl::drivers
