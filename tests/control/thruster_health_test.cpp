// ThrusterHealth on the BlueROV2-heavy layout: a flagged, dead, weak or stuck thruster is failed
// after its persistence, a healthy one following its command never is, a short glitch is not.
#include "control/thruster_health.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

struct Health : ::testing::Test {
  ThrusterHealthParams params;
  ThrusterEffectiveness effectiveness{hal::VehicleGeometry{}.thrusters, 0.0625};
  hal::ThrusterCommand command = [] {
    hal::ThrusterCommand c;
    c.count = 8;
    for (std::size_t ch = 0; ch < 8; ++ch) c.thrust_fraction[ch] = ch % 2 == 0 ? 0.6 : -0.5;
    return c;
  }();

  // The rpm a healthy thruster turns at in steady state for the command, as the mock reports it.
  double healthy_rpm(std::size_t i, double fraction) const {
    const double f = effectiveness.thrust_for_command(i, fraction);
    return std::copysign(
        params.full_thrust_rpm * std::sqrt(std::abs(f) / effectiveness.limit_n(i, f)), f);
  }
  hal::ThrusterTelemetry healthy() const {
    hal::ThrusterTelemetry t;
    t.valid = true;
    t.count = 8;
    for (std::size_t i = 0; i < 8; ++i) t.speed_rpm[i] = healthy_rpm(i, command.thrust_fraction[i]);
    return t;
  }
  // Ticks of `telemetry` until the first failure (0: none within `ticks`).
  int ticks_to_failure(ThrusterHealth& h, const hal::ThrusterTelemetry& telemetry, int ticks) {
    for (int k = 1; k <= ticks; ++k) {
      if (h.update(telemetry, command, 0.033) > 0) return k;
    }
    return 0;
  }
  // Settles the expected thrust on the command with healthy telemetry.
  void settle(ThrusterHealth& h) { ASSERT_EQ(ticks_to_failure(h, healthy(), 60), 0); }
};

TEST_F(Health, HealthyThrustersFollowingTheirCommandsNeverFail) {
  ThrusterHealth h(effectiveness, params);
  // Steps between full commands both ways, the thrust lagging 0.1 s behind (the mock's T200)
  // and integrated finer than the tick.
  double thrust_n[8] = {};
  for (int k = 0; k < 600; ++k) {
    hal::ThrusterTelemetry t = healthy();
    for (std::size_t i = 0; i < 8; ++i) {
      const double target = effectiveness.thrust_for_command(i, command.thrust_fraction[i]);
      for (int step = 0; step < 33; ++step)
        thrust_n[i] += (1.0 - std::exp(-0.001 / 0.1)) * (target - thrust_n[i]);
      t.speed_rpm[i] = std::copysign(
          params.full_thrust_rpm *
              std::sqrt(std::abs(thrust_n[i]) / effectiveness.limit_n(i, thrust_n[i])),
          thrust_n[i]);
    }
    EXPECT_EQ(h.update(t, command, 0.033), 0u) << "tick " << k;
    for (std::size_t ch = 0; ch < 8; ++ch) {
      command.thrust_fraction[ch] = (k / 40) % 2 == 0 ? 0.8 : -0.8;
    }
  }
  for (std::size_t i = 0; i < 8; ++i) EXPECT_FALSE(h.failed(i));
}

TEST_F(Health, FaultFlagFailsAfterItsPersistence) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry t = healthy();
  t.fault_flags[2] = 0x4;
  EXPECT_EQ(ticks_to_failure(h, t, 10), params.fault_flag_ticks);
  EXPECT_TRUE(h.failed(2));
  EXPECT_EQ(h.failure(2), ThrusterFailure::fault_flag);
  EXPECT_FALSE(h.failed(1));
}

TEST_F(Health, DeadThrusterWithoutAFlagIsFoundByItsRpm) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry t = healthy();
  t.speed_rpm[6] = 0.0;
  EXPECT_EQ(ticks_to_failure(h, t, 30), params.mismatch_ticks);
  EXPECT_EQ(h.failure(6), ThrusterFailure::dead);
}

TEST_F(Health, WeakThrusterAtThirtyPercentThrustIsFound) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry t = healthy();
  t.speed_rpm[4] *= std::sqrt(0.3);
  EXPECT_EQ(ticks_to_failure(h, t, 30), params.mismatch_ticks);
  EXPECT_EQ(h.failure(4), ThrusterFailure::weak);
  // 80 % of the thrust (89 % of the rpm) is within what a real propeller varies: not failed.
  ThrusterHealth h2(effectiveness, params);
  settle(h2);
  t = healthy();
  t.speed_rpm[4] *= std::sqrt(0.8);
  EXPECT_EQ(ticks_to_failure(h2, t, 100), 0);
}

TEST_F(Health, StuckThrusterTurningAgainstItsCommandOrAtNeutralIsFound) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry t = healthy();
  t.speed_rpm[1] = -t.speed_rpm[1];  // held the reverse of what it is asked
  EXPECT_EQ(ticks_to_failure(h, t, 30), params.mismatch_ticks);
  EXPECT_EQ(h.failure(1), ThrusterFailure::stuck);

  ThrusterHealth idle(effectiveness, params);
  command.thrust_fraction.fill(0.0);
  hal::ThrusterTelemetry spinning = healthy();
  spinning.speed_rpm[7] = 2500.0;  // turning on at neutral
  EXPECT_EQ(ticks_to_failure(idle, spinning, 30), params.mismatch_ticks);
  EXPECT_EQ(idle.failure(7), ThrusterFailure::stuck);
}

TEST_F(Health, AGlitchShorterThanThePersistenceFailsNothing) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry bad = healthy();
  bad.speed_rpm[0] = 0.0;
  bad.fault_flags[3] = 1;
  for (int round = 0; round < 20; ++round) {
    EXPECT_EQ(h.update(bad, command, 0.033), 0u);  // one tick bad (fewer than both counts)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(h.update(healthy(), command, 0.033), 0u);
  }
  EXPECT_FALSE(h.failed(0));
  EXPECT_FALSE(h.failed(3));
}

TEST_F(Health, InvalidTelemetryOrDisabledJudgesNothing) {
  ThrusterHealth h(effectiveness, params);
  settle(h);
  hal::ThrusterTelemetry t = healthy();
  t.fault_flags.fill(1);
  t.valid = false;
  EXPECT_EQ(ticks_to_failure(h, t, 30), 0);
  params.enabled = false;
  ThrusterHealth off(effectiveness, params);
  t.valid = true;
  EXPECT_EQ(ticks_to_failure(off, t, 30), 0);
}

}  // namespace
}  // namespace rovctl::control
