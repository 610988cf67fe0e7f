// The recharging mission after DOCKED: the seated hold, charge complete, each charging fault (probe
// unseated -> re-seat, then UNDOCK and ABORT; current beyond the hold; no charger current), the
// operator's command and the time limit, each ending in its stated state with its logged cause.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "control/mission.hpp"
#include "hal/model/docking_station.hpp"
#include "hal/model/vehicle_geometry.hpp"

namespace rovctl::control {
namespace {

using namespace std::chrono_literals;

class RechargeMissionTest : public ::testing::Test {
 protected:
  hal::VehicleGeometry geometry;
  Eigen::Isometry3d T_body_cl = geometry.T_body_cl();
  Eigen::Isometry3d docked =
      hal::docked_T_cl_marker(T_body_cl, geometry.probe_tip_body_m, hal::DockingStation{});
  MissionParams params = [] {
    MissionParams p;
    p.kind = "recharge";
    return p;
  }();
  std::chrono::nanoseconds now{0};
  std::vector<std::string> log;

  Mission make() { return Mission(params, T_body_cl, docked, geometry.probe_tip_body_m); }

  // The marker as seen with the vehicle `back_m` short of docked along body x (negative: past the
  // socket mouth, into the seat).
  Eigen::Isometry3d seen_at(double back_m, double lateral_m = 0.0, double yaw_rad = 0.0) const {
    const Eigen::Isometry3d T = Eigen::Translation3d(back_m, lateral_m, 0.0) *
                                Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
    return T_body_cl.inverse() * T * T_body_cl * docked;
  }

  struct Charge {
    bool contact = true;
    double current_a = 15.0;
    double soc = 0.5;
    double hold_force_n = 5.0;
    bool undock = false;
    bool seen = true;
    double back_m = -0.02;  // seated: 2 cm past the socket mouth
    double yaw_rad = 0.0;   // the vehicle turned about body z
  };

  MissionOutput tick(Mission& m, const Charge& c) {
    now += 33ms;
    MissionInput in;
    in.now = now;
    in.recognised = c.seen;
    in.full_view = c.seen;
    in.fitness = 0.9;
    in.T_cl_marker = seen_at(c.back_m, 0.0, c.yaw_rad);
    in.contact = c.contact;
    in.charger_valid = true;
    in.charge_current_a = c.current_a;
    in.battery_valid = true;
    in.soc_fraction = c.soc;
    in.hold_force_n = c.hold_force_n;
    in.undock_requested = c.undock;
    const MissionOutput out = m.update(in);
    MissionEvent e;
    while (m.pop_event(e)) {
      log.push_back(std::string(to_string(e.from)) + ">" + to_string(e.to) + ":" + e.reason);
    }
    return out;
  }
  MissionOutput ticks(Mission& m, const Charge& c, std::chrono::milliseconds span) {
    MissionOutput out;
    for (auto t = 0ms; t < span; t += 33ms) out = tick(m, c);
    return out;
  }
  bool logged(const std::string& entry) const {
    for (const auto& l : log)
      if (l == entry) return true;
    return false;
  }

  // SEARCH -> ... -> DOCK -> DOCKED -> CHARGING with the marker seen all the way.
  void to_charging(Mission& m) {
    Charge far;
    far.contact = false;
    far.back_m = params.standoff_m;
    for (int k = 0; k < params.acquire_frames + 1 + params.align_hold_frames; ++k) tick(m, far);
    ASSERT_EQ(m.state(), MissionState::dock);
    Charge seat;
    for (int k = 0; k < params.contact_frames; ++k) tick(m, seat);
    ASSERT_EQ(m.state(), MissionState::charging);
  }

  // Backs the vehicle out to the stand-off, the marker in view.
  MissionOutput back_out(Mission& m) {
    Charge out;
    out.contact = false;
    MissionOutput o;
    for (double back = 0.0; back <= params.standoff_m + 1e-9; back += 0.05) {
      out.back_m = back;
      o = tick(m, out);
    }
    return o;
  }
};

TEST_F(RechargeMissionTest, HoldsSeatedWhileChargingThenUndocksAndDeparts) {
  Mission m = make();
  to_charging(m);
  EXPECT_TRUE(logged("dock>docked:contact"));
  EXPECT_TRUE(logged("docked>charging:seated: charging"));
  MissionOutput out = ticks(m, Charge{}, 10s);
  EXPECT_EQ(out.state, MissionState::charging);
  EXPECT_FALSE(m.finished());
  // The hold: the servo on lateral and yaw, the push along the docking axis (body +x here).
  EXPECT_TRUE(out.thrusters_enabled);
  EXPECT_TRUE(out.servo_active);
  EXPECT_FALSE(out.servo_restart);  // the integral's trim carries over from the dock
  EXPECT_NEAR(out.push_body[0], params.recharge.charge_push_n, 1e-6);
  EXPECT_NEAR(out.push_body.segment<2>(1).norm(), 0.0, 1e-6);
  // Along the axis the set-point is where the probe is: the servo does not pull it out.
  EXPECT_NEAR((out.T_cl_marker_desired.translation() - seen_at(-0.02).translation()).norm(), 0.0,
              1e-6);

  Charge full;
  full.soc = params.recharge.soc_complete_fraction;
  out = tick(m, full);
  EXPECT_EQ(out.state, MissionState::undock);
  EXPECT_TRUE(m.charge_complete());
  EXPECT_TRUE(logged("charging>undock:charge complete (state of charge)"));
  EXPECT_TRUE(out.servo_active);
  out = back_out(m);
  EXPECT_EQ(out.state, MissionState::departed);
  EXPECT_TRUE(logged("undock>departed:clear of the station, marker in view"));
  EXPECT_FALSE(out.thrusters_enabled);  // departed_action neutral
  EXPECT_TRUE(m.finished());
}

TEST_F(RechargeMissionTest, ATaperedChargeCurrentCompletesButOnlyPastTheTaperSoc) {
  Mission m = make();
  to_charging(m);
  Charge taper;
  taper.soc = params.recharge.complete_min_soc_fraction + 0.01;
  taper.current_a = params.recharge.complete_current_a * 0.5;
  EXPECT_EQ(tick(m, taper).state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:charge complete (current)"));
  EXPECT_TRUE(m.charge_complete());
}

TEST_F(RechargeMissionTest, UndockBacksOutAlongTheAxisAndPushesBackBlind) {
  Mission m = make();
  to_charging(m);
  Charge op;
  op.undock = true;
  MissionOutput out = tick(m, op);
  ASSERT_EQ(out.state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:operator command"));
  EXPECT_FALSE(m.charge_complete());
  // After 2 s the set-point is undock_speed * 2 s further back along the docking axis.
  out = ticks(m, Charge{}, 2s);
  const double back = (out.T_cl_marker_desired.translation() - docked.translation()).norm();
  EXPECT_NEAR(back, -0.02 + params.recharge.undock_speed_mps * 2.0, 0.01);
  Charge blind;
  blind.seen = false;
  out = tick(m, blind);
  EXPECT_FALSE(out.servo_active);
  EXPECT_LT(out.wrench_override_body[0], -0.9 * params.recharge.undock_push_n);
  EXPECT_EQ(back_out(m).state, MissionState::departed);
}

TEST_F(RechargeMissionTest, UnseatedProbeIsReseatedThenUndocksAndAbortsWhenReseatsRunOut) {
  params.recharge.max_reseats = 2;
  Mission m = make();
  to_charging(m);
  Charge lost;
  lost.contact = false;
  for (int k = 1; k <= params.recharge.max_reseats; ++k) {
    // A brief loss is not an unseat.
    EXPECT_EQ(ticks(m, lost, 200ms).state, MissionState::charging);
    MissionOutput out = ticks(m, Charge{}, 100ms);
    MissionOutput dock = ticks(m, lost, 400ms);
    ASSERT_EQ(dock.state, MissionState::dock) << "re-seat " << k;
    EXPECT_EQ(m.reseats(), k);
    // The re-seat docks from where the probe is, not from the stand-off, pressing on.
    EXPECT_LT((dock.T_cl_marker_desired.translation() - docked.translation()).norm(), 0.06);
    EXPECT_GT(dock.push_body[0], 0.0);
    for (int f = 0; f < params.contact_frames; ++f) out = tick(m, Charge{});
    ASSERT_EQ(out.state, MissionState::charging);
  }
  EXPECT_TRUE(logged("charging>dock:probe unseated: re-seat"));
  EXPECT_TRUE(logged("docked>charging:re-seated"));
  MissionOutput out = ticks(m, lost, 400ms);
  ASSERT_EQ(out.state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:probe unseated: re-seats exhausted"));
  out = back_out(m);
  ASSERT_EQ(out.state, MissionState::abort);
  EXPECT_TRUE(logged("undock>abort:undocked after the re-seats ran out"));
  EXPECT_FALSE(m.finished());  // still backing off
  Charge away = lost;
  away.back_m = params.standoff_m;
  out = ticks(m, away,
              std::chrono::milliseconds(static_cast<int>(params.abort_backoff_s * 1000) + 100));
  EXPECT_EQ(out.state, MissionState::abort);  // ends there: no new search
  EXPECT_FALSE(out.thrusters_enabled);
  EXPECT_TRUE(m.finished());
}

TEST_F(RechargeMissionTest, AxialTrimIsKeptAtTheStandOffRestoredOnceSeatedAndHeldWhileCharging) {
  Mission m = make();
  Charge far;
  far.contact = false;
  far.back_m = params.standoff_m;
  int kept = 0;
  MissionOutput out;
  for (int k = 0; k < params.acquire_frames + 1 + params.align_hold_frames; ++k) {
    out = tick(m, far);
    kept += out.keep_axial_trim ? 1 : 0;
    EXPECT_FALSE(out.restore_axial_trim);
    EXPECT_FALSE(out.hold_axial_trim);
  }
  ASSERT_EQ(m.state(), MissionState::dock);
  EXPECT_EQ(kept, 1);  // once, on ALIGN -> DOCK
  EXPECT_TRUE(out.keep_axial_trim);
  int restored = 0;
  for (int k = 0; k < params.contact_frames; ++k) {
    out = tick(m, Charge{});
    restored += out.restore_axial_trim ? 1 : 0;
  }
  ASSERT_EQ(out.state, MissionState::charging);
  EXPECT_EQ(restored, 1);  // on the first CHARGING tick
  EXPECT_TRUE(out.restore_axial_trim);
  EXPECT_TRUE(out.hold_axial_trim);
  out = ticks(m, Charge{}, 1s);
  EXPECT_FALSE(out.restore_axial_trim);
  EXPECT_TRUE(out.hold_axial_trim);
  // A re-seat keeps the trim its DOCK learnt: no restore when CHARGING resumes.
  Charge lost;
  lost.contact = false;
  ASSERT_EQ(ticks(m, lost, 400ms).state, MissionState::dock);
  EXPECT_FALSE(out.keep_axial_trim);
  restored = 0;
  for (int k = 0; k < params.contact_frames; ++k) {
    out = tick(m, Charge{});
    restored += out.restore_axial_trim ? 1 : 0;
  }
  ASSERT_EQ(out.state, MissionState::charging);
  EXPECT_EQ(restored, 0);
}

TEST_F(RechargeMissionTest, FailsafeAtTheStationUndocksWithTheReasonLoggedAndBacksOutAlongTheAxis) {
  Mission m = make();
  EXPECT_FALSE(m.at_station());
  m.failsafe_undock(now, "failsafe: backing out of the socket");  // not at the station: nothing
  EXPECT_EQ(m.state(), MissionState::search);
  to_charging(m);
  EXPECT_TRUE(m.at_station());
  m.failsafe_undock(now, "failsafe: backing out of the socket");
  EXPECT_EQ(m.state(), MissionState::undock);
  tick(m, Charge{});
  EXPECT_TRUE(logged("charging>undock:failsafe: backing out of the socket"));
  EXPECT_TRUE(m.at_station());
  // Out of the socket: backwards along the docking axis (body -x when docked).
  const Wrench w = m.back_out_wrench_body();
  EXPECT_NEAR(w[0], -params.recharge.undock_push_n, 1e-6);
  EXPECT_NEAR(w.tail<5>().norm(), 0.0, 1e-6);
}

TEST_F(RechargeMissionTest, VisionSeeingTheProbeOutOfTheSocketIsAnUnseat) {
  Mission m = make();
  to_charging(m);
  Charge slipped;  // the contact still claims seated, vision sees the probe 3 cm out
  slipped.back_m = params.recharge.vision_unseat_m + 0.02;
  ticks(m, slipped, 400ms);
  EXPECT_TRUE(logged("charging>dock:probe unseated: re-seat"));
  EXPECT_EQ(m.reseats(), 1);
}

// The tide turning the current onto the axis pushes the probe back out of the seat, where no
// integral sees it (the axial error is nil): the push grows while it slips, shrinks once seated.
TEST_F(RechargeMissionTest, ThePushGrowsWhileTheProbeSlipsOutAndShrinksOnceSeated) {
  Mission m = make();
  to_charging(m);
  const RechargeParams& r = params.recharge;
  MissionOutput out = ticks(m, Charge{}, 2s);
  EXPECT_NEAR(out.push_body[0], r.charge_push_n, 1e-6);
  // Seen short of the contact depth, still short of an unseat: the push rises at the rise rate.
  Charge slipping;
  slipping.back_m = -0.5 * params.vision_contact_depth_m;
  ASSERT_LT(0.5 * params.vision_contact_depth_m, r.vision_unseat_m + params.vision_contact_depth_m);
  out = ticks(m, slipping, 1s);
  EXPECT_EQ(out.state, MissionState::charging);
  // The seen depth is low-passed over a tenth of a second: the rise starts a few ticks late.
  const double grown_n = out.push_body[0] - r.charge_push_n;
  EXPECT_GT(grown_n, r.seat_trim_rise_nps * 0.85);
  EXPECT_LE(grown_n, r.seat_trim_rise_nps * 1.0 + 1e-9);
  // Seated again, the push holds what it learnt, giving it back slowly (after the filter's lag).
  Charge seated;
  out = ticks(m, seated, 2s);
  EXPECT_NEAR(out.push_body[0] - r.charge_push_n, grown_n - 2.0 * r.seat_trim_decay_nps,
              0.15 * r.seat_trim_rise_nps);
  EXPECT_GT(out.push_body[0], r.charge_push_n);
  // The seat contact lost says the same as vision, even where vision does not see it.
  Charge lifted;
  lifted.contact = false;
  const double before_n = out.push_body[0];
  out = ticks(m, lifted, 198ms);  // under unseat_confirm_s: no re-seat yet
  ASSERT_EQ(out.state, MissionState::charging);
  EXPECT_GT(out.push_body[0], before_n + 0.5 * r.seat_trim_rise_nps * 0.198);
  // Never past the overload: the hold gives way to UNDOCK there.
  out = ticks(m, slipping, 60s);
  EXPECT_LE(out.push_body[0], r.overload_force_n + 1e-9);
}

// Told where the socket's bottom is, the hold sees the probe slip while the pins still touch: a
// few millimetres out of the bottom, long before the contact depth.
TEST_F(RechargeMissionTest, ThePushGrowsWhenSeenShortOfTheSocketBottom) {
  const double bottom_m = 0.02;
  Mission m(params, T_body_cl, docked, geometry.probe_tip_body_m, bottom_m);
  to_charging(m);
  const RechargeParams& r = params.recharge;
  ASSERT_GT(bottom_m - 2.0 * r.seat_slip_m, params.vision_contact_depth_m);
  Charge pressed;
  pressed.back_m = -bottom_m;
  MissionOutput out = ticks(m, pressed, 2s);
  EXPECT_NEAR(out.push_body[0], r.charge_push_n, 1e-6);
  Charge within;  // inside the slip margin: seated
  within.back_m = -(bottom_m - 0.5 * r.seat_slip_m);
  out = ticks(m, within, 1s);
  EXPECT_NEAR(out.push_body[0], r.charge_push_n, 1e-6);
  Charge drawn_out;  // past it, the pins still closed
  drawn_out.back_m = -(bottom_m - 2.0 * r.seat_slip_m);
  out = ticks(m, drawn_out, 1s);
  EXPECT_EQ(out.state, MissionState::charging);
  EXPECT_GT(out.push_body[0] - r.charge_push_n, 0.85 * r.seat_trim_rise_nps);
  // The mission without the station's depth judges only by the contact depth: no growth there.
  Mission blind_to_bottom = make();
  to_charging(blind_to_bottom);
  out = ticks(blind_to_bottom, drawn_out, 1s);
  EXPECT_NEAR(out.push_body[0], r.charge_push_n, 1e-6);
}

TEST_F(RechargeMissionTest, CurrentBeyondTheHoldUndocksAndDeparts) {
  Mission m = make();
  to_charging(m);
  Charge gust;
  gust.hold_force_n = params.recharge.overload_force_n + 5.0;
  EXPECT_EQ(ticks(m, gust, 1s).state, MissionState::charging);  // a gust, not yet overload
  EXPECT_EQ(ticks(m, gust, 1500ms).state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:current beyond what the hold resists"));
  EXPECT_EQ(back_out(m).state, MissionState::departed);
  EXPECT_TRUE(m.finished());
}

TEST_F(RechargeMissionTest, ACrossCurrentTurningTheVehicleAboutItsProbeUndocks) {
  Mission m = make();
  to_charging(m);
  Charge gust;  // a gust turns it half-way, briefly: held
  gust.yaw_rad = params.recharge.overload_yaw_rad * 0.5;
  EXPECT_EQ(ticks(m, gust, 3s).state, MissionState::charging);
  Charge swing;
  swing.yaw_rad = params.recharge.overload_yaw_rad + 0.02;
  EXPECT_EQ(ticks(m, swing, 300ms).state, MissionState::charging);
  EXPECT_EQ(ticks(m, Charge{}, 100ms).state, MissionState::charging);  // back: the timer restarts
  EXPECT_EQ(ticks(m, swing, 300ms).state, MissionState::charging);
  EXPECT_EQ(ticks(m, swing, 300ms).state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:current beyond what the hold resists"));
  EXPECT_EQ(m.reseats(), 0);
}

TEST_F(RechargeMissionTest, ChargerWithNoCurrentUndocksWithTheCauseLogged) {
  Mission m = make();
  to_charging(m);
  Charge dead;
  dead.current_a = 0.0;
  EXPECT_EQ(ticks(m, dead, 2s).state, MissionState::charging);
  EXPECT_EQ(ticks(m, dead, 1500ms).state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:charger reports no current"));
  EXPECT_FALSE(m.charge_complete());
  EXPECT_EQ(back_out(m).state, MissionState::departed);
}

TEST_F(RechargeMissionTest, TimeLimitEndsTheCharge) {
  params.recharge.charge_timeout_s = 5.0;
  Mission m = make();
  to_charging(m);
  EXPECT_EQ(ticks(m, Charge{}, 4s).state, MissionState::charging);
  EXPECT_EQ(ticks(m, Charge{}, 2s).state, MissionState::undock);
  EXPECT_TRUE(logged("charging>undock:charge time limit"));
}

TEST_F(RechargeMissionTest, UndockThatNeverSeesTheStandOffFails) {
  params.recharge.undock_timeout_s = 3.0;
  Mission m = make();
  to_charging(m);
  Charge op;
  op.undock = true;
  tick(m, op);
  Charge stuck;
  stuck.contact = false;
  EXPECT_EQ(ticks(m, stuck, 4s).state, MissionState::failed);
  EXPECT_TRUE(logged("undock>failed:undock timed out"));
  EXPECT_TRUE(m.finished());
}

TEST_F(RechargeMissionTest, DepartedCanHoldTheStandOff) {
  params.recharge.departed_action = "hold";
  Mission m = make();
  to_charging(m);
  Charge op;
  op.undock = true;
  tick(m, op);
  const MissionOutput out = back_out(m);
  ASSERT_EQ(out.state, MissionState::departed);
  EXPECT_TRUE(out.thrusters_enabled);
  EXPECT_TRUE(out.servo_active);
  EXPECT_TRUE(out.T_cl_marker_desired.isApprox(m.standoff_T_cl_marker()));
}

TEST_F(RechargeMissionTest, TheDockingMissionStillEndsAtDocked) {
  params.kind = "dock";
  Mission m = make();
  Charge far;
  far.contact = false;
  far.back_m = params.standoff_m;
  for (int k = 0; k < params.acquire_frames + 1 + params.align_hold_frames; ++k) tick(m, far);
  for (int k = 0; k < params.contact_frames; ++k) tick(m, Charge{});
  EXPECT_EQ(m.state(), MissionState::docked);
  EXPECT_TRUE(m.finished());
  EXPECT_FALSE(tick(m, Charge{}).thrusters_enabled);
}

}  // namespace
}  // namespace rovctl::control
