// The docking mission: SEARCH -> APPROACH -> ALIGN -> DOCK -> DOCKED, with ABORT (back off, search
// again, a bounded number of times) and FAILED; the recharging mission goes on from DOCKED to
// CHARGING (hold seated) -> UNDOCK -> DEPARTED. Decides what the servo aims at and when the
// thrusters may push; every transition is queued as an event. The tick allocates nothing.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <chrono>
#include <cstddef>

#include "control/control_params.hpp"
#include "control/thruster_effectiveness.hpp"

namespace rovctl::control {

// Appended states keep the ids telemetry has always recorded.
enum class MissionState {
  search,
  approach,
  align,
  dock,
  docked,
  abort,
  failed,
  charging,
  undock,
  departed
};
constexpr int kMissionStateCount = 10;
const char* to_string(MissionState s);

struct MissionInput {
  std::chrono::nanoseconds now{0};
  bool recognised = false;  // the estimator's verdict
  // Every sphere supported in both views (the estimator's ok). A partial view is enough to
  // search and approach on; aligning for the dock and docking itself need the full view (inside
  // the blind zone at the end of the push a partial view is all there is).
  bool full_view = false;
  double fitness = 0.0;  // the estimate's fitness (also gated by min_fitness)
  // T_cl_marker is the pose tracked across frames (PoseTracker), within the estimator's ok limits
  // by its own bound: a full view, seen whatever this frame's estimate and fitness.
  bool tracked = false;
  // On a partial view: T_cl_marker's rotation is the attitude sensor's since the last full view
  // (AttitudeAidedPose), so DOCK may steer on it while its push waits.
  bool attitude_aided = false;
  Eigen::Isometry3d T_cl_marker = Eigen::Isometry3d::Identity();
  bool contact = false;  // contact switch if the vehicle has one; the sim reports it
  // The recharging mission's inputs: battery and charger (from hal::Sensors), the horizontal
  // force the hold commanded last tick, and the operator's request to end the charge.
  bool charger_valid = false;
  double charge_current_a = 0.0;
  bool battery_valid = false;
  double soc_fraction = 0.0;
  double hold_force_n = 0.0;
  bool undock_requested = false;
  // The servo's estimate of the current's push (DisturbanceEstimate): settled (ALIGN's hold
  // counts only settled frames), at its limit now, and beyond what the thrusters may hold.
  bool disturbance_settled = true;
  bool disturbance_at_limit = false;
  bool disturbance_rising = false;  // still growing toward the push
  bool current_beyond_hold = false;
};

// The application's contract: thrusters_enabled false -> neutral. Else if servo_active:
// servo_restart -> PdVisualServo::restart(), then the wrench is the servo's, aimed at
// T_cl_marker_desired. Else if use_override: wrench_override_body plus the servo's
// hold_wrench_body() (feed-forward and integral: the trim against buoyancy and current).
// The servo need not be reset after a brief loss (it restarts its derivative after a gap).
struct MissionOutput {
  MissionState state = MissionState::search;
  bool servo_active = false;
  // The servo takes over this tick (PdVisualServo::restart: the derivative afresh, the current's
  // estimate kept).
  bool servo_restart = false;
  Eigen::Isometry3d T_cl_marker_desired = Eigen::Isometry3d::Identity();
  Wrench wrench_override_body = Wrench::Zero();
  bool use_override = false;
  // Added to the wrench whenever the thrusters are enabled (the seated hold's push).
  Wrench push_body = Wrench::Zero();
  bool thrusters_enabled = true;
  // > 0: the servo turns only as far as keeps the marker within this bearing of the camera's
  // axis (PdVisualServo::keep_in_view); 0: no limit.
  double max_bearing_rad = 0.0;
  // The servo's integral along body x, the docking axis once aligned: the axial trim against the
  // current. keep_axial_trim: remember it now (ALIGN -> DOCK: it has just held the vehicle still
  // at the stand-off, so it is the current's drag along the axis). restore_axial_trim: set it
  // back to what was kept (the first CHARGING tick: DOCK winds it up while its set-point runs past
  // the socket bottom the probe cannot pass, and the hold would press that into the station for
  // the whole charge: in the 0.14 m/s head-on trial 7 N of trim against 4 N of drag).
  // hold_axial_trim: do not integrate it (CHARGING: the set-point follows the probe, so the axial
  // error left is the estimate's bias, not a disturbance; the push is the hold's margin).
  bool keep_axial_trim = false;
  bool restore_axial_trim = false;
  bool hold_axial_trim = false;
  // The control point's error against the docking axis, when the marker is seen this tick:
  // lateral = off the axis, axial = along it (negative: short of the docked position), yaw of
  // the docking axis in body x-y.
  bool errors_valid = false;
  double lateral_error_m = 0.0;
  double axial_error_m = 0.0;
  double yaw_error_rad = 0.0;
};

struct MissionEvent {
  std::chrono::nanoseconds time{0};
  MissionState from = MissionState::search;
  MissionState to = MissionState::search;
  const char* reason = "";  // static string
  int aborts = 0;
};

// The desired T_cl_marker with the vehicle moved back by `back_m` along the docking axis
// (marker +z) from `T_cl_marker_docked`; negative values go past it, into the station.
Eigen::Isometry3d offset_along_docking_axis(const Eigen::Isometry3d& T_cl_marker_docked,
                                            double back_m);

class Mission {
 public:
  static constexpr std::size_t kEventCapacity = 32;

  // control_point_body_m: the body point that must meet the socket (the probe tip); lateral and
  // axial errors are measured there. The docked pose comes from hal::docked_T_cl_marker().
  // seat_depth_m: how far past the socket mouth the seated probe sits (the socket's bottom,
  // hal::DockingStation::capture_depth_m); 0 when not known.
  Mission(const MissionParams& params, const Eigen::Isometry3d& T_body_cl,
          const Eigen::Isometry3d& T_cl_marker_docked,
          const Eigen::Vector3d& control_point_body_m = Eigen::Vector3d::Zero(),
          double seat_depth_m = 0.0);

  // One tick. `in.now` must not go backwards. No allocation.
  MissionOutput update(const MissionInput& in);

  // Back to SEARCH with no aborts counted (a new mission, or one resumed after a failsafe);
  // logged with `reason` (a static string).
  void restart(std::chrono::nanoseconds now, const char* reason = "restart");

  // The probe is in or at the socket: CHARGING, a re-seat's DOCK, UNDOCK.
  bool at_station() const;
  // A failsafe tripped at the station and the vehicle backs out (Failsafe, SafeAction::back_out):
  // UNDOCK with `reason` (a static string) logged, unless already undocking. No allocation.
  void failsafe_undock(std::chrono::nanoseconds now, const char* reason);
  // The failsafe's back-out: open-loop push out of the socket along the docking axis as it lay
  // when docked (mission.recharge.undock_push_n).
  Wrench back_out_wrench_body() const;

  MissionState state() const { return state_; }
  // Nothing more will happen: DOCKED (docking mission), DEPARTED, FAILED, or the final ABORT of
  // a recharge given up after its re-seats.
  bool finished() const;
  int aborts() const { return aborts_; }
  // FAILED because SEARCH ran out of time (the failsafe's search_time rather than mission_failed).
  bool search_timed_out() const { return search_timed_out_; }
  int reseats() const { return reseats_; }
  bool charge_complete() const { return charge_complete_; }
  const Eigen::Isometry3d& standoff_T_cl_marker() const { return T_standoff_; }
  const Eigen::Isometry3d& docked_T_cl_marker() const { return T_docked_; }

  // Oldest queued transition; false when none. The queue keeps the newest kEventCapacity
  // events; dropped_events() counts those overwritten.
  bool pop_event(MissionEvent& event);
  std::size_t dropped_events() const { return dropped_; }

 private:
  struct Errors {
    double lateral_m, axial_m, yaw_rad;
    double lateral_x_m, lateral_y_m;  // the lateral error's components in the marker frame
  };
  // What this tick's input says, worked out once for the transitions and the outputs.
  struct Sight {
    const MissionInput& in;
    bool seen = false;        // recognised, fit enough, finite
    bool full = false;        // ... on the full view
    bool blind_zone = false;  // the probe is within dock_blind_distance_m of the socket
    bool seen_dock = false;   // seen well enough to push the dock on
    bool steer_dock = false;  // ... and to steer it
    bool contact_switch = false;
    bool waiting_for_full_view = false;
    bool lost = false;                 // unseen for lost_frames
    double t_state = 0.0;              // s in the current state
    std::chrono::nanoseconds tick{0};  // since the last update
    Errors err{0.0, 0.0, 0.0, 0.0, 0.0};
  };
  Errors errors(const Eigen::Isometry3d& T_cl_marker) const;
  Sight observe(const MissionInput& in);
  // One transition function per state (mission_state_table() says what each does), then the
  // outputs of the state the tick ends in.
  void transition(const Sight& s);
  void from_search(const Sight& s);
  void from_approach(const Sight& s);
  void from_align(const Sight& s);
  void from_dock(const Sight& s);
  void from_docked(const Sight& s);
  void from_abort(const Sight& s);
  void from_charging(const Sight& s);
  void from_undock(const Sight& s);
  MissionOutput outputs(const Sight& s);
  static void servo_when(bool in_view, MissionOutput& out);
  void search_outputs(const Sight& s, MissionOutput& out) const;
  void dock_outputs(const Sight& s, MissionOutput& out);
  // The push along the docked axis into the seat: the charge push plus the seat trim, updated.
  void press_seat(const Sight& s, MissionOutput& out);
  void undock_outputs(const Sight& s, MissionOutput& out) const;
  void enter(MissionState to, std::chrono::nanoseconds now, const char* reason);
  // APPROACH or ALIGN lost the marker: an abort that searches at once, without backing off;
  // lost while the current's estimate was at its limit, or for the
  // mission.beyond_hold_losses-th time while it was still rising toward the push, the current
  // swept it away: FAILED.
  void lost_before_dock(const Sight& s);
  // The current pushes harder than the thrusters may hold: no retry can succeed, so FAILED
  // (thrusters neutral) rather than an abort that would search and approach again.
  bool beyond_hold(const Sight& s);
  void start_undock(std::chrono::nanoseconds now, const char* reason);
  void push_event(const MissionEvent& e);

  MissionParams p_;
  Eigen::Isometry3d T_body_cl_;
  Eigen::Isometry3d T_docked_;
  Eigen::Isometry3d T_standoff_;
  Eigen::Vector3d control_point_body_m_;
  Eigen::Vector3d cp_docked_marker_m_;  // the control point in the marker frame when docked

  MissionState state_ = MissionState::search;
  std::chrono::nanoseconds entered_{0};
  bool started_ = false;
  bool servo_was_active_ = false;
  int aborts_ = 0;
  // Markers lost in APPROACH or ALIGN while the current's estimate was still rising toward the
  // push, since it last settled with the marker in view.
  int swept_losses_ = 0;
  int seen_frames_ = 0;
  int unseen_frames_ = 0;
  int partial_frames_ = 0;  // consecutive frames recognised on a partial view
  int hold_frames_ = 0;
  // ALIGN's average of the signed errors (lateral x, y, axial from the stand-off, yaw).
  Eigen::Vector4d align_avg_ = Eigen::Vector4d::Zero();
  bool align_avg_valid_ = false;
  int contact_frames_ = 0;
  int dock_off_frames_ = 0;  // consecutive seen frames past the dock abort limits
  bool have_last_ = false;
  double last_axial_m_ = 0.0;
  Eigen::Vector3d docked_axis_body_ = Eigen::Vector3d::UnitX();  // docking axis when docked
  std::chrono::nanoseconds blind_since_{-1};
  // DOCK's push runs on the full view only: the time it has run, and since when the view is
  // partial (a passing bar, a bubble on a sphere) while the push waits.
  std::chrono::nanoseconds dock_pushed_{0};
  // The full view's lateral error (marker-frame x, y), low-passed for the wait.
  double dock_lateral_lp_x_m_ = 0.0, dock_lateral_lp_y_m_ = 0.0;
  bool dock_lateral_lp_valid_ = false;
  std::chrono::nanoseconds partial_since_{-1};
  std::chrono::nanoseconds last_now_{-1};
  // Recharging.
  bool recharge_ = false;
  bool charging_started_ = false;
  bool charge_complete_ = false;
  bool abort_after_undock_ = false;  // re-seats exhausted: UNDOCK ends in the final ABORT
  bool final_abort_ = false;
  bool search_timed_out_ = false;
  bool backed_off_ = false;  // ABORT's back-off time is over
  bool back_off_ = true;     // this ABORT backs off (not one for a marker lost at the stand-off)
  bool departed_hold_ = false;
  bool keep_axial_trim_ = false;     // the next output asks to keep the axial trim
  bool restore_axial_trim_ = false;  // ... to restore it
  int reseats_ = 0;
  // Seen this short of the socket mouth (low-passed) in the seat, the probe is slipping out.
  double slip_depth_m_ = 0.0;
  double seat_depth_seen_m_ = 0.0;  // the seated depth seen, low-passed
  bool seat_depth_seen_valid_ = false;
  double seat_trim_n_ = 0.0;          // the push CHARGING adds against the current's axial part
  double dock_start_back_m_ = 0.0;    // DOCK's set-point starts this far back (re-seat: from here)
  double undock_start_back_m_ = 0.0;  // UNDOCK's set-point starts here
  std::chrono::nanoseconds charging_since_{0};  // the first CHARGING entry (the time limit)
  std::chrono::nanoseconds unseated_since_{-1};
  std::chrono::nanoseconds no_current_since_{-1};
  std::chrono::nanoseconds overload_since_{-1};
  std::chrono::nanoseconds swing_since_{-1};

  std::array<MissionEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace rovctl::control
