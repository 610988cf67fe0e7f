// The failsafe monitors. Ordered so the most basic fault (no camera, no bus) is reported first.
#include "control/failsafe.hpp"

#include <cmath>
#include <stdexcept>

namespace rovctl::control {

const char* to_string(FailsafeCause c) {
  switch (c) {
    case FailsafeCause::none:
      return "none";
    case FailsafeCause::camera_lost:
      return "camera lost";
    case FailsafeCause::bus_fault:
      return "thruster bus fault";
    case FailsafeCause::estimate_not_finite:
      return "estimate not finite";
    case FailsafeCause::wrench_not_finite:
      return "wrench not finite";
    case FailsafeCause::mission_failed:
      return "mission failed";
    case FailsafeCause::mission_time:
      return "mission time limit";
    case FailsafeCause::thruster_fault:
      return "thruster fault";
  }
  return "?";
}

const char* to_string(SafeAction a) {
  switch (a) {
    case SafeAction::none:
      return "none";
    case SafeAction::neutral:
      return "neutral";
    case SafeAction::disarm:
      return "disarm";
    case SafeAction::back_out:
      return "back out";
  }
  return "?";
}

Failsafe::Failsafe(const FailsafeParams& params)
    : p_(params), action_(params.action == "neutral" ? SafeAction::neutral : SafeAction::disarm) {
  if (params.action != "neutral" && params.action != "disarm") {
    throw std::invalid_argument("control.failsafe.action: '" + params.action +
                                "' (disarm or neutral)");
  }
}

FailsafeCause Failsafe::check(const FailsafeInput& in) {
  camera_timeouts_ = in.grab == hal::GrabStatus::timeout ? camera_timeouts_ + 1 : 0;
  bus_degraded_ = in.bus == hal::BusStatus::degraded ? bus_degraded_ + 1 : 0;
  if (in.grab == hal::GrabStatus::device_lost || in.grab == hal::GrabStatus::end_of_stream ||
      camera_timeouts_ > p_.camera_timeout_ticks) {
    return FailsafeCause::camera_lost;
  }
  if (in.bus == hal::BusStatus::fault || bus_degraded_ > p_.bus_degraded_ticks) {
    return FailsafeCause::bus_fault;
  }
  if (in.thrusters_uncontrollable) return FailsafeCause::thruster_fault;
  if (!in.T_cl_marker.matrix().allFinite() || !std::isfinite(in.fitness)) {
    return FailsafeCause::estimate_not_finite;
  }
  if (!in.wrench_body.allFinite()) return FailsafeCause::wrench_not_finite;
  if (in.mission == MissionState::failed) return FailsafeCause::mission_failed;
  if (p_.max_mission_time_s > 0.0 &&
      std::chrono::duration<double>(in.now - start_).count() > p_.max_mission_time_s) {
    return FailsafeCause::mission_time;
  }
  return FailsafeCause::none;
}

namespace {

// Causes that leave the thrusters obeying a command the loop can still form without the failed
// input: the back-out is a constant wrench, so a lost camera or estimate does not matter. A bus
// that does not deliver, or a wrench already not finite, cannot back anything out.
bool thrusters_usable(FailsafeCause c) {
  return c == FailsafeCause::camera_lost || c == FailsafeCause::estimate_not_finite ||
         c == FailsafeCause::mission_time;
}

}  // namespace

void Failsafe::push_event(const FailsafeEvent& e) {
  if (event_count_ < kEventCapacity) {
    events_[(event_head_ + event_count_) % kEventCapacity] = e;
    ++event_count_;
  }
}

SafeAction Failsafe::update(const FailsafeInput& in) {
  if (!started_) {
    started_ = true;
    start_ = in.now;
  }
  const FailsafeCause c = check(in);
  if (!tripped() && c != FailsafeCause::none) {
    cause_ = c;
    backing_out_ = in.at_station && p_.backout_s > 0.0 && thrusters_usable(c);
    back_out_since_ = in.now;
    push_event({in.now, c, action()});
  } else if (backing_out_) {
    // Backed out, or the bus stopped delivering (or the back-out wrench is not finite): now the
    // safe state proper.
    const bool backed_out =
        std::chrono::duration<double>(in.now - back_out_since_).count() >= p_.backout_s;
    const bool cannot_push = in.bus == hal::BusStatus::fault || !in.wrench_body.allFinite();
    if (backed_out || cannot_push) {
      backing_out_ = false;
      push_event({in.now, cause_, action_});
    }
  }
  return action();
}

void Failsafe::reset(std::chrono::nanoseconds now) {
  cause_ = FailsafeCause::none;
  backing_out_ = false;
  camera_timeouts_ = 0;
  bus_degraded_ = 0;
  started_ = true;
  start_ = now;
}

bool Failsafe::pop_event(FailsafeEvent& event) {
  if (event_count_ == 0) return false;
  event = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_count_;
  return true;
}

}  // namespace rovctl::control
