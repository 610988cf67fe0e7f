// The application's tick. Stage order as in docs/architecture.md; every failure path ends in a
// written command (neutral in the safe state), so the thrusters never keep a stale command.
#include "app/runtime/vehicle_loop.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "app/runtime/pose_measurement.hpp"
#include "hal/model/docking_station.hpp"

namespace rovctl::app {
namespace {

constexpr std::chrono::seconds kSettleAfterEnd{1};
// The body rates carry the attitude across a few missed reads, not across a sensor outage.
constexpr std::chrono::milliseconds kAttitudeMaxGap{250};

bool finite_pose(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

void put_pose(const Eigen::Isometry3d& T, std::array<double, 3>& t, std::array<double, 4>& q) {
  const Eigen::Quaterniond r(T.linear());
  t = {T.translation().x(), T.translation().y(), T.translation().z()};
  q = {r.w(), r.x(), r.y(), r.z()};
}

}  // namespace

std::string format_event(const LoopEvent& e) {
  char line[256];
  const double t = std::chrono::duration<double>(e.time).count();
  if (e.thruster >= 0) {
    std::snprintf(line, sizeof(line),
                  "%9.3f s  THRUSTER %d (channel %d) failed at tick %llu: %s -> removed from the "
                  "allocation, %zu left, x y z yaw %s",
                  t, e.thruster, e.thruster_channel, static_cast<unsigned long long>(e.tick),
                  control::to_string(e.thruster_failure), e.thrusters_left,
                  e.servo_axes_controllable ? "controllable" : "NOT controllable");
  } else if (e.failsafe && e.failsafe_kind == control::FailsafeEventKind::recovered) {
    std::snprintf(line, sizeof(line), "%9.3f s  FAILSAFE %s recovered (tick %llu)", t,
                  control::to_string(e.cause), static_cast<unsigned long long>(e.tick));
  } else if (e.failsafe && e.failsafe_kind == control::FailsafeEventKind::latched) {
    std::snprintf(line, sizeof(line), "%9.3f s  FAILSAFE %s%s%s%s latched -> %s (tick %llu)", t,
                  control::to_string(e.cause), *e.reason ? " (" : "", e.reason,
                  *e.reason ? ")" : "", control::to_string(e.action),
                  static_cast<unsigned long long>(e.tick));
  } else if (e.failsafe) {
    std::snprintf(line, sizeof(line), "%9.3f s  FAILSAFE %s%s%s%s -> %s (tick %llu)", t,
                  control::to_string(e.cause), *e.reason ? " (" : "", e.reason,
                  *e.reason ? ")" : "", control::to_string(e.action),
                  static_cast<unsigned long long>(e.tick));
  } else {
    std::snprintf(line, sizeof(line), "%9.3f s  mission %s -> %s (%s, aborts %d)", t,
                  control::to_string(e.from), control::to_string(e.to), e.reason, e.aborts);
  }
  return line;
}

VehicleLoop::VehicleLoop(const AppConfig& config, const hal::StereoRig& rig,
                         hal::StereoCamera& camera, hal::ThrusterBus& bus, hal::Sensors* sensors,
                         CyclicScheduler& scheduler, TelemetryRing* telemetry, std::uint64_t seed)
    : config_(config),
      camera_(camera),
      bus_(bus),
      sensors_(sensors),
      scheduler_(scheduler),
      telemetry_(telemetry),
      estimator_(rig, config.marker, config.estimator, seed),
      confirmation_(config.estimator.improved() ? config.estimator.confirm
                                                : estimator::ConfirmationParams{0.0, 0.0, 1.0}),
      servo_(config.control.servo, config.vehicle.T_body_cl()),
      attitude_(config.control.attitude),
      allocator_(config.vehicle.thrusters, config.control.allocation),
      health_(allocator_.effectiveness(), config.control.thruster_health),
      mission_(config.mission, config.vehicle.T_body_cl(),
               hal::docked_T_cl_marker(config.vehicle.T_body_cl(), config.vehicle.probe_tip_body_m,
                                       config.station),
               config.vehicle.probe_tip_body_m, config.station.capture_depth_m),
      failsafe_(config.control.failsafe),
      aided_pose_(config.vehicle.T_body_cl(),
                  std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::duration<double>(config.mission.partial_view_attitude_s))),
      attitude_filter_(config.control.tracker.attitude_filter_s, kAttitudeMaxGap),
      tracker_(config.control.tracker, config.vehicle.T_body_cl(),
               config.estimator.ok_bound_mm / 1000.0, config.estimator.ok_bound_deg),
      frame_monitor_(config.control.failsafe.dead_range_levels) {
  // Start-up allocations: the frame buffers at the calibrated size, the neutral command.
  frame_.left_bgr.create(rig.left.height_px, rig.left.width_px, CV_8UC3);
  frame_.right_bgr.create(rig.right.height_px, rig.right.width_px, CV_8UC3);
  allocator_.neutral(neutral_);
  command_ = neutral_;
  servo_.set_capacity(allocator_.axis_capacity());
}

bool VehicleLoop::arm(std::string& error) {
  if (bus_.write(neutral_) == hal::BusStatus::fault || bus_.arm(true) == hal::BusStatus::fault) {
    const char* why = bus_.fault_reason();
    error = bus_.name() + ": could not arm the thrusters" +
            (why != nullptr && why[0] != '\0' ? std::string(" (") + why + ")" : std::string());
    return false;
  }
  armed_ = true;
  return true;
}

void VehicleLoop::disarm() {
  if (!armed_) return;
  bus_.write(neutral_);
  bus_.arm(false);
  armed_ = false;
}

void VehicleLoop::queue(const LoopEvent& e) {
  if (!events_.try_push(e)) ++dropped_events_;
}

void VehicleLoop::check_thrusters(std::chrono::nanoseconds now, std::chrono::nanoseconds period) {
  // Read every tick, health monitor or not: its status is this tick's news of the bus (a slow
  // or dead peer), where the last write's status is a tick old.
  bus_read_status_ = bus_.read(thruster_telemetry_);
  if (!config_.control.thruster_health.enabled) return;
  // A bus that cannot be read is the bus fault's business, not a thruster's.
  if (bus_read_status_ == hal::BusStatus::fault) return;
  // command_ is what the previous tick wrote: what the thrusters answer now.
  if (health_.update(thruster_telemetry_, command_,
                     std::chrono::duration<double>(period).count()) == 0) {
    return;
  }
  for (std::size_t i = 0; i < allocator_.effectiveness().count(); ++i) {
    if (!health_.failed(i) || !allocator_.active(i)) continue;
    thrusters_uncontrollable_ = !allocator_.remove_thruster(i);
    servo_.set_capacity(allocator_.axis_capacity());
    LoopEvent e;
    e.time = now;
    e.from = e.to = mission_.state();
    e.aborts = mission_.aborts();
    e.thruster = static_cast<int>(i);
    e.thruster_channel = allocator_.effectiveness().channel(i);
    e.thruster_failure = health_.failure(i);
    e.tick = ticks_;
    e.thrusters_left = allocator_.active_count();
    e.servo_axes_controllable = !thrusters_uncontrollable_;
    queue(e);
  }
}

// The tick reads as ARCHITECTURE.md's table: one method per stage, each timed against its budget.
bool VehicleLoop::tick(const TickInfo& info) {
  ++ticks_;
  TickState t(info);
  capture(t);
  const auto compute_start = std::chrono::steady_clock::now();
  segment(t);
  estimate(t);
  control(t);
  compute_time_ = std::chrono::steady_clock::now() - compute_start;
  actuate(t);
  telemetry(t);
  return keep_running(t.now);
}

void VehicleLoop::capture(TickState& t) {
  {
    auto timer = scheduler_.stage(Stage::capture);
    t.grab = camera_.grab(frame_);
  }
  t.have_images = t.grab == hal::GrabStatus::ok;
  if (t.have_images) frame_monitor_.update(frame_, t.now);
}

void VehicleLoop::segment(TickState& t) {
  if (t.have_images) {
    auto timer = scheduler_.stage(Stage::segment);
    // An image the calibration does not describe is a camera fault, not an exception.
    if (!estimator_.segment(frame_.left_bgr, frame_.right_bgr)) {
      t.grab = hal::GrabStatus::device_lost;
      t.have_images = false;
    }
  }
  if (!t.have_images) {
    ++grab_failures_;
    t.flags |= telemetry_flag::capture_failed;
  }
}

void VehicleLoop::estimate(TickState& t) {
  {
    auto timer = scheduler_.stage(Stage::estimate);
    if (t.have_images) {
      // The tracker carries the pose through a frame the first look declines for a bar.
      estimate_ = estimator_.estimate(config_.control.tracker.enabled ? estimator::Looks::as_needed
                                                                      : estimator::Looks::all);
      confirmation_.judge(estimate_, frame_.left_stamp);
    } else {
      estimate_.recognised = false;
      estimate_.generations = 0;
    }
  }
  t.seen = t.have_images && estimate_.recognised && finite_pose(estimate_.T_cl_marker) &&
           std::isfinite(estimate_.fitness);
  if (t.seen) ++recognised_ticks_;
}

void VehicleLoop::control(TickState& t) {
  auto timer = scheduler_.stage(Stage::control);
  check_thrusters(t.now, t.info.period);
  mission_input(t);
  take_operator_commands(t.now);
  const bool safe_hold = failsafe_.tripped() && !failsafe_.backing_out();
  if (operator_hold_ || safe_hold) {
    // The mission is frozen where the operator or the failsafe stopped it; nothing is thrust.
    t.out.state = mission_.state();
    t.out.thrusters_enabled = false;
  } else {
    t.out = mission_.update(t.in);
  }
  // Roll and pitch from the IMU in every state: the vision servo only damps them, and a
  // tipped vehicle loses the marker.
  t.levelled =
      !config_.control.servo.six_dof && t.have_readings && attitude_.update(readings_, t.level_nm);
  servo_wrench(t);
  last_hold_force_n_ = t.out.thrusters_enabled ? t.wrench.head<2>().norm() : 0.0;
  if (t.out.state != control::MissionState::charging) undock_requested_.store(false);
  run_failsafe(t);
  const bool thrust = t.action == control::SafeAction::none
                          ? t.out.thrusters_enabled
                          : t.action == control::SafeAction::back_out;
  if (!thrust) {
    command_ = neutral_;
  } else {
    servo_.set_allocation_fraction(allocator_.allocate(t.wrench, command_));
  }
}

void VehicleLoop::actuate(TickState& t) {
  auto timer = scheduler_.stage(Stage::actuate);
  if ((t.action == control::SafeAction::disarm && armed_) || disarm_unacked_) {
    retry_disarm();
  } else if (t.action == control::SafeAction::none && disarmed_by_failsafe_) {
    rearm_after_failsafe();
  } else {
    bus_status_ = bus_.write(command_);
  }
}

void VehicleLoop::telemetry(TickState& t) {
  auto timer = scheduler_.stage(Stage::telemetry);
  queue_mission_and_failsafe_events();
  if (gcs_ != nullptr) post_gcs_values(t);
  if (telemetry_ != nullptr || operator_link_ != nullptr) {
    TelemetryRecord rec;
    fill_record(t, rec);
    if (telemetry_ != nullptr) telemetry_->try_push(rec);
    if (operator_link_ != nullptr)
      operator_link_->publish(rec, t.have_images ? &frame_ : nullptr, t.now);
  }
}

bool VehicleLoop::keep_running(std::chrono::nanoseconds now) {
  // An operator hold waits for START (or the operator's stop), even after the mission ended; a
  // failsafe ends the run once the vehicle is safe, not while it backs out of the socket.
  const bool latched = failsafe_.tripped() && !failsafe_.backing_out() &&
                       !failsafe_.awaiting_recovery() && operator_link_ == nullptr;
  const bool ended = latched || (mission_.finished() && !operator_hold_ && !failsafe_.tripped());
  if (!ended) {
    ended_at_ = std::chrono::nanoseconds{-1};
    return true;
  }
  if (ended_at_.count() < 0) ended_at_ = now;
  return now - ended_at_ < kSettleAfterEnd;
}

// --- control's parts

void VehicleLoop::mission_input(TickState& t) {
  control::MissionInput& in = t.in;
  t.have_readings = sensors_ != nullptr && sensors_->read(readings_);
  if (t.have_readings) {
    in.charger_valid = readings_.charger_valid && std::isfinite(readings_.charge_current_a);
    in.charge_current_a = readings_.charge_current_a;
    in.battery_valid = readings_.battery_valid && std::isfinite(readings_.soc_fraction);
    in.soc_fraction = readings_.soc_fraction;
  }
  in.hold_force_n = last_hold_force_n_;
  const control::DisturbanceEstimate& current = servo_.disturbance();
  in.disturbance_settled = current.settled();
  in.disturbance_at_limit = current.at_limit();
  in.disturbance_rising = current.rising();
  in.current_beyond_hold = current.beyond_hold();
  in.undock_requested = undock_requested_.load(std::memory_order_relaxed);
  in.now = t.now;
  in.recognised = t.seen;
  in.full_view = t.seen && estimate_.ok;
  in.fitness = estimate_.fitness;
  in.T_cl_marker = estimate_.T_cl_marker;
  t.attitude = t.have_readings && readings_.attitude_valid &&
               readings_.q_world_body.coeffs().allFinite() && readings_.q_world_body.norm() > 0.5;
  track(t);
  aid_partial_view(t);
  in.contact = t.have_readings && readings_.dock_contact_valid && readings_.dock_contact;
}

void VehicleLoop::track(TickState& t) {
  if (!config_.control.tracker.enabled) return;
  const bool attitude = attitude_filter_.update(t.now, t.attitude, readings_.q_world_body,
                                                readings_.omega_body_radps);
  // Without a frame there is nothing to fuse: the track is predicted to now, unchanged.
  const std::chrono::nanoseconds at = t.have_images ? frame_.left_stamp : t.now;
  const Eigen::Quaterniond q =
      attitude ? attitude_filter_.q_world_body_at(at) : Eigen::Quaterniond::Identity();
  tracked_ = t.have_images ? tracker_.update(at, q, attitude,
                                             pose_measurement(estimate_, config_.marker,
                                                              config_.estimator.rim_support))
                           : tracker_.predict(at, q, attitude);
  // A frame's ok estimate the track has not taken (its first, or one that disagrees) is no full
  // view yet: the next frame confirms one or the other.
  t.in.tracked = tracked_.ok;
  t.in.full_view = tracked_.ok;
  if (tracked_.ok) t.in.T_cl_marker = tracked_.T_cl_marker;
}

void VehicleLoop::aid_partial_view(TickState& t) {
  if (!t.attitude) return;
  if (t.in.full_view) {
    aided_pose_.remember(t.now, readings_.q_world_body, t.in.T_cl_marker);
    return;
  }
  if (!t.seen) return;
  // The spheres the pose is supported by in both views fix the translation.
  std::array<Eigen::Vector3d, control::AttitudeAidedPose::kMaxPoints> points;
  int n = 0;
  const double support = config_.estimator.sphere_support;
  for (std::size_t s = 0; s < config_.marker.spheres.size() && s < points.size(); ++s) {
    if (estimate_.sphere_scores[0][s] >= support && estimate_.sphere_scores[1][s] >= support)
      points[n++] = config_.marker.spheres[s].centre_marker_m;
  }
  t.in.attitude_aided = aided_pose_.aid(t.now, readings_.q_world_body, estimate_.T_cl_marker,
                                        points.data(), n, t.in.T_cl_marker);
}

void VehicleLoop::take_operator_commands(std::chrono::nanoseconds now) {
  if (operator_link_ == nullptr) return;
  if (operator_link_->take_abort() && !operator_hold_) {
    operator_hold_ = true;
    LoopEvent e;
    e.time = now;
    e.from = e.to = mission_.state();
    e.reason = "operator ABORT: neutral, holding until START";
    e.aborts = mission_.aborts();
    queue(e);
  }
  if (operator_link_->take_start() &&
      (operator_hold_ || mission_.finished() || failsafe_.tripped())) {
    // START re-arms after any failsafe, latched or not: the operator has seen the cause.
    operator_hold_ = false;
    failsafe_.reset(now);
    restart_mission(now, "restart");  // logged by the mission as a restart
  }
}

void VehicleLoop::restart_mission(std::chrono::nanoseconds now, const char* reason) {
  mission_.restart(now, reason);
  servo_.reset();
  last_servo_time_ = std::chrono::nanoseconds{-1};
}

// A failsafe at the station backs out open loop: the trim that held the vehicle (feed-forward
// and the integral against the current) plus the push out; no input it may distrust.
control::Wrench VehicleLoop::back_out_wrench(const TickState& t) const {
  control::Wrench w = servo_.hold_wrench_body() + mission_.back_out_wrench_body();
  if (t.levelled) {
    w[3] = t.level_nm.x();
    w[4] = t.level_nm.y();
  }
  return w;
}

void VehicleLoop::servo_wrench(TickState& t) {
  const control::MissionOutput& out = t.out;
  t.backing_out = failsafe_.backing_out();  // tripped on an earlier tick
  if (t.backing_out) {
    t.wrench = back_out_wrench(t);
    return;
  }
  if (!out.thrusters_enabled) return;
  if (out.servo_active && out.servo_restart) servo_.restart();
  if (out.keep_axial_trim) axial_trim_n_ = servo_.integral_term()[0];
  if (out.restore_axial_trim) servo_.set_integral_term(0, axial_trim_n_);
  servo_.hold_integral(0, out.hold_axial_trim);
  if (out.servo_active) {
    const std::chrono::nanoseconds dt =
        last_servo_time_.count() < 0 ? t.info.period : t.now - last_servo_time_;
    servo_.keep_in_view(out.max_bearing_rad);
    t.wrench = servo_.update(t.in.T_cl_marker, out.T_cl_marker_desired, dt);
    last_servo_time_ = t.now;
  } else {
    // Keep the integral's trim (against the current) while the marker is briefly unseen.
    t.wrench = servo_.hold_wrench_body();
    if (out.use_override) t.wrench += out.wrench_override_body;
    last_servo_time_ = std::chrono::nanoseconds{-1};
  }
  t.wrench += out.push_body;
  if (t.levelled) {
    t.wrench[3] = t.level_nm.x();
    t.wrench[4] = t.level_nm.y();
  }
}

void VehicleLoop::run_failsafe(TickState& t) {
  t.action = failsafe_.update(failsafe_input(t));
  if (failsafe_.take_recovered()) {
    // The cause has passed: the mission starts over from SEARCH (where the vehicle is now is
    // not where the interrupted state left it), re-armed if the trip disarmed.
    restart_mission(t.now, "failsafe recovered: resuming from SEARCH");
    t.out.state = mission_.state();
    t.out.thrusters_enabled = false;  // from the next tick
  }
  if (t.action == control::SafeAction::back_out && !t.backing_out) {
    // Tripped this tick: the mission backs out too (logged), from this tick's command on.
    mission_.failsafe_undock(t.now, "failsafe: backing out of the socket");
    t.out.state = mission_.state();
    t.wrench = back_out_wrench(t);
  }
}

control::FailsafeInput VehicleLoop::failsafe_input(const TickState& t) {
  control::FailsafeInput fs;
  fs.now = t.now;
  fs.tick = ticks_;
  fs.grab = t.grab;
  const FrameHealth& fh = frame_monitor_.health();
  fs.identical_frames = fh.identical_frames;
  fs.image_dead = fh.image_dead;
  fs.frame_age = fh.frame_age;
  fs.stereo_skew = fh.stereo_skew;
  fs.sensors_fitted = sensors_ != nullptr;
  fs.sensors_answered = t.have_readings;
  fs.readings = &readings_;
  // An overrun counts once: at the tick that overran when it already knows before actuating
  // (a stalled capture or estimate), else at the next tick from the releases it skipped.
  const bool overrunning = scheduler_.tick_overrunning();
  fs.overrun = overrunning || (t.info.skipped_before > 0 && !overrun_counted_);
  overrun_counted_ = overrunning;
  fs.search_timed_out = mission_.search_timed_out();
  fs.bus = std::max(bus_status_, bus_read_status_);  // the worse of the two
  fs.disarm_unacked = disarm_unacked_;
  fs.T_cl_marker = estimate_.T_cl_marker;
  fs.fitness = t.have_images ? estimate_.fitness : 0.0;
  fs.wrench_body = t.wrench;
  fs.mission = t.out.state;
  fs.at_station = mission_.at_station();
  fs.thrusters_uncontrollable = thrusters_uncontrollable_;
  return fs;
}

// --- actuate's parts

// An unacknowledged disarm is retried every tick, behind a neutral command, until the bus takes
// it; meanwhile the failsafe knows the ESCs may still be armed.
void VehicleLoop::retry_disarm() {
  bus_.write(neutral_);
  bus_status_ = bus_.arm(false);
  // A bus that answers nothing is the bus fault's (the ESCs' own timeout stops them); one that
  // answers the rest but refuses the disarm leaves them armed.
  disarm_unacked_ =
      bus_status_ == hal::BusStatus::fault && bus_read_status_ != hal::BusStatus::fault;
  armed_ = disarm_unacked_;
  disarmed_by_failsafe_ = !disarm_unacked_;
}

// Recovered (or re-armed by the operator) after a disarm: neutral, then arm again.
void VehicleLoop::rearm_after_failsafe() {
  bus_status_ = bus_.write(neutral_);
  if (bus_status_ != hal::BusStatus::fault) bus_status_ = bus_.arm(true);
  armed_ = bus_status_ != hal::BusStatus::fault;
  disarmed_by_failsafe_ = !armed_;
}

// --- telemetry's parts

void VehicleLoop::queue_mission_and_failsafe_events() {
  control::MissionEvent me;
  while (mission_.pop_event(me)) {
    LoopEvent e;
    e.time = me.time;
    e.from = me.from;
    e.to = me.to;
    e.reason = me.reason;
    e.aborts = me.aborts;
    queue(e);
  }
  control::FailsafeEvent fe;
  while (failsafe_.pop_event(fe)) {
    LoopEvent e;
    e.failsafe = true;
    e.time = fe.time;
    e.cause = fe.cause;
    e.action = fe.action;
    e.failsafe_kind = fe.kind;
    e.tick = fe.tick;
    if (fe.cause == control::FailsafeCause::bus_fault &&
        fe.kind != control::FailsafeEventKind::recovered) {
      const char* why = bus_.fault_reason();
      if (why != nullptr) e.reason = why;
    }
    queue(e);
  }
}

void VehicleLoop::post_gcs_values(const TickState& t) {
  constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
  const bool img = t.have_images;
  drivers::GcsValues v;
  v.mission_state = static_cast<float>(t.out.state);
  v.fitness = img ? static_cast<float>(estimate_.fitness) : kNaNf;
  v.distance_m = img ? static_cast<float>(estimate_.T_cl_marker.translation().norm()) : kNaNf;
  v.lateral_error_m = t.out.errors_valid ? static_cast<float>(t.out.lateral_error_m) : kNaNf;
  v.not_ok_reason = img ? static_cast<float>(estimate_.not_ok_reason) : kNaNf;
  v.failsafe = failsafe_.tripped();
  gcs_->post_values(v);
}

void VehicleLoop::fill_record(const TickState& t, TelemetryRecord& rec) const {
  std::uint32_t flags = t.flags;
  fill_schedule_fields(rec, t.info, scheduler_);
  rec.capture_ns = frame_.left_stamp.count();
  rec.mission_state = static_cast<std::int32_t>(t.out.state);
  rec.generations = estimate_.generations;
  if (t.have_images) {
    rec.fitness = estimate_.fitness;
    rec.spheres_seen_left = estimate_.spheres_seen[0];
    rec.spheres_seen_right = estimate_.spheres_seen[1];
    rec.error_bound_m = estimate_.error_bound_m;
    rec.error_bound_deg = estimate_.error_bound_deg;
    rec.not_ok_reason = static_cast<std::int32_t>(estimate_.not_ok_reason);
    if (estimate_.ok) flags |= telemetry_flag::full_view;
    put_pose(estimate_.T_cl_marker, rec.est_t_m, rec.est_q_wxyz);
    flags |= telemetry_flag::estimate_valid;
  }
  if (t.seen) flags |= telemetry_flag::recognised;
  if (config_.control.tracker.enabled) {
    flags |= telemetry_flag::tracking;
    if (tracked_.ok) flags |= telemetry_flag::track_ok;
    rec.track_source = static_cast<std::int32_t>(tracked_.source);
    if (tracked_.source != control::TrackSource::none) {
      rec.track_bound_m = tracked_.bound_m;
      rec.track_bound_deg = tracked_.bound_deg;
      put_pose(tracked_.T_cl_marker, rec.track_t_m, rec.track_q_wxyz);
    }
  }
  if (t.out.errors_valid) {
    rec.dock_lateral_error_m = t.out.lateral_error_m;
    rec.dock_axial_error_m = t.out.axial_error_m;
    rec.dock_yaw_error_rad = t.out.yaw_error_rad;
    flags |= telemetry_flag::dock_errors_valid;
  }
  if (t.out.servo_active) {
    for (int i = 0; i < 6; ++i) rec.pose_error[i] = servo_.error()[i];
  }
  for (int i = 0; i < 6; ++i) rec.wrench_body[i] = t.wrench[i];
  const control::DisturbanceEstimate& current = servo_.disturbance();
  rec.push_est_n = {-current.wrench_body()[0], -current.wrench_body()[1]};
  if (current.settled()) flags |= telemetry_flag::current_settled;
  rec.thruster_count = static_cast<std::int32_t>(command_.count);
  for (std::size_t i = 0; i < command_.count && i < hal::kMaxThrusters; ++i) {
    rec.thruster_cmd[i] = command_.thrust_fraction[i];
  }
  rec.bus_status = static_cast<std::int32_t>(bus_status_);
  if (armed_) flags |= telemetry_flag::armed;
  if (failsafe_.tripped()) flags |= telemetry_flag::failsafe;
  if (operator_hold_) flags |= telemetry_flag::operator_hold;
  rec.flags |= flags;
}

}  // namespace rovctl::app
