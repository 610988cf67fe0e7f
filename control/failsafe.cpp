// The failsafe monitors. Ordered so the most basic fault (no camera, no bus) is reported first.
#include "control/failsafe.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "hal/primitives/duration_seconds.hpp"

namespace rovctl::control {

using hal::seconds;

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

const char* to_string(FailsafeEventKind k) {
  switch (k) {
    case FailsafeEventKind::trip:
      return "trip";
    case FailsafeEventKind::safe:
      return "safe";
    case FailsafeEventKind::recovered:
      return "recovered";
    case FailsafeEventKind::latched:
      return "latched";
  }
  return "?";
}

namespace {

SafeAction parse_action(const std::string& name, const std::string& key) {
  if (name == "neutral") return SafeAction::neutral;
  if (name == "disarm") return SafeAction::disarm;
  throw std::invalid_argument(key + ": '" + name + "' (disarm or neutral)");
}

// Causes that leave the thrusters obeying a command the loop can still form without the failed
// input: the back-out is a constant wrench, so a lost camera or estimate does not matter. A bus
// that does not deliver, a wrench already not finite, or thrusters that no longer control the
// servo's axes cannot back anything out.
bool thrusters_usable(FailsafeCause c) {
  return c != FailsafeCause::bus_fault && c != FailsafeCause::bus_slow &&
         c != FailsafeCause::wrench_not_finite && c != FailsafeCause::thruster_fault &&
         c != FailsafeCause::disarm_unacked;
}

bool finite_readings(const hal::SensorReadings& r) {
  if (r.depth_valid && !std::isfinite(r.depth_m)) return false;
  return !r.attitude_valid ||
         (r.q_world_body.coeffs().allFinite() && r.omega_body_radps.allFinite());
}

}  // namespace

Failsafe::Failsafe(const FailsafeParams& params)
    : p_(params), action_(parse_action(params.action, "control.failsafe.action")) {
  for (std::size_t i = 0; i < kFailsafeCauseCount; ++i) {
    const FailsafeRule& r = params.policy.rules[i];
    const std::string key =
        std::string("control.failsafe.policy.") + cause_key(static_cast<FailsafeCause>(i));
    actions_[i] = r.action == "default" ? action_ : parse_action(r.action, key + ".action");
    if (r.recovery != "auto" && r.recovery != "latch") {
      throw std::invalid_argument(key + ".recovery: '" + r.recovery + "' (auto or latch)");
    }
    recovers_[i] = r.recovery == "auto";
  }
}

FailsafeCause Failsafe::check(const FailsafeInput& in) {
  camera_timeouts_ = in.grab == hal::GrabStatus::timeout ? camera_timeouts_ + 1 : 0;
  bus_degraded_ = in.bus == hal::BusStatus::degraded ? bus_degraded_ + 1 : 0;
  sensors_silent_ = in.sensors_fitted && !in.sensors_answered ? sensors_silent_ + 1 : 0;
  overruns_ = in.overrun ? overruns_ + 1 : 0;
  // First: it follows another trip's disarm, and what the vehicle can still do depends on it.
  if (in.disarm_unacked) return FailsafeCause::disarm_unacked;
  if (in.grab == hal::GrabStatus::device_lost || in.grab == hal::GrabStatus::end_of_stream) {
    return FailsafeCause::camera_lost;
  }
  if (in.grab == hal::GrabStatus::ok && in.image_dead) return FailsafeCause::camera_dead;
  if (camera_timeouts_ > p_.camera_timeout_ticks) return FailsafeCause::vision_lost;
  if (in.grab == hal::GrabStatus::ok) {
    if (in.identical_frames >= p_.frozen_ticks) return FailsafeCause::vision_frozen;
    if (seconds(in.frame_age) * 1e3 > p_.stale_ms) return FailsafeCause::vision_stale;
    if (seconds(in.stereo_skew) * 1e3 > p_.stereo_skew_ms) return FailsafeCause::stereo_skew;
  }
  if (in.bus == hal::BusStatus::fault) return FailsafeCause::bus_fault;
  if (bus_degraded_ > p_.bus_degraded_ticks) return FailsafeCause::bus_slow;
  if (sensors_silent_ >= p_.sensor_lost_ticks) return FailsafeCause::sensor_lost;
  if (in.sensors_fitted && in.sensors_answered && in.readings != nullptr) {
    const hal::SensorReadings& r = *in.readings;
    if (!finite_readings(r)) return FailsafeCause::sensor_nan;
    if ((r.depth_valid && (r.depth_m < p_.min_depth_m || r.depth_m > p_.max_depth_m)) ||
        (r.attitude_valid && (std::abs(r.q_world_body.norm() - 1.0) > 0.1 ||
                              r.omega_body_radps.cwiseAbs().maxCoeff() > p_.max_rate_radps))) {
      return FailsafeCause::sensor_implausible;
    }
    if (r.leak_valid && r.leak) return FailsafeCause::leak;
    if (r.battery_valid && r.soc_fraction < p_.min_soc_fraction) {
      return FailsafeCause::battery_low;
    }
    if (r.attitude_valid) {
      // Roll and pitch together: the body's z axis off the world's vertical.
      const double cos_tilt = r.q_world_body.normalized().toRotationMatrix()(2, 2);
      if (cos_tilt < std::cos(p_.attitude_limit_rad)) return FailsafeCause::attitude_limit;
    }
  }
  if (in.thrusters_uncontrollable) return FailsafeCause::thruster_fault;
  if (!in.T_cl_marker.matrix().allFinite() || !std::isfinite(in.fitness)) {
    return FailsafeCause::estimate_not_finite;
  }
  if (!in.wrench_body.allFinite()) return FailsafeCause::wrench_not_finite;
  if (overruns_ >= p_.overrun_ticks) return FailsafeCause::cpu_overrun;
  if (in.mission == MissionState::failed) {
    return in.search_timed_out ? FailsafeCause::search_time : FailsafeCause::mission_failed;
  }
  if (mission_s_ > p_.max_mission_time_s) return FailsafeCause::mission_time;
  return FailsafeCause::none;
}

void Failsafe::push_event(const FailsafeInput& in, FailsafeEventKind kind, SafeAction action) {
  if (event_count_ < kEventCapacity) {
    events_[(event_head_ + event_count_) % kEventCapacity] = {in.now, in.tick, kind, cause_,
                                                              action};
    ++event_count_;
  }
}

void Failsafe::trip(FailsafeCause c, const FailsafeInput& in) {
  const auto i = static_cast<std::size_t>(c);
  cause_ = c;
  action_ = actions_[i];
  latched_ = !recovers_[i];
  healthy_ticks_ = 0;
  tripped_at_ = in.now;
  // A back-out already under way goes on unless the new cause stops the thrusters obeying.
  const bool was_backing_out = backing_out_;
  backing_out_ = (was_backing_out || in.at_station) && p_.backout_s > 0.0 && thrusters_usable(c);
  if (!was_backing_out) back_out_since_ = in.now;
  push_event(in, FailsafeEventKind::trip, action());
}

SafeAction Failsafe::update(const FailsafeInput& in) {
  if (!started_) {
    started_ = true;
    last_now_ = in.now;
  }
  if (in.mission != MissionState::charging) mission_s_ += seconds(in.now - last_now_);
  last_now_ = in.now;
  const FailsafeCause c = check(in);
  if (!tripped()) {
    if (c != FailsafeCause::none) trip(c, in);
    return action();
  }
  const bool takes_over =
      c == FailsafeCause::disarm_unacked || (!latched_ && !recovers_[static_cast<std::size_t>(c)]);
  if (c != FailsafeCause::none && c != cause_ && takes_over) {
    trip(c, in);  // hardware failed while waiting for a transient cause to pass
    return action();
  }
  if (backing_out_) {
    // Backed out, or the bus stopped delivering (or the back-out wrench is not finite): now the
    // safe state proper.
    const bool backed_out = seconds(in.now - back_out_since_) >= p_.backout_s;
    const bool cannot_push = in.bus == hal::BusStatus::fault || !in.wrench_body.allFinite();
    if (backed_out || cannot_push) {
      backing_out_ = false;
      push_event(in, FailsafeEventKind::safe, action_);
    }
    return action();
  }
  if (latched_) return action();
  healthy_ticks_ = c == FailsafeCause::none ? healthy_ticks_ + 1 : 0;
  if (healthy_ticks_ >= p_.recover_ticks) {
    push_event(in, FailsafeEventKind::recovered, SafeAction::none);
    cause_ = FailsafeCause::none;
    recovered_ = true;
  } else if (seconds(in.now - tripped_at_) > p_.recover_within_s) {
    latched_ = true;
    push_event(in, FailsafeEventKind::latched, action_);
  }
  return action();
}

void Failsafe::reset(std::chrono::nanoseconds now) {
  cause_ = FailsafeCause::none;
  latched_ = recovered_ = backing_out_ = false;
  healthy_ticks_ = camera_timeouts_ = bus_degraded_ = sensors_silent_ = overruns_ = 0;
  started_ = true;
  last_now_ = now;
  mission_s_ = 0.0;
}

bool Failsafe::pop_event(FailsafeEvent& event) {
  if (event_count_ == 0) return false;
  event = events_[event_head_];
  event_head_ = (event_head_ + 1) % kEventCapacity;
  --event_count_;
  return true;
}

}  // namespace rovctl::control
