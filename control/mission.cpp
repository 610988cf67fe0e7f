// The docking mission's transitions. Counters are in frames (ticks with a fresh estimate),
// timeouts in the input's clock.
#include "control/mission.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "control/pd_visual_servo.hpp"
#include "hal/primitives/duration_seconds.hpp"

namespace rovctl::control {
namespace {

using hal::seconds;

// States in which the servo's integral (the trim against the current) carries over.
bool servo_state(MissionState s) {
  return s == MissionState::approach || s == MissionState::align || s == MissionState::dock ||
         s == MissionState::charging || s == MissionState::undock || s == MissionState::departed;
}

// Starts or clears a condition's timer; true once it has held for `hold_s`.
bool held_for(bool condition, std::chrono::nanoseconds now, std::chrono::nanoseconds& since,
              double hold_s) {
  if (!condition) {
    since = std::chrono::nanoseconds{-1};
    return false;
  }
  if (since.count() < 0) since = now;
  return seconds(now - since) >= hold_s;
}

}  // namespace

const char* to_string(MissionState s) {
  switch (s) {
    case MissionState::search:
      return "search";
    case MissionState::approach:
      return "approach";
    case MissionState::align:
      return "align";
    case MissionState::dock:
      return "dock";
    case MissionState::docked:
      return "docked";
    case MissionState::abort:
      return "abort";
    case MissionState::failed:
      return "failed";
    case MissionState::charging:
      return "charging";
    case MissionState::undock:
      return "undock";
    case MissionState::departed:
      return "departed";
  }
  return "?";
}

Eigen::Isometry3d offset_along_docking_axis(const Eigen::Isometry3d& T_cl_marker_docked,
                                            double back_m) {
  // Moving the camera by -back along marker z is moving the marker by +back along its own z.
  return T_cl_marker_docked * Eigen::Translation3d(0.0, 0.0, back_m);
}

Mission::Mission(const MissionParams& params, const Eigen::Isometry3d& T_body_cl,
                 const Eigen::Isometry3d& T_cl_marker_docked,
                 const Eigen::Vector3d& control_point_body_m, double seat_depth_m)
    : p_(params),
      T_body_cl_(T_body_cl),
      T_docked_(T_cl_marker_docked),
      T_standoff_(offset_along_docking_axis(T_cl_marker_docked, params.standoff_m)),
      control_point_body_m_(control_point_body_m) {
  recharge_ = p_.kind == "recharge";
  departed_hold_ = p_.recharge.departed_action == "hold";
  dock_start_back_m_ = p_.standoff_m;
  slip_depth_m_ = std::max(p_.vision_contact_depth_m, seat_depth_m - p_.recharge.seat_slip_m);
  cp_docked_marker_m_ = (T_body_cl_ * T_docked_).inverse() * control_point_body_m_;
  // Blind, the vehicle pushes along the docking axis as it lies when docked: the servo has just
  // aligned it, and one noisy last estimate would be a worse guess.
  docked_axis_body_ = (T_body_cl_ * T_docked_).linear().col(2);
}

Mission::Errors Mission::errors(const Eigen::Isometry3d& T_cl_marker) const {
  const Eigen::Vector3d cp = (T_body_cl_ * T_cl_marker).inverse() * control_point_body_m_;
  const Eigen::Vector3d d = cp - cp_docked_marker_m_;
  const double yaw = pose_error_body(T_body_cl_, T_cl_marker, T_docked_, false)[5];
  return {d.head<2>().norm(), d.z(), yaw, d.x(), d.y()};
}

void Mission::push_event(const MissionEvent& e) {
  if (event_count_ == kEventCapacity) {
    event_head_ = (event_head_ + 1) % kEventCapacity;  // overwrite the oldest
    --event_count_;
    ++dropped_;
  }
  events_[(event_head_ + event_count_) % kEventCapacity] = e;
  ++event_count_;
}

bool Mission::pop_event(MissionEvent& event) {
  if (event_count_ == 0) return false;
  event = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_count_;
  return true;
}

bool Mission::finished() const {
  switch (state_) {
    case MissionState::docked:
      return !recharge_;
    case MissionState::departed:
    case MissionState::failed:
      return true;
    case MissionState::abort:
      return final_abort_ && backed_off_;
    default:
      return false;
  }
}

void Mission::enter(MissionState to, std::chrono::nanoseconds now, const char* reason) {
  if (to == MissionState::abort && !final_abort_) ++aborts_;
  if (to == MissionState::dock && state_ == MissionState::align) keep_axial_trim_ = true;
  // A re-seat keeps what its DOCK learnt: the stand-off's trim has just proven too weak.
  if (to == MissionState::charging && !charging_started_) restore_axial_trim_ = true;
  push_event({now, state_, to, reason, aborts_});
  state_ = to;
  entered_ = now;
  hold_frames_ = 0;
  align_avg_valid_ = false;
  contact_frames_ = 0;
  dock_off_frames_ = 0;
  blind_since_ = std::chrono::nanoseconds{-1};
  dock_pushed_ = std::chrono::nanoseconds{0};
  dock_lateral_lp_valid_ = false;
  partial_since_ = std::chrono::nanoseconds{-1};
  unseated_since_ = no_current_since_ = overload_since_ = swing_since_ =
      std::chrono::nanoseconds{-1};
  backed_off_ = false;
  back_off_ = true;
  if (to == MissionState::search) seen_frames_ = 0;
  if (to == MissionState::charging && !charging_started_) {
    charging_started_ = true;
    charging_since_ = now;
  }
  if (to == MissionState::abort && !final_abort_ && aborts_ > p_.max_retries) {
    push_event({now, state_, MissionState::failed, "retries exhausted", aborts_});
    state_ = MissionState::failed;
  }
}

bool Mission::beyond_hold(const Sight& s) {
  if (!s.in.current_beyond_hold) return false;
  enter(MissionState::failed, s.in.now, "current beyond hold");
  return true;
}

void Mission::lost_before_dock(const Sight& s) {
  const std::chrono::nanoseconds now = s.in.now;
  // A current the thrusters cannot hold sweeps the marker from view before the estimate reaches
  // its limit (0.8 m/s across takes it out of view in 3-4 s); it does so again on every retry.
  if (s.in.disturbance_rising) ++swept_losses_;
  if (s.in.disturbance_at_limit || swept_losses_ >= p_.beyond_hold_losses) {
    enter(MissionState::failed, now, "current beyond hold");
    return;
  }
  // APPROACH and ALIGN steer to the stand-off, short of the station, so the probe is not where a
  // back-off must pull it from; and backing off blind takes the vehicle beyond the range the
  // marker can be seen at in turbid water: in the sim's murky water (red extinction 1.6 /m) a
  // loss 0.75 m out backed off to 1.5 m, and the search never saw the marker again. So the abort
  // counts, and the search turns from where the vehicle is.
  enter(MissionState::abort, now, "marker lost");
  back_off_ = false;
}

void Mission::restart(std::chrono::nanoseconds now, const char* reason) {
  aborts_ = 0;
  swept_losses_ = 0;
  search_timed_out_ = false;
  enter(MissionState::search, now, reason);
  started_ = true;
  servo_was_active_ = false;
  have_last_ = false;
  charging_started_ = charge_complete_ = abort_after_undock_ = final_abort_ = false;
  keep_axial_trim_ = restore_axial_trim_ = false;
  reseats_ = 0;
  seat_trim_n_ = 0.0;
  seat_depth_seen_valid_ = false;
  dock_start_back_m_ = p_.standoff_m;
}

MissionOutput Mission::update(const MissionInput& in) {
  if (!started_) {
    started_ = true;
    entered_ = in.now;
  }
  const Sight s = observe(in);
  transition(s);
  return outputs(s);
}

Mission::Sight Mission::observe(const MissionInput& in) {
  Sight s{in};
  s.seen = (in.tracked || (in.recognised && in.fitness >= p_.min_fitness)) &&
           in.T_cl_marker.matrix().allFinite();
  if (s.seen) {
    ++seen_frames_;
    unseen_frames_ = 0;
    s.err = errors(in.T_cl_marker);
    have_last_ = true;
    last_axial_m_ = s.err.axial_m;
  } else {
    seen_frames_ = 0;
    ++unseen_frames_;
  }
  s.full = s.seen && in.full_view;
  partial_frames_ = (s.seen && !s.full) ? partial_frames_ + 1 : 0;
  s.blind_zone = have_last_ && -last_axial_m_ <= p_.dock_blind_distance_m;
  // Outside the blind zone a partial view is no view for docking: the push goes on only on the
  // full one.
  s.seen_dock = s.full || (s.seen && s.blind_zone);
  // In the blind zone a partial view is steered on only when its rotation is the attitude
  // sensor's: in the sim's occluders scenario a bar left no sphere in both views, the estimator's
  // two-sphere pose was 14-58 deg off, and servoing on it brought the probe in 12.8 mm off the
  // axis. Such a view gets the blind push along the docked axis instead.
  s.steer_dock = s.full || (s.seen && s.blind_zone && in.attitude_aided);
  s.contact_switch = p_.contact_switch && in.contact;
  s.tick = last_now_.count() >= 0 ? in.now - last_now_ : std::chrono::nanoseconds{0};
  last_now_ = in.now;
  s.waiting_for_full_view = s.seen && !s.seen_dock;
  if (!s.waiting_for_full_view) {
    partial_since_ = std::chrono::nanoseconds{-1};
  } else if (partial_since_.count() < 0) {
    partial_since_ = in.now;
  }
  s.t_state = seconds(in.now - entered_);
  s.lost = unseen_frames_ >= p_.lost_frames;
  return s;
}

void Mission::transition(const Sight& s) {
  switch (state_) {
    case MissionState::search:
      return from_search(s);
    case MissionState::approach:
      return from_approach(s);
    case MissionState::align:
      return from_align(s);
    case MissionState::dock:
      return from_dock(s);
    case MissionState::abort:
      return from_abort(s);
    case MissionState::charging:
      return from_charging(s);
    case MissionState::undock:
      return from_undock(s);
    case MissionState::docked:
      return from_docked(s);
    case MissionState::failed:
    case MissionState::departed:
      return;
  }
}

void Mission::from_search(const Sight& s) {
  if (seen_frames_ >= p_.acquire_frames) {
    enter(MissionState::approach, s.in.now, "marker recognised");
  } else if (p_.search_timeout_s > 0.0 && s.t_state > p_.search_timeout_s) {
    search_timed_out_ = true;
    enter(MissionState::failed, s.in.now, "search timed out");
  }
}

void Mission::from_approach(const Sight& s) {
  const Errors& err = s.err;
  if (beyond_hold(s)) return;
  // Settled with the marker in view: the thrusters hold this current, so earlier losses while
  // the estimate was rising were not its doing.
  if (s.seen && s.in.disturbance_settled && !s.in.disturbance_rising) swept_losses_ = 0;
  if (s.lost) {
    lost_before_dock(s);
  } else if (s.t_state > p_.approach_timeout_s) {
    enter(MissionState::abort, s.in.now, "approach timed out");
  } else if (s.seen && err.lateral_m <= p_.approach_lateral_m &&
             std::abs(err.axial_m + p_.standoff_m) <= p_.approach_axial_m &&
             std::abs(err.yaw_rad) <= p_.approach_yaw_rad) {
    enter(MissionState::align, s.in.now, "stand-off reached");
  }
}

void Mission::from_align(const Sight& s) {
  // The hold is judged on the signed errors averaged over about align_average_frames full
  // views: in the sim's noisy scenario the estimate's frame-to-frame rotation noise (0.8 deg
  // median) put the probe's lateral error at 7 mm median, 16 mm p90, while the truth was
  // 3.6 mm and 7.5 mm, and 20 frames in a row under 8 mm took minutes. Each frame must still
  // be within the dock's abort limits.
  const Errors& err = s.err;
  bool within = false;
  if (s.full) {
    const Eigen::Vector4d e(err.lateral_x_m, err.lateral_y_m, err.axial_m + p_.standoff_m,
                            err.yaw_rad);
    align_avg_ = align_avg_valid_
                     ? Eigen::Vector4d(align_avg_ + (e - align_avg_) / p_.align_average_frames)
                     : e;
    align_avg_valid_ = true;
    within = err.lateral_m <= p_.dock_abort_lateral_m &&
             std::abs(err.yaw_rad) <= p_.dock_abort_yaw_rad &&
             align_avg_.head<2>().norm() <= p_.align_lateral_m &&
             std::abs(align_avg_.z()) <= p_.align_axial_m &&
             std::abs(align_avg_.w()) <= p_.align_yaw_rad;
  }
  // Judged only once the current's estimate has settled: an error within the limits while it is
  // still learning the push is a vehicle passing through, not one held there.
  hold_frames_ = within && s.in.disturbance_settled ? hold_frames_ + 1 : 0;
  if (beyond_hold(s)) return;
  // Settled with the marker in view: the thrusters hold this current, so earlier losses while
  // the estimate was rising were not its doing.
  if (s.seen && s.in.disturbance_settled && !s.in.disturbance_rising) swept_losses_ = 0;
  if (s.lost) {
    lost_before_dock(s);
  } else if (hold_frames_ >= p_.align_hold_frames) {
    dock_start_back_m_ = p_.standoff_m;
    enter(MissionState::dock, s.in.now, "aligned");
  } else if (s.t_state > p_.align_timeout_s) {
    enter(MissionState::abort, s.in.now,
          s.in.disturbance_settled ? "align timed out" : "align timed out: current not settled");
  }
}

void Mission::from_dock(const Sight& s) {
  const Errors& err = s.err;
  const std::chrono::nanoseconds now = s.in.now;
  if (beyond_hold(s)) return;
  const bool vision_contact = p_.contact_from_vision && s.seen_dock &&
                              err.axial_m >= p_.vision_contact_depth_m &&
                              err.lateral_m <= p_.dock_abort_lateral_m;
  contact_frames_ = (s.contact_switch || vision_contact) ? contact_frames_ + 1 : 0;
  if (s.steer_dock) {
    blind_since_ = std::chrono::nanoseconds{-1};
  } else if (s.blind_zone && blind_since_.count() < 0) {
    blind_since_ = now;
  }
  const bool lateral_off = s.steer_dock && err.lateral_m > p_.dock_abort_lateral_m;
  const bool yaw_off = s.steer_dock && std::abs(err.yaw_rad) > p_.dock_abort_yaw_rad;
  if (s.steer_dock) dock_off_frames_ = (lateral_off || yaw_off) ? dock_off_frames_ + 1 : 0;
  const bool off_limits = dock_off_frames_ >= p_.dock_abort_frames;
  if (contact_frames_ >= p_.contact_frames) {
    enter(MissionState::docked, now, vision_contact ? "contact (vision)" : "contact");
  } else if (off_limits && lateral_off) {
    enter(MissionState::abort, now, "lateral error limit");
  } else if (off_limits && yaw_off) {
    enter(MissionState::abort, now, "yaw error limit");
  } else if (!s.seen_dock && !s.blind_zone && s.lost) {
    enter(MissionState::abort, now, "marker lost");
  } else if (s.waiting_for_full_view && seconds(now - partial_since_) > p_.dock_partial_timeout_s) {
    enter(MissionState::abort, now, "partial view while docking");
  } else if (!s.steer_dock && s.blind_zone &&
             seconds(now - blind_since_) > p_.dock_blind_timeout_s) {
    enter(MissionState::abort, now, "no contact after blind push");
  } else if (s.t_state > p_.dock_timeout_s) {
    enter(MissionState::abort, now, "dock timed out");
  } else {
    return;
  }
  // The recharging mission does not stop at DOCKED: the hold starts in the same tick, so the
  // thrusters never let go of the seat.
  if (state_ == MissionState::docked) from_docked(s);
}

void Mission::from_docked(const Sight& s) {
  if (recharge_) {
    enter(MissionState::charging, s.in.now, charging_started_ ? "re-seated" : "seated: charging");
  }
}

void Mission::from_abort(const Sight& s) {
  if (s.t_state >= (back_off_ ? p_.abort_backoff_s : 0.0)) {
    backed_off_ = true;
    if (!final_abort_)
      enter(MissionState::search, s.in.now, back_off_ ? "backed off" : "searching from here");
  }
}

void Mission::from_undock(const Sight& s) {
  if (s.seen_dock && s.err.axial_m <= -(p_.standoff_m - p_.approach_axial_m)) {
    if (abort_after_undock_) {
      final_abort_ = true;
      enter(MissionState::abort, s.in.now, "undocked after the re-seats ran out");
    } else {
      enter(MissionState::departed, s.in.now, "clear of the station, marker in view");
    }
  } else if (s.t_state > p_.recharge.undock_timeout_s) {
    enter(MissionState::failed, s.in.now, "undock timed out");
  }
}

// Outputs of the state we are in after this tick's transition.
MissionOutput Mission::outputs(const Sight& s) {
  MissionOutput out;
  if (s.seen) {
    out.errors_valid = true;
    out.lateral_error_m = s.err.lateral_m;
    out.axial_error_m = s.err.axial_m;
    out.yaw_error_rad = s.err.yaw_rad;
  }
  out.state = state_;
  out.keep_axial_trim = std::exchange(keep_axial_trim_, false);
  out.restore_axial_trim = std::exchange(restore_axial_trim_, false);
  out.hold_axial_trim = state_ == MissionState::charging;
  switch (state_) {
    case MissionState::search:
      search_outputs(s, out);
      break;
    case MissionState::approach:
    case MissionState::align:
      out.T_cl_marker_desired = T_standoff_;
      // Turning to the axis's heading from far off the axis swings the marker out of view
      // (recharge trial 33: four aborts, FAILED); ALIGN, at the stand-off, turns the rest.
      if (state_ == MissionState::approach) out.max_bearing_rad = p_.approach_view_bearing_rad;
      servo_when(s.seen, out);  // brief loss: hold (feed-forward only)
      break;
    case MissionState::dock:
      dock_outputs(s, out);
      break;
    case MissionState::abort:
      out.use_override = true;
      if (final_abort_ && backed_off_) {
        out.thrusters_enabled = false;
      } else if (back_off_) {
        out.wrench_override_body[0] = -p_.abort_backoff_force_n;
      }
      break;
    case MissionState::charging:
      // Lateral and yaw on the servo; along the axis the set-point follows the probe, so only the
      // push (and the integral's trim carried from the dock) presses it into the seat.
      out.T_cl_marker_desired =
          s.seen_dock ? offset_along_docking_axis(T_docked_, -s.err.axial_m) : T_docked_;
      servo_when(s.seen_dock, out);
      press_seat(s, out);
      break;
    case MissionState::undock:
      undock_outputs(s, out);
      break;
    case MissionState::departed:
      if (departed_hold_) {
        out.T_cl_marker_desired = T_standoff_;
        servo_when(s.seen, out);
      } else {
        out.thrusters_enabled = false;
      }
      break;
    case MissionState::docked:
    case MissionState::failed:
      out.thrusters_enabled = false;
      break;
  }
  if (!servo_state(state_)) out.T_cl_marker_desired = T_standoff_;
  // The servo restarts when it takes over from an open-loop state, not after a brief loss.
  out.servo_restart = out.servo_active && !servo_was_active_;
  if (out.servo_active) servo_was_active_ = true;
  if (!servo_state(state_)) servo_was_active_ = false;
  return out;
}

void Mission::servo_when(bool in_view, MissionOutput& out) {
  out.servo_active = in_view;
  out.use_override = !in_view;
}

void Mission::search_outputs(const Sight& s, MissionOutput& out) const {
  out.use_override = true;
  // A marker found is confirmed over acquire_frames while the scan goes on: the scan turns
  // toward it meanwhile rather than carrying it out of view (in murky water the scan's yaw
  // rate took a faint marker found 27 deg to port out of view 1.8 s into APPROACH). Lost
  // again, the scan turns the configured way: a scan turning back toward the side it was lost
  // on may have to turn against the current, which its moment cannot (in the recharge sim it
  // stalled for 28 s; with the current, the scan came round to the marker in 5.5 s).
  out.wrench_override_body[5] = p_.search_yaw_moment_nm;
  if (s.seen) {
    const Eigen::Vector3d marker_body_m = T_body_cl_ * s.in.T_cl_marker.translation();
    out.wrench_override_body[5] =
        std::copysign(p_.search_yaw_moment_nm, marker_body_m.y() >= 0.0 ? 1.0 : -1.0);
  }
}

void Mission::dock_outputs(const Sight& s, MissionOutput& out) {
  // On a partial view the push waits where it is until the view is whole again or
  // dock_partial_timeout_s runs out, held by the servo only when the pose's rotation comes
  // from the attitude sensor, else by the hold (the trim against the current): the
  // estimator's own pose on two spheres has no error bound and its yaw was 5-40 deg off in
  // the sim's occluders scenario; servoing on it 0.4 m out turned the vehicle past the yaw
  // limit, and holding alone let the current carry it 30 mm off the axis in 2 s. In the blind
  // zone the push goes on: on the servo when the view is full or aided, else blind.
  // A gust that carries the probe off the axis near the socket would have it touch off the axis
  // before the current's estimate catches up: the set-point waits until the servo brings it back.
  // Judged on the error low-passed: a camera on a vibrating mount sees the probe swing by
  // millimetres at several hertz, which is no drift and would stall the push.
  if (s.full) {
    const double tau_s = p_.dock_wait_filter_s;
    const double share =
        !dock_lateral_lp_valid_ || tau_s <= 0.0 ? 1.0 : 1.0 - std::exp(-seconds(s.tick) / tau_s);
    dock_lateral_lp_x_m_ += share * (s.err.lateral_x_m - dock_lateral_lp_x_m_);
    dock_lateral_lp_y_m_ += share * (s.err.lateral_y_m - dock_lateral_lp_y_m_);
    dock_lateral_lp_valid_ = true;
  }
  const bool off_axis =
      s.full && std::hypot(dock_lateral_lp_x_m_, dock_lateral_lp_y_m_) > p_.dock_wait_lateral_m;
  if (s.seen_dock && !off_axis) dock_pushed_ += s.tick;
  if (off_axis) {
    // The servo lags the ramp by centimetres at the dock speed: waiting with the set-point where
    // it was let the probe coast 2 cm on and meet the face 20-40 mm off the axis in a gust.
    const double wait_back_m = -s.err.axial_m + p_.dock_wait_backoff_m;
    const double pushed_max_s =
        std::max(0.0, (dock_start_back_m_ - wait_back_m) / p_.dock_speed_mps);
    dock_pushed_ = std::min(dock_pushed_, std::chrono::duration_cast<std::chrono::nanoseconds>(
                                              std::chrono::duration<double>(pushed_max_s)));
  }
  const double back = std::max(dock_start_back_m_ - p_.dock_speed_mps * seconds(dock_pushed_),
                               -p_.dock_overshoot_m);
  out.T_cl_marker_desired = offset_along_docking_axis(T_docked_, back);
  // steer_dock, and the aided wait
  servo_when(s.full || (s.seen && s.in.attitude_aided), out);
  // A re-seat keeps pressing with what CHARGING had learnt while it slides back in.
  if (charging_started_) press_seat(s, out);
  if (!s.steer_dock && blind_since_.count() >= 0) {
    out.wrench_override_body.head<3>() = docked_axis_body_ * p_.dock_blind_push_n;
  }
}

void Mission::press_seat(const Sight& s, MissionOutput& out) {
  const RechargeParams& r = p_.recharge;
  const double dt_s = seconds(s.tick);
  if (s.seen_dock) {
    // A tenth of a second: the estimate's axial noise in the seat is a fraction of a millimetre,
    // a probe the current draws out moves a centimetre a second.
    const double share = seat_depth_seen_valid_ ? 1.0 - std::exp(-dt_s / 0.1) : 1.0;
    seat_depth_seen_m_ += share * (s.err.axial_m - seat_depth_seen_m_);
    seat_depth_seen_valid_ = true;
  }
  // Short of the socket's bottom by seat_slip_m the pins still touch, so the push grows before
  // the contact is lost, not after; the bottom is the station's, so a harder push (deeper in the
  // compliant seat) cannot move the reference. A re-seat's DOCK keeps the trim as it is: out of
  // the seat the probe is short of the bottom however well the push holds, and a trim grown
  // there pressed a knocked vehicle sideways off the axis.
  const bool slipping =
      (p_.contact_switch && !s.in.contact) || (s.seen_dock && seat_depth_seen_m_ < slip_depth_m_);
  if (state_ == MissionState::charging) {
    seat_trim_n_ = slipping ? std::min(seat_trim_n_ + r.seat_trim_rise_nps * dt_s,
                                       std::max(0.0, r.overload_force_n - r.charge_push_n))
                            : std::max(seat_trim_n_ - r.seat_trim_decay_nps * dt_s, 0.0);
  }
  out.push_body.head<3>() = docked_axis_body_ * (r.charge_push_n + seat_trim_n_);
}

void Mission::undock_outputs(const Sight& s, MissionOutput& out) const {
  const double back =
      std::min(undock_start_back_m_ + p_.recharge.undock_speed_mps * seconds(s.in.now - entered_),
               p_.standoff_m);
  out.T_cl_marker_desired = offset_along_docking_axis(T_docked_, back);
  servo_when(s.seen_dock, out);
  if (!s.seen_dock) {
    out.wrench_override_body.head<3>() = -docked_axis_body_ * p_.recharge.undock_push_n;
  }
}

void Mission::from_charging(const Sight& s) {
  const MissionInput& in = s.in;
  const bool seen_dock = s.seen_dock;
  const Errors& err = s.err;
  const RechargeParams& r = p_.recharge;
  const bool vision_out = seen_dock && err.axial_m < -r.vision_unseat_m;
  const bool contact_lost = p_.contact_switch && !in.contact;
  const bool unseated =
      held_for(contact_lost || vision_out, in.now, unseated_since_, r.unseat_confirm_s);
  const bool past_taper = in.battery_valid && in.soc_fraction >= r.complete_min_soc_fraction;
  const bool full = in.battery_valid && in.soc_fraction >= r.soc_complete_fraction;
  const bool tapered = past_taper && in.charger_valid && in.charge_current_a < r.complete_current_a;
  const bool no_current = held_for(in.charger_valid && !past_taper && !contact_lost &&
                                       !vision_out && in.charge_current_a < r.no_current_a,
                                   in.now, no_current_since_, r.no_current_s);
  const bool pushed =
      held_for(in.hold_force_n > r.overload_force_n, in.now, overload_since_, r.overload_s);
  const bool swung = held_for(seen_dock && std::abs(err.yaw_rad) > r.overload_yaw_rad, in.now,
                              swing_since_, r.overload_yaw_s);
  const bool overload = pushed || swung || in.current_beyond_hold;
  if (in.undock_requested) {
    start_undock(in.now, "operator command");
  } else if (overload) {
    start_undock(in.now, "current beyond what the hold resists");
  } else if (unseated && reseats_ < r.max_reseats) {
    ++reseats_;
    // From where the probe is now (or the socket mouth when it is not seen), not the stand-off.
    dock_start_back_m_ =
        std::clamp(have_last_ ? -last_axial_m_ : 0.0, -p_.dock_overshoot_m, p_.standoff_m);
    enter(MissionState::dock, in.now, "probe unseated: re-seat");
  } else if (unseated) {
    abort_after_undock_ = true;
    start_undock(in.now, "probe unseated: re-seats exhausted");
  } else if (full || (tapered && !contact_lost)) {
    charge_complete_ = true;
    start_undock(in.now, full ? "charge complete (state of charge)" : "charge complete (current)");
  } else if (no_current) {
    start_undock(in.now, "charger reports no current");
  } else if (seconds(in.now - charging_since_) > r.charge_timeout_s) {
    start_undock(in.now, "charge time limit");
  }
}

bool Mission::at_station() const {
  return state_ == MissionState::charging || state_ == MissionState::undock ||
         (state_ == MissionState::dock && charging_started_);
}

void Mission::failsafe_undock(std::chrono::nanoseconds now, const char* reason) {
  if (!at_station() || state_ == MissionState::undock) return;
  start_undock(now, reason);
}

Wrench Mission::back_out_wrench_body() const {
  Wrench w = Wrench::Zero();
  w.head<3>() = -docked_axis_body_ * p_.recharge.undock_push_n;
  return w;
}

void Mission::start_undock(std::chrono::nanoseconds now, const char* reason) {
  undock_start_back_m_ =
      std::clamp(have_last_ ? -last_axial_m_ : 0.0, -p_.dock_overshoot_m, p_.standoff_m);
  enter(MissionState::undock, now, reason);
}

}  // namespace rovctl::control
