// The docking mission's transitions. Counters are in frames (ticks with a fresh estimate),
// timeouts in the input's clock.
#include "control/mission.hpp"

#include <algorithm>
#include <cmath>

#include "control/pd_visual_servo.hpp"

namespace rovctl::control {
namespace {

double seconds(std::chrono::nanoseconds d) { return std::chrono::duration<double>(d).count(); }

bool servo_state(MissionState s) {
  return s == MissionState::approach || s == MissionState::align || s == MissionState::dock;
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
                 const Eigen::Vector3d& control_point_body_m)
    : p_(params),
      T_body_cl_(T_body_cl),
      T_docked_(T_cl_marker_docked),
      T_standoff_(offset_along_docking_axis(T_cl_marker_docked, params.standoff_m)),
      control_point_body_m_(control_point_body_m) {
  cp_docked_marker_m_ = (T_body_cl_ * T_docked_).inverse() * control_point_body_m_;
  // Blind, the vehicle pushes along the docking axis as it lies when docked: the servo has just
  // aligned it, and one noisy last estimate would be a worse guess.
  docked_axis_body_ = (T_body_cl_ * T_docked_).linear().col(2);
}

Mission::Errors Mission::errors(const Eigen::Isometry3d& T_cl_marker) const {
  const Eigen::Vector3d cp = (T_body_cl_ * T_cl_marker).inverse() * control_point_body_m_;
  const Eigen::Vector3d d = cp - cp_docked_marker_m_;
  const double yaw = pose_error_body(T_body_cl_, T_cl_marker, T_docked_, false)[5];
  return {d.head<2>().norm(), d.z(), yaw};
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

void Mission::enter(MissionState to, std::chrono::nanoseconds now, const char* reason) {
  if (to == MissionState::abort) ++aborts_;
  push_event({now, state_, to, reason, aborts_});
  state_ = to;
  entered_ = now;
  hold_frames_ = 0;
  contact_frames_ = 0;
  dock_off_frames_ = 0;
  blind_since_ = std::chrono::nanoseconds{-1};
  if (to == MissionState::search) seen_frames_ = 0;
  if (to == MissionState::abort && aborts_ > p_.max_retries) {
    push_event({now, state_, MissionState::failed, "retries exhausted", aborts_});
    state_ = MissionState::failed;
  }
}

void Mission::restart(std::chrono::nanoseconds now) {
  aborts_ = 0;
  enter(MissionState::search, now, "restart");
  started_ = true;
  servo_was_active_ = false;
  have_last_ = false;
}

MissionOutput Mission::update(const MissionInput& in) {
  if (!started_) {
    started_ = true;
    entered_ = in.now;
  }
  const bool seen =
      in.recognised && in.fitness >= p_.min_fitness && in.T_cl_marker.matrix().allFinite();
  MissionOutput out;
  Errors err{0.0, 0.0, 0.0};
  if (seen) {
    ++seen_frames_;
    unseen_frames_ = 0;
    err = errors(in.T_cl_marker);
    out.errors_valid = true;
    out.lateral_error_m = err.lateral_m;
    out.axial_error_m = err.axial_m;
    out.yaw_error_rad = err.yaw_rad;
    have_last_ = true;
    last_axial_m_ = err.axial_m;
  } else {
    seen_frames_ = 0;
    ++unseen_frames_;
  }
  const bool full = seen && in.full_view;
  partial_frames_ = (seen && !full) ? partial_frames_ + 1 : 0;
  const bool blind_zone = have_last_ && -last_axial_m_ <= p_.dock_blind_distance_m;
  // Outside the blind zone a partial view is no view for docking: the push goes on only on the
  // full one.
  const bool seen_dock = full || (seen && blind_zone);
  const bool contact_switch = p_.contact_switch && in.contact;
  const double t_state = seconds(in.now - entered_);
  const bool lost = unseen_frames_ >= p_.lost_frames;

  switch (state_) {
    case MissionState::search:
      if (seen_frames_ >= p_.acquire_frames) {
        enter(MissionState::approach, in.now, "marker recognised");
      } else if (p_.search_timeout_s > 0.0 && t_state > p_.search_timeout_s) {
        enter(MissionState::failed, in.now, "search timed out");
      }
      break;
    case MissionState::approach:
      if (lost) {
        enter(MissionState::abort, in.now, "marker lost");
      } else if (t_state > p_.approach_timeout_s) {
        enter(MissionState::abort, in.now, "approach timed out");
      } else if (seen && err.lateral_m <= p_.approach_lateral_m &&
                 std::abs(err.axial_m + p_.standoff_m) <= p_.approach_axial_m &&
                 std::abs(err.yaw_rad) <= p_.approach_yaw_rad) {
        enter(MissionState::align, in.now, "stand-off reached");
      }
      break;
    case MissionState::align:
      if (full && err.lateral_m <= p_.align_lateral_m &&
          std::abs(err.axial_m + p_.standoff_m) <= p_.align_axial_m &&
          std::abs(err.yaw_rad) <= p_.align_yaw_rad) {
        ++hold_frames_;
      } else {
        hold_frames_ = 0;
      }
      if (lost) {
        enter(MissionState::abort, in.now, "marker lost");
      } else if (hold_frames_ >= p_.align_hold_frames) {
        enter(MissionState::dock, in.now, "aligned");
      } else if (t_state > p_.align_timeout_s) {
        enter(MissionState::abort, in.now, "align timed out");
      }
      break;
    case MissionState::dock: {
      const bool vision_contact = p_.contact_from_vision && seen_dock &&
                                  err.axial_m >= p_.vision_contact_depth_m &&
                                  err.lateral_m <= p_.dock_abort_lateral_m;
      contact_frames_ = (contact_switch || vision_contact) ? contact_frames_ + 1 : 0;
      if (seen_dock) {
        blind_since_ = std::chrono::nanoseconds{-1};
      } else if (blind_zone && blind_since_.count() < 0) {
        blind_since_ = in.now;
      }
      const bool lateral_off = seen_dock && err.lateral_m > p_.dock_abort_lateral_m;
      const bool yaw_off = seen_dock && std::abs(err.yaw_rad) > p_.dock_abort_yaw_rad;
      if (seen_dock) dock_off_frames_ = (lateral_off || yaw_off) ? dock_off_frames_ + 1 : 0;
      const bool off_limits = dock_off_frames_ >= p_.dock_abort_frames;
      if (contact_frames_ >= p_.contact_frames) {
        enter(MissionState::docked, in.now, vision_contact ? "contact (vision)" : "contact");
      } else if (off_limits && lateral_off) {
        enter(MissionState::abort, in.now, "lateral error limit");
      } else if (off_limits && yaw_off) {
        enter(MissionState::abort, in.now, "yaw error limit");
      } else if (!seen_dock && !blind_zone && (lost || partial_frames_ >= p_.lost_frames)) {
        enter(MissionState::abort, in.now, lost ? "marker lost" : "partial view while docking");
      } else if (!seen_dock && blind_zone &&
                 seconds(in.now - blind_since_) > p_.dock_blind_timeout_s) {
        enter(MissionState::abort, in.now, "no contact after blind push");
      } else if (t_state > p_.dock_timeout_s) {
        enter(MissionState::abort, in.now, "dock timed out");
      }
      break;
    }
    case MissionState::abort:
      if (t_state >= p_.abort_backoff_s) enter(MissionState::search, in.now, "backed off");
      break;
    case MissionState::docked:
    case MissionState::failed:
      break;
  }

  // Outputs of the state we are in after this tick's transition.
  out.state = state_;
  switch (state_) {
    case MissionState::search:
      out.use_override = true;
      out.wrench_override_body[5] = p_.search_yaw_moment_nm;
      break;
    case MissionState::approach:
    case MissionState::align:
      out.T_cl_marker_desired = T_standoff_;
      out.servo_active = seen;
      out.use_override = !seen;  // brief loss: hold (feed-forward only)
      break;
    case MissionState::dock: {
      const double back = std::max(p_.standoff_m - p_.dock_speed_mps * seconds(in.now - entered_),
                                   -p_.dock_overshoot_m);
      out.T_cl_marker_desired = offset_along_docking_axis(T_docked_, back);
      out.servo_active = seen_dock;
      out.use_override = !seen_dock;
      if (!seen_dock && blind_since_.count() >= 0) {
        out.wrench_override_body.head<3>() = docked_axis_body_ * p_.dock_blind_push_n;
      }
      break;
    }
    case MissionState::abort:
      out.use_override = true;
      out.wrench_override_body[0] = -p_.abort_backoff_force_n;
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

}  // namespace rovctl::control
