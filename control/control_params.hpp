// The `control` and `mission` config sections: servo gains, rate filter, allocation weights,
// failsafe limits and the docking mission's thresholds, each declared once by describe().
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "control/failsafe_policy.hpp"
#include "control/pose_tracker.hpp"
#include "hal/primitives/parameters.hpp"

namespace rovctl::control {

// The servo's integral term as an estimate of the current's push (DisturbanceEstimate): how much
// of the thrusters it may take, when it counts as settled, and when the current is beyond hold.
struct DisturbanceParams {
  // Share of the thrusters' force (or moment) along each axis the estimate may take; the rest is
  // left to the servo's P and D terms.
  double hold_fraction = 0.7;
  // Settled: the horizontal force, low-passed twice at rate_cutoff_hz, changes slower than
  // settle_rate_nps for settle_s. ALIGN's hold counts only settled frames.
  double settle_rate_nps = 0.5;
  double settle_s = 1.5;
  double rate_cutoff_hz = 0.5;
  // Beyond hold: a horizontal axis at its limit, or the thrusters saturated, for this long.
  double beyond_hold_s = 4.0;
  // A marker lost while the estimate is still rising counts toward mission.beyond_hold_losses
  // once the estimate has reached this share of its limit.
  double swept_fraction = 0.3;
};

void describe(hal::ParamVisitor& v, DisturbanceParams& p);

// The PD(+I) visual servo. Linear gains act on the position error in body axes (x fwd, y stbd,
// z down), angular gains on the rotation error (roll, pitch, yaw about body x, y, z).
struct ServoParams {
  // false: x, y, z and yaw are servoed; roll and pitch (passively stable on a BlueROV2) only get
  // their derivative (damping) term. true: all six axes.
  bool six_dof = false;
  Eigen::Vector3d kp_linear{80.0, 90.0, 90.0};  // N/m
  // Heave: 70 limit-cycled at 1 Hz (+-0.1 m, +-50 N) holding the stand-off in a 0.25 m/s current.
  Eigen::Vector3d kd_linear{60.0, 60.0, 40.0};  // N s/m
  Eigen::Vector3d ki_linear{20.0, 30.0, 30.0};  // N/(m s)
  // Yaw: the camera latency, the frame period and the thrusters' lag add up to ~0.15 s, so the
  // yaw loop must cross over near 3 rad/s (kp 8 / kd 3 limit-cycled at +-0.03 rad, 0.8 Hz).
  Eigen::Vector3d kp_angular{4.0, 4.0, 2.0};  // N m/rad
  Eigen::Vector3d kd_angular{1.0, 1.0, 2.0};  // N m s/rad
  Eigen::Vector3d ki_angular{0.0, 0.0, 0.3};  // N m/(rad s)
  // Anti-windup: the integral term's magnitude per axis never exceeds these.
  Eigen::Vector3d integral_limit_linear_n{60.0, 60.0, 20.0};
  Eigen::Vector3d integral_limit_angular_nm{1.0, 1.0, 1.0};
  // The proportional and integral terms see the error clipped to these norms, which bounds the
  // approach speed (about kp * max / kd) so the estimator can keep the marker tracked.
  double max_position_error_m = 0.2;
  double max_angle_error_rad = 0.6;
  // First-order low-pass on the differentiated error.
  double rate_cutoff_hz = 3.0;
  // If positive, the differentiated error is clamped to these rates before the low-pass, so a
  // single outlier estimate cannot pass as a velocity (a 0.3 m jump read as 9 m/s, a 242 N
  // kick). 0: no clamp. Without IMU levelling a 0.8 m/s clamp lifted docking from 88 to 93 of
  // 100 trials; with levelling it is not needed, and at 2.5 m it cuts into the real error rate
  // a turn makes (range x yaw rate), so it is off by default.
  double max_rate_linear_mps = 0.0;
  double max_rate_angular_radps = 0.0;
  // A gap longer than this between updates restarts the derivative (no kick from stale data).
  double max_update_gap_s = 0.25;
  // Buoyancy minus weight; the feed-forward pushes down (body +z) by this much.
  double net_buoyancy_n = 2.0;
  DisturbanceParams disturbance;
};

void describe(hal::ParamVisitor& v, ServoParams& p);

struct ThrusterWeight {
  std::string thruster;  // a name from vehicle.thrusters
  double weight = 1.0;
};

// Weighted pseudo-inverse: thruster weights price each thruster's effort (higher = used less);
// axis weights rank the wrench axes when the layout cannot produce all of them.
struct AllocationParams {
  std::vector<ThrusterWeight> thruster_weights;  // thrusters not listed weigh 1
  Eigen::Vector3d axis_weights_force{1.0, 1.0, 1.0};
  Eigen::Vector3d axis_weights_moment{1.0, 1.0, 1.0};
  // The ESCs' deadband as a command fraction (Blue Robotics Basic ESC: 25 of 400 us); commands
  // skip it so that small forces are not lost. 0 when the bus already compensates.
  double deadband = 0.0625;
};

void describe(hal::ParamVisitor& v, AllocationParams& p);

struct FailsafeParams {
  // Consecutive camera timeouts tolerated (vision lost; a lost device trips at once). One: a
  // single dropped frame passes, two in a row (66 ms without a picture) trip.
  int camera_timeout_ticks = 1;
  // Consecutive degraded bus writes tolerated (bus slow; a faulted bus trips at once).
  // 0: the first degraded report trips. A real bus says degraded only once its heartbeat gap is
  // past timing.degraded_ms (3 ticks): a further streak would only trip it after the watchdog.
  int bus_degraded_ticks = 0;
  // Longest a mission may run, CHARGING not counted, before the vehicle is made safe. The sim's
  // dockings take 15-40 s and give up by 150 s; a recharge's undock adds 30 s.
  double max_mission_time_s = 900.0;
  // "disarm": disarm the bus (ESCs neutral, vehicle floats up); "neutral": armed, zero thrust.
  // The action of every cause whose policy says "default".
  std::string action = "disarm";
  // A trip with the probe in the socket (charging, re-seating, undocking) whose thrusters still
  // obey backs out along the docking axis this long first (mission.recharge.undock_push_n, open
  // loop): a disarmed vehicle would hang on its probe in the current, pivot about it and grind the
  // socket. At the push's ~0.2 m/s, 4 s clears the 0.5 m stand-off. 0: go safe at once.
  double backout_s = 4.0;
  // Vision: identical images (a hash of a subsample) this many ticks in a row; the newest frame
  // older than stale_ms (the mock camera's latency is 40 ms, a USB camera's 50-100 ms); left and
  // right captured further apart than stereo_skew_ms (a third of a frame at 30 fps); an image
  // whose subsample spans no more than dead_range_levels grey levels (black or covered).
  int frozen_ticks = 2;
  double stale_ms = 250.0;
  double stereo_skew_ms = 10.0;
  int dead_range_levels = 3;
  // Sensors: lost for this many ticks in a row; implausible outside these bounds; the attitude
  // limit on roll and pitch (the cameras lose the marker well before 35 deg).
  int sensor_lost_ticks = 2;
  double min_depth_m = -5.0;
  double max_depth_m = 500.0;
  double max_rate_radps = 10.0;
  double min_soc_fraction = 0.05;  // battery below this trips battery_low
  double attitude_limit_rad = 0.6;
  // Consecutive overrun ticks (the tick ran past the next release).
  int overrun_ticks = 2;
  // Recovery of an "auto" cause: gone for recover_ticks in a row; a trip that has not recovered
  // within recover_within_s latches.
  int recover_ticks = 10;
  double recover_within_s = 30.0;
  FailsafePolicy policy;
};

void describe(hal::ParamVisitor& v, FailsafeParams& p);

// Roll and pitch held level from the IMU (ArduSub's STABILIZE does the same under every mode):
// the visual servo leaves them to passive stability, which on a BlueROV2 (centre of buoyancy
// ~1 cm above gravity's) lets thrust and current tip the cameras off the marker by 15-20 deg.
// Used when the servo is not six_dof and the sensors report a valid attitude.
// Stiff enough that a heave drives no pitch the servo could see: in a 0.25 m/s head current the
// added mass's Munk moment turns heave speed into pitch, which the camera reads as the marker
// moving vertically; at 6 N m/rad that loop held a +-3 cm heave limit cycle through ALIGN. Not
// stiffer: at 20 N m/rad the levelling's own jitter took docking's lateral error p95 from 4 to 5.5
// mm.
struct AttitudeParams {
  bool enabled = true;
  double roll_kp_nm_per_rad = 12.0;
  double roll_kd_nms_per_rad = 3.0;
  double pitch_kp_nm_per_rad = 12.0;
  double pitch_kd_nms_per_rad = 3.0;
  double max_moment_nm = 12.0;  // per axis
};

void describe(hal::ParamVisitor& v, AttitudeParams& p);

// Thruster health from the ESCs' telemetry (ThrusterHealth): a thruster whose ESC flags a fault,
// or whose rpm does not follow its command, for long enough is failed and leaves the allocation.
struct ThrusterHealthParams {
  bool enabled = true;
  // rpm at full thrust (T200 at 16 V); the expected rpm grows with the square root of the thrust.
  double full_thrust_rpm = 3800.0;
  // The expected thrust follows the command with the motors' spin-up lag.
  double time_constant_s = 0.10;
  // Below this expected rpm the ratio tests say nothing (deadband, sign changes); a thruster
  // turning faster than stuck_idle_rpm there does not follow its command.
  double min_expected_rpm = 800.0;
  double stuck_idle_rpm = 1200.0;
  // rpm / expected rpm: below dead_rpm_ratio the thruster is dead, below weak_rpm_ratio weak,
  // above overspeed_rpm_ratio (or the wrong sign) stuck. A weak thruster at 30 % of its thrust
  // turns at sqrt(0.3) = 55 % of its rpm.
  double dead_rpm_ratio = 0.15;
  double weak_rpm_ratio = 0.7;
  double overspeed_rpm_ratio = 1.6;
  // Consecutive ticks a symptom must last: a fault flag, an rpm mismatch.
  int fault_flag_ticks = 2;
  int mismatch_ticks = 10;
};

void describe(hal::ParamVisitor& v, ThrusterHealthParams& p);

struct ControlParams {
  ServoParams servo;
  AttitudeParams attitude;
  AllocationParams allocation;
  FailsafeParams failsafe;
  ThrusterHealthParams thruster_health;
  PoseTrackerParams tracker;
};

void describe(hal::ParamVisitor& v, PoseTrackerParams& p);
void describe(hal::ParamVisitor& v, ControlParams& p);

// The recharging mission after DOCKED: hold seated while charging, then back out and hand over.
// Axial errors are those of the probe tip along the docking axis against the docked pose (the
// probe at the socket mouth; negative: short of it).
struct RechargeParams {
  // CHARGING: push along the docking axis (feed-forward) while the servo holds lateral and yaw.
  double charge_push_n = 3.0;
  // Pressed on the socket's bottom the axial error is nil, so no integral learns the current's
  // axial part while the tide turns it; the seat trim does: it adds to the push at
  // seat_trim_rise_nps while the probe slips (the seat contact lost, or vision seeing the probe
  // seat_slip_m short of the socket's bottom, station.capture_depth_m), and gives it back at
  // seat_trim_decay_nps once seated. Not against the deepest seat seen: the seat is compliant, so
  // a harder push sits deeper, and that reference ratcheted the push up to the overload limit
  // after one knock.
  double seat_trim_rise_nps = 5.0;
  double seat_trim_decay_nps = 0.1;
  double seat_slip_m = 0.0025;
  // Charge complete: SoC at or above soc_complete_fraction, or the charge current below
  // complete_current_a once the SoC is past complete_min_soc_fraction (the charger's taper).
  double soc_complete_fraction = 0.95;
  double complete_current_a = 1.0;
  double complete_min_soc_fraction = 0.85;
  double charge_timeout_s = 14400.0;  // CHARGING time limit, then UNDOCK
  // Unseated: the seat contact lost, or vision seeing the probe this far short of the socket
  // mouth, for unseat_confirm_s -> DOCK again (a re-seat) up to max_reseats times.
  double unseat_confirm_s = 0.3;
  double vision_unseat_m = 0.01;
  int max_reseats = 3;
  // Seated, but the charger's current below no_current_a for no_current_s -> UNDOCK.
  double no_current_a = 0.5;
  double no_current_s = 3.0;
  // The horizontal force the hold commands above overload_force_n for overload_s: the current is
  // beyond what the hold resists -> UNDOCK before being dragged off.
  double overload_force_n = 30.0;
  double overload_s = 2.0;
  // Or the vehicle turning about its pinned probe: the yaw error beyond overload_yaw_rad for
  // overload_yaw_s. The socket holds the probe tip, so a cross-current turns the vehicle about it
  // until the servo's force at that error balances it; the seat is lost at its 10 deg tolerance,
  // at about 16 N of hold force (a 0.5 m/s cross-current in the sim), long before overload_force_n.
  // 0.09 rad is half that tolerance and twice the swing of the worst gust in the recharge trials.
  double overload_yaw_rad = 0.09;
  double overload_yaw_s = 0.5;
  // UNDOCK: the set-point backs out along the docking axis at undock_speed_mps to the stand-off
  // (standoff_m); blind, push back with undock_push_n. Done when the marker is seen there.
  double undock_speed_mps = 0.08;
  double undock_push_n = 10.0;
  double undock_timeout_s = 30.0;
  // DEPARTED: "neutral" (hand the vehicle back with the thrusters off) or "hold" (servo at the
  // stand-off).
  std::string departed_action = "neutral";
};

void describe(hal::ParamVisitor& v, RechargeParams& p);

// The docking mission's thresholds. Lateral and axial errors are those of the vehicle's control
// point (the probe tip) in the marker frame: lateral = off the docking axis, axial = along it.
struct MissionParams {
  // "dock": the mission ends at DOCKED. "recharge": DOCKED goes on to CHARGING, UNDOCK, DEPARTED.
  std::string kind = "dock";
  RechargeParams recharge;
  // Recognition: fitness at or above this counts as seeing the marker.
  double min_fitness = 0.6;
  int acquire_frames = 3;  // consecutive recognised frames to leave SEARCH
  // 1.5 s at 30 Hz: a passing bar or a fish hides the marker that long; the vehicle holds.
  int lost_frames = 45;  // consecutive unrecognised frames that abort APPROACH/ALIGN/DOCK
  // SEARCH: constant yaw moment (sets a slow scan against the yaw drag); its sign is the direction,
  // except while a marker found is confirmed: then the scan turns toward it.
  double search_yaw_moment_nm = 0.6;
  double search_timeout_s = 120.0;  // then the failsafe (search_time)
  // APPROACH: servo to the stand-off pose, this far back from docked along the docking axis.
  double standoff_m = 0.5;
  double approach_lateral_m = 0.05;  // enter ALIGN when within these
  double approach_axial_m = 0.08;
  double approach_yaw_rad = 0.10;
  // APPROACH: the servo turns toward the docking axis's heading only as far as keeps the marker
  // within this bearing of the camera's axis (half the field of view is ~30 deg here). 0: off.
  double approach_view_bearing_rad = 0.26;
  double approach_timeout_s = 90.0;
  // ALIGN: hold the stand-off until the error stays within these for hold_frames frames.
  double align_lateral_m = 0.008;
  double align_axial_m = 0.03;
  double align_yaw_rad = 0.04;
  int align_hold_frames = 20;
  double align_average_frames = 10.0;  // the hold judges errors averaged over about this many
  double align_timeout_s = 60.0;
  // DOCK: the set-point advances along the docking axis at this speed to this far past the
  // socket mouth; the dock aborts when the error leaves these limits.
  double dock_speed_mps = 0.06;
  double dock_overshoot_m = 0.05;
  double dock_abort_lateral_m = 0.03;
  double dock_abort_yaw_rad = 0.10;
  // The set-point waits while the probe is seen this far off the axis (a gust that the current's
  // estimate has not caught up with yet), until the servo brings it back: no further in than
  // dock_wait_backoff_m behind the probe, so that the probe stops where the gust found it.
  double dock_wait_lateral_m = 0.006;
  double dock_wait_filter_s = 0.2;
  double dock_wait_backoff_m = 0.01;
  // Consecutive frames beyond those limits before the dock aborts: one outlier estimate (a
  // rotated pose that scores well near the socket) must not throw away a good approach.
  int dock_abort_frames = 3;
  double dock_timeout_s = 40.0;
  double dock_partial_timeout_s = 4.0;  // partial view in DOCK: the push waits this long
  // A partial view's rotation from the attitude sensor, remembered at the last full view, for
  // this long (0: never; the partial pose itself is then not steered on in DOCK).
  double partial_view_attitude_s = 6.0;
  // Near the socket the marker leaves the cameras' view: within this remaining distance a lost
  // marker does not abort, the vehicle pushes along the docking axis for up to blind_timeout_s.
  double dock_blind_distance_m = 0.15;
  double dock_blind_push_n = 8.0;
  double dock_blind_timeout_s = 4.0;
  // Contact: the contact switch, and optionally vision (past the socket mouth by this depth).
  bool contact_switch = true;
  bool contact_from_vision = false;
  double vision_contact_depth_m = 0.01;
  int contact_frames = 2;
  // ABORT: back off along body -x with this force for this long, then SEARCH again.
  double abort_backoff_force_n = 15.0;
  double abort_backoff_s = 3.0;
  int max_retries = 3;  // aborts after which the mission fails
  // Markers lost in APPROACH or ALIGN while the current's estimate was still rising (since it
  // last settled in view) after which the current counts as beyond hold: FAILED.
  int beyond_hold_losses = 2;
};

void describe(hal::ParamVisitor& v, MissionParams& p);

}  // namespace rovctl::control
