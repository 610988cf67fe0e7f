// Failsafe: each monitor trips into the safe state its policy names, recovers or latches as the
// policy says, and every trip, recovery and latch is logged once with its tick.
#include "control/failsafe.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <vector>

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

FailsafeInput healthy(std::chrono::nanoseconds now) {
  FailsafeInput in;
  in.now = now;
  in.fitness = 0.8;
  return in;
}

TEST(Failsafe, HealthyStaysNone) {
  Failsafe fs(FailsafeParams{});
  for (int k = 0; k < 100; ++k) EXPECT_EQ(fs.update(healthy(k * 33ms)), SafeAction::none);
  FailsafeEvent e;
  EXPECT_FALSE(fs.pop_event(e));
}

TEST(Failsafe, CameraLostTripsAtOnceAndLatches) {
  Failsafe fs(FailsafeParams{});
  FailsafeInput in = healthy(1s);
  in.grab = hal::GrabStatus::device_lost;
  EXPECT_EQ(fs.update(in), SafeAction::disarm);
  EXPECT_EQ(fs.cause(), FailsafeCause::camera_lost);
  EXPECT_EQ(fs.update(healthy(2s)), SafeAction::disarm);  // latched
  FailsafeEvent e;
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.cause, FailsafeCause::camera_lost);
  EXPECT_EQ(e.time, 1s);
  EXPECT_FALSE(fs.pop_event(e));  // logged once
  fs.reset(3s);
  EXPECT_EQ(fs.update(healthy(3s)), SafeAction::none);
}

TEST(Failsafe, CameraTimeoutsTripAfterTheAllowance) {
  FailsafeParams p;
  p.camera_timeout_ticks = 3;
  Failsafe fs(p);
  FailsafeInput in = healthy(0s);
  in.grab = hal::GrabStatus::timeout;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(fs.update(in), SafeAction::none);
  EXPECT_EQ(fs.update(healthy(0s)), SafeAction::none);  // a good frame resets the count
  for (int k = 0; k < 3; ++k) EXPECT_EQ(fs.update(in), SafeAction::none);
  EXPECT_EQ(fs.update(in), SafeAction::neutral);  // the default policy: neutral, recovers
  EXPECT_EQ(fs.cause(), FailsafeCause::vision_lost);
}

TEST(Failsafe, BusFaultAndLongDegradation) {
  {
    Failsafe fs(FailsafeParams{});
    FailsafeInput in = healthy(0s);
    in.bus = hal::BusStatus::fault;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
    EXPECT_EQ(fs.cause(), FailsafeCause::bus_fault);
  }
  {
    FailsafeParams p;
    p.bus_degraded_ticks = 2;
    Failsafe fs(p);
    FailsafeInput in = healthy(0s);
    in.bus = hal::BusStatus::degraded;
    EXPECT_EQ(fs.update(in), SafeAction::none);
    EXPECT_EQ(fs.update(in), SafeAction::none);
    EXPECT_EQ(fs.update(in), SafeAction::neutral);
    EXPECT_EQ(fs.cause(), FailsafeCause::bus_slow);
  }
}

TEST(Failsafe, NaNInTheEstimateOrTheWrench) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  {
    Failsafe fs(FailsafeParams{});
    FailsafeInput in = healthy(0s);
    in.T_cl_marker.translation().y() = nan;
    EXPECT_EQ(fs.update(in), SafeAction::neutral);
    EXPECT_EQ(fs.cause(), FailsafeCause::estimate_not_finite);
  }
  {
    Failsafe fs(FailsafeParams{});
    FailsafeInput in = healthy(0s);
    in.fitness = nan;
    fs.update(in);
    EXPECT_EQ(fs.cause(), FailsafeCause::estimate_not_finite);
  }
  {
    FailsafeParams p;
    p.action = "neutral";
    Failsafe fs(p);
    FailsafeInput in = healthy(0s);
    in.wrench_body[5] = std::numeric_limits<double>::infinity();
    EXPECT_EQ(fs.update(in), SafeAction::neutral);
    EXPECT_EQ(fs.cause(), FailsafeCause::wrench_not_finite);
  }
}

TEST(Failsafe, MissionLimits) {
  {
    Failsafe fs(FailsafeParams{});
    FailsafeInput in = healthy(0s);
    in.mission = MissionState::failed;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
    EXPECT_EQ(fs.cause(), FailsafeCause::mission_failed);
  }
  {
    FailsafeParams p;
    p.max_mission_time_s = 10.0;
    Failsafe fs(p);
    EXPECT_EQ(fs.update(healthy(5s)), SafeAction::none);  // the clock starts here
    EXPECT_EQ(fs.update(healthy(15s)), SafeAction::none);
    EXPECT_EQ(fs.update(healthy(15s + 1ms)), SafeAction::disarm);
    EXPECT_EQ(fs.cause(), FailsafeCause::mission_time);
  }
}

TEST(Failsafe, FirstCauseWins) {
  Failsafe fs(FailsafeParams{});
  FailsafeInput in = healthy(0s);
  in.bus = hal::BusStatus::fault;
  fs.update(in);
  in.grab = hal::GrabStatus::device_lost;
  fs.update(in);
  EXPECT_EQ(fs.cause(), FailsafeCause::bus_fault);
  EXPECT_STREQ(to_string(fs.cause()), "thruster bus fault");
}

TEST(Failsafe, AtTheStationALostCameraBacksOutFirstThenGoesSafe) {
  FailsafeParams p;
  p.backout_s = 4.0;
  Failsafe fs(p);
  FailsafeInput in = healthy(10s);
  in.mission = MissionState::charging;
  in.at_station = true;
  EXPECT_EQ(fs.update(in), SafeAction::none);
  in.grab = hal::GrabStatus::device_lost;
  in.now = 11s;
  EXPECT_EQ(fs.update(in), SafeAction::back_out);
  EXPECT_TRUE(fs.backing_out());
  EXPECT_EQ(fs.cause(), FailsafeCause::camera_lost);
  in.mission = MissionState::undock;
  in.now = 14s;
  EXPECT_EQ(fs.update(in), SafeAction::back_out);
  in.now = 15s;
  EXPECT_EQ(fs.update(in), SafeAction::disarm);  // backed out: the safe state proper
  EXPECT_FALSE(fs.backing_out());
  EXPECT_EQ(fs.update(in), SafeAction::disarm);
  FailsafeEvent e;
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.action, SafeAction::back_out);
  EXPECT_EQ(e.time, 11s);
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.action, SafeAction::disarm);
  EXPECT_EQ(e.cause, FailsafeCause::camera_lost);
  EXPECT_EQ(e.time, 15s);
  EXPECT_FALSE(fs.pop_event(e));
  EXPECT_STREQ(to_string(SafeAction::back_out), "back out");
}

TEST(Failsafe, NoBackOutAwayFromTheStationOrWithoutThrusters) {
  {
    Failsafe fs(FailsafeParams{});  // free in the water: as before
    FailsafeInput in = healthy(0s);
    in.mission = MissionState::approach;
    in.grab = hal::GrabStatus::device_lost;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
  }
  {
    Failsafe fs(FailsafeParams{});  // a bus that does not deliver cannot back anything out
    FailsafeInput in = healthy(0s);
    in.mission = MissionState::charging;
    in.at_station = true;
    in.bus = hal::BusStatus::fault;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
  }
  {
    Failsafe fs(FailsafeParams{});  // nor a wrench that is not finite
    FailsafeInput in = healthy(0s);
    in.at_station = true;
    in.wrench_body[0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
  }
  {
    Failsafe fs(FailsafeParams{});  // the bus fails while backing out: stop at once
    FailsafeInput in = healthy(0s);
    in.at_station = true;
    in.grab = hal::GrabStatus::device_lost;
    EXPECT_EQ(fs.update(in), SafeAction::back_out);
    in.now = 1s;
    in.bus = hal::BusStatus::fault;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
  }
  {
    FailsafeParams p;
    p.backout_s = 0.0;  // configured off
    Failsafe fs(p);
    FailsafeInput in = healthy(0s);
    in.at_station = true;
    in.grab = hal::GrabStatus::device_lost;
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
  }
}

TEST(Failsafe, TransientCauseRecoversAfterRecoverTicks) {
  FailsafeParams p;
  p.recover_ticks = 3;
  Failsafe fs(p);
  FailsafeInput in = healthy(0s);
  in.identical_frames = p.frozen_ticks;
  in.tick = 7;
  EXPECT_EQ(fs.update(in), SafeAction::neutral);
  EXPECT_EQ(fs.cause(), FailsafeCause::vision_frozen);
  EXPECT_TRUE(fs.awaiting_recovery());
  in.now = 33ms;
  EXPECT_EQ(fs.update(in), SafeAction::neutral);  // still frozen: no healthy tick yet
  for (int k = 0; k < 2; ++k) {
    FailsafeInput ok = healthy(66ms + k * 33ms);
    EXPECT_EQ(fs.update(ok), SafeAction::neutral);
    EXPECT_FALSE(fs.take_recovered());
  }
  FailsafeInput ok = healthy(200ms);
  ok.tick = 12;
  EXPECT_EQ(fs.update(ok), SafeAction::none);
  EXPECT_FALSE(fs.tripped());
  EXPECT_TRUE(fs.take_recovered());
  EXPECT_FALSE(fs.take_recovered());  // once
  FailsafeEvent e;
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.kind, FailsafeEventKind::trip);
  EXPECT_EQ(e.cause, FailsafeCause::vision_frozen);
  EXPECT_EQ(e.tick, 7u);
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.kind, FailsafeEventKind::recovered);
  EXPECT_EQ(e.cause, FailsafeCause::vision_frozen);
  EXPECT_EQ(e.tick, 12u);
  EXPECT_FALSE(fs.pop_event(e));
}

TEST(Failsafe, HardwareCauseLatchesUntilReset) {
  Failsafe fs(FailsafeParams{});
  hal::SensorReadings r;
  r.depth_valid = true;
  r.depth_m = std::numeric_limits<double>::quiet_NaN();
  FailsafeInput in = healthy(0s);
  in.sensors_fitted = in.sensors_answered = true;
  in.readings = &r;
  EXPECT_EQ(fs.update(in), SafeAction::disarm);
  EXPECT_EQ(fs.cause(), FailsafeCause::sensor_nan);
  EXPECT_FALSE(fs.awaiting_recovery());
  for (int k = 1; k < 100; ++k) EXPECT_EQ(fs.update(healthy(k * 33ms)), SafeAction::disarm);
  EXPECT_FALSE(fs.take_recovered());
  fs.reset(4s);  // the operator re-arms
  EXPECT_EQ(fs.update(healthy(4s)), SafeAction::none);
}

TEST(Failsafe, TransientTripThatDoesNotPassLatches) {
  FailsafeParams p;
  p.recover_within_s = 1.0;
  Failsafe fs(p);
  FailsafeInput in = healthy(0s);
  in.stereo_skew = 100ms;
  EXPECT_EQ(fs.update(in), SafeAction::neutral);
  EXPECT_EQ(fs.cause(), FailsafeCause::stereo_skew);
  in.now = 1100ms;
  fs.update(in);
  EXPECT_FALSE(fs.awaiting_recovery());
  for (int k = 0; k < 50; ++k) fs.update(healthy(2s + k * 33ms));
  EXPECT_TRUE(fs.tripped());  // latched: healthy ticks no longer clear it
  FailsafeEvent e;
  ASSERT_TRUE(fs.pop_event(e));
  ASSERT_TRUE(fs.pop_event(e));
  EXPECT_EQ(e.kind, FailsafeEventKind::latched);
}

TEST(Failsafe, HardwareFaultDuringATransientTripTakesOver) {
  Failsafe fs(FailsafeParams{});
  FailsafeInput in = healthy(0s);
  in.grab = hal::GrabStatus::timeout;
  fs.update(in);
  EXPECT_EQ(fs.update(in), SafeAction::neutral);
  EXPECT_EQ(fs.cause(), FailsafeCause::vision_lost);
  in.grab = hal::GrabStatus::device_lost;
  EXPECT_EQ(fs.update(in), SafeAction::disarm);
  EXPECT_EQ(fs.cause(), FailsafeCause::camera_lost);
  EXPECT_FALSE(fs.awaiting_recovery());
}

TEST(Failsafe, PolicyTableChangesActionAndRecovery) {
  FailsafeParams p;
  p.policy.rule(FailsafeCause::sensor_lost) = {"neutral", "auto"};
  p.policy.rule(FailsafeCause::cpu_overrun) = {"disarm", "latch"};
  p.recover_ticks = 1;
  {
    Failsafe fs(p);
    FailsafeInput in = healthy(0s);
    in.sensors_fitted = true;                    // not answering
    EXPECT_EQ(fs.update(in), SafeAction::none);  // one silent tick tolerated
    EXPECT_EQ(fs.update(in), SafeAction::neutral);
    EXPECT_EQ(fs.cause(), FailsafeCause::sensor_lost);
    EXPECT_EQ(fs.update(healthy(1s)), SafeAction::none);  // configured to recover
  }
  {
    Failsafe fs(p);
    FailsafeInput in = healthy(0s);
    in.overrun = true;
    fs.update(in);
    EXPECT_EQ(fs.update(in), SafeAction::disarm);
    EXPECT_EQ(fs.cause(), FailsafeCause::cpu_overrun);
    EXPECT_EQ(fs.update(healthy(1s)), SafeAction::disarm);  // configured to latch
  }
}

TEST(Failsafe, SensorAndImageMonitors) {
  struct Case {
    const char* what;
    FailsafeCause expected;
    std::function<void(FailsafeInput&, hal::SensorReadings&)> set;
  };
  const std::vector<Case> cases = {
      {"implausible depth", FailsafeCause::sensor_implausible,
       [](FailsafeInput&, hal::SensorReadings& r) { r.depth_m = -1000.0; }},
      {"gyro beyond the plausible", FailsafeCause::sensor_implausible,
       [](FailsafeInput&, hal::SensorReadings& r) { r.omega_body_radps.x() = 50.0; }},
      {"rolled 45 deg", FailsafeCause::attitude_limit,
       [](FailsafeInput&, hal::SensorReadings& r) {
         r.q_world_body = Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitX());
       }},
      {"black right image", FailsafeCause::camera_dead,
       [](FailsafeInput& in, hal::SensorReadings&) { in.image_dead = true; }},
      {"stale frame", FailsafeCause::vision_stale,
       [](FailsafeInput& in, hal::SensorReadings&) { in.frame_age = 400ms; }},
      {"leak detected", FailsafeCause::leak,
       [](FailsafeInput&, hal::SensorReadings& r) { r.leak_valid = r.leak = true; }},
      {"battery at 4 %", FailsafeCause::battery_low,
       [](FailsafeInput&, hal::SensorReadings& r) {
         r.battery_valid = true;
         r.soc_fraction = 0.04;
       }},
      {"battery at 4 %, unknown", FailsafeCause::none,
       [](FailsafeInput&, hal::SensorReadings& r) {
         r.battery_valid = false;
         r.soc_fraction = 0.04;
       }},
  };
  for (const Case& c : cases) {
    Failsafe fs(FailsafeParams{});
    hal::SensorReadings r;
    r.depth_valid = r.attitude_valid = true;
    r.depth_m = 2.0;
    FailsafeInput in = healthy(0s);
    in.sensors_fitted = in.sensors_answered = true;
    in.readings = &r;
    EXPECT_EQ(fs.update(in), SafeAction::none) << c.what;
    c.set(in, r);
    const SafeAction a = fs.update(in);
    EXPECT_EQ(a != SafeAction::none, c.expected != FailsafeCause::none) << c.what;
    EXPECT_EQ(fs.cause(), c.expected) << c.what;
  }
}

TEST(Failsafe, RejectsUnknownAction) {
  FailsafeParams p;
  p.action = "explode";
  EXPECT_THROW(Failsafe{p}, std::invalid_argument);
}

TEST(FailsafeThrusters, UncontrollableThrustersTripAsAThrusterFaultAndDoNotBackOut) {
  FailsafeParams p;
  Failsafe f(p);
  FailsafeInput in;
  in.at_station = true;  // a back-out needs thrusters that can push: not these
  EXPECT_EQ(f.update(in), SafeAction::none);
  in.now = std::chrono::milliseconds(33);
  in.thrusters_uncontrollable = true;
  EXPECT_EQ(f.update(in), SafeAction::disarm);
  EXPECT_EQ(f.cause(), FailsafeCause::thruster_fault);
  FailsafeEvent e;
  ASSERT_TRUE(f.pop_event(e));
  EXPECT_EQ(e.cause, FailsafeCause::thruster_fault);
  EXPECT_STREQ(to_string(e.cause), "thruster fault");
}

TEST(Failsafe, AnUnacknowledgedDisarmTakesOverALatchedTripAndHoldsNeutral) {
  Failsafe fs{FailsafeParams{}};
  FailsafeInput in = healthy(0s);
  in.sensors_fitted = true;  // silent: sensors lost after the tolerated tick
  fs.update(in);
  in.now = 33ms;
  ASSERT_EQ(fs.update(in), SafeAction::disarm);
  ASSERT_EQ(fs.cause(), FailsafeCause::sensor_lost);
  in.now = 66ms;
  in.disarm_unacked = true;  // a latched cause does not block it
  EXPECT_EQ(fs.update(in), SafeAction::neutral);
  EXPECT_EQ(fs.cause(), FailsafeCause::disarm_unacked);
  in.disarm_unacked = false;
  in.sensors_answered = true;
  in.now = 5s;
  EXPECT_EQ(fs.update(in), SafeAction::neutral) << "latched until the operator re-arms";
}

}  // namespace
}  // namespace rovctl::control
