// Fixed-step integration of the vehicle in the current, the station's contact, docking
// detection and the pose history that the latency of the mock cameras draws on.
#include "hal/mock/simulated_world.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "hal/model/pose.hpp"

namespace rovctl::hal::mock {

namespace {

double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

double wrap_pi(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

}  // namespace

SimulatedWorld::SimulatedWorld(const SimParams& params, const VehicleGeometry& vehicle,
                               const DockingStation& station)
    : params_(params),
      vehicle_(vehicle),
      station_(station),
      dynamics_(params.dynamics),
      thrusters_(vehicle.thrusters, params.thrusters),
      current_(params.current, 0),
      battery_(params.recharge.battery),
      charger_(params.recharge.charger) {
  if (!(params.integration_step_ms > 0.0)) {
    throw std::invalid_argument("sim.integration_step_ms must be positive");
  }
  step_ns_ = std::max<std::int64_t>(1000, std::llround(params.integration_step_ms * 1e6));
  T_world_marker_ = station_T_world_marker(params.station);
  T_marker_world_ = T_world_marker_.inverse();
  T_body_cl_ = vehicle.T_body_cl();
  thrusters_.set_faults(params.faults);

  const double history_ms = params.camera.latency_ms + 250.0;
  history_.resize(static_cast<std::size_t>(std::ceil(history_ms / params.integration_step_ms)) + 4);

  // A default start: aligned, 1 m short of the docked pose.
  VehicleState start;
  const Eigen::Isometry3d docked = docked_T_world_body();
  start.q_world_body = Eigen::Quaterniond(docked.linear());
  start.position_world_m = docked.translation() - 1.0 * T_world_marker_.linear().col(2);
  reset(start, params.current.mean_world_mps, 0);
}

void SimulatedWorld::reset(const VehicleState& initial,
                           const Eigen::Vector3d& current_mean_world_mps, std::uint64_t seed) {
  state_ = initial;
  state_.q_world_body.normalize();
  current_.set_mean_world_mps(current_mean_world_mps);
  current_.reset(seed);
  thrusters_.reset();
  time_ns_.store(0);
  docking_ = DockingTruth{};
  // The starting SoC from its own generator: the trial's other draws stay as they were.
  std::mt19937_64 soc_rng(seed ^ 0x2545f4914f6cdd1dULL);
  const auto& r = params_.recharge;
  battery_.reset(std::uniform_real_distribution<double>(
      r.initial_soc_min, std::max(r.initial_soc_min, r.initial_soc_max))(soc_rng));
  charge_ = ChargeTruth{};
  charge_.soc_fraction = battery_.soc_fraction();
  charge_.battery_voltage_v = battery_.voltage_v();
  charger_failed_ = false;
  first_seated_ns_ = seated_since_ns_ = knock_until_ns_ = -1;
  knocks_ = 0;
  surge_last_world_mps_.setZero();
  history_count_ = 0;
  history_head_ = 0;
  update_docking();
  record();
}

Eigen::Isometry3d SimulatedWorld::docked_T_world_body() const {
  const Eigen::Isometry3d T_cl_marker =
      docked_T_cl_marker(T_body_cl_, vehicle_.probe_tip_body_m, station_);
  return T_world_marker_ * (T_body_cl_ * T_cl_marker).inverse();
}

void SimulatedWorld::command_thrusters(const ThrusterCommand& command) {
  thrusters_.command(command, seconds(time_ns_.load()));
}

void SimulatedWorld::neutral_thrusters() { thrusters_.neutral(seconds(time_ns_.load())); }

void SimulatedWorld::step_to(std::chrono::nanoseconds t) {
  const std::int64_t target = t.count();
  while (time_ns_.load() < target) {
    substep(std::min(step_ns_, target - time_ns_.load()));
  }
}

Eigen::Vector3d SimulatedWorld::contact_force_world(const VehicleState& s, bool& touching) const {
  touching = false;
  const Eigen::Matrix3d R = s.q_world_body.toRotationMatrix();
  const Eigen::Vector3d& tip = vehicle_.probe_tip_body_m;
  const Eigen::Vector3d tip_marker = T_marker_world_ * (s.position_world_m + R * tip);
  const Eigen::Vector3d d = tip_marker - station_.socket_marker_m;
  // Outside the socket the face (the plane of the socket mouth) stops the probe; inside, the
  // socket bottom at the capture depth does.
  const ContactParams& c = params_.contact;
  const double lateral = std::hypot(d.x(), d.y());
  // The wall's radius at this depth: the funnel narrowing to the bore at the capture depth.
  const double depth = std::clamp(d.z() / std::max(1e-6, station_.capture_depth_m), 0.0, 1.0);
  const double wall_radius_m =
      c.lateral_tolerance_m - depth * std::max(0.0, c.lateral_tolerance_m - c.bore_radius_m);
  const bool walled = c.socket_wall && d.z() > 0.0 && lateral > wall_radius_m &&
                      lateral <= c.lateral_tolerance_m + c.wall_band_m;
  const bool in_socket = lateral <= c.lateral_tolerance_m || walled;
  const bool on_face =
      std::abs(d.x()) <= c.face_half_size_m && std::abs(d.y()) <= c.face_half_size_m;
  if (!in_socket && !on_face) return Eigen::Vector3d::Zero();  // beside the station
  const double penetration = in_socket ? d.z() - station_.capture_depth_m : d.z();
  const Eigen::Vector3d tip_velocity_world =
      R * (s.velocity_body_mps() + s.omega_body_radps().cross(tip));
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  if (walled) {
    touching = true;
    const Eigen::Vector3d out_world =
        T_world_marker_.linear() * Eigen::Vector3d(d.x(), d.y(), 0.0) / lateral;
    const double push = c.stiffness_npm * (lateral - wall_radius_m) +
                        c.damping_nspm * tip_velocity_world.dot(out_world);
    f -= std::max(0.0, push) * out_world;
  }
  if (penetration <= 0.0) return f;
  touching = true;
  const Eigen::Vector3d axis_world = T_world_marker_.linear().col(2);
  const double push =
      c.stiffness_npm * penetration + c.damping_nspm * tip_velocity_world.dot(axis_world);
  return f - std::max(0.0, push) * axis_world;
}

double SimulatedWorld::since_first_seated_s() const {
  return first_seated_ns_ < 0 ? -1.0 : seconds(time_ns_.load() - first_seated_ns_);
}

Eigen::Vector3d SimulatedWorld::knock_force_world() {
  const FaultInjection& f = params_.faults;
  const std::int64_t now = time_ns_.load();
  if (f.knock_after_seated_s >= 0.0 && knocks_ < f.knock_count && knock_until_ns_ < now &&
      seated_since_ns_ >= 0 && seconds(now - seated_since_ns_) >= f.knock_after_seated_s) {
    knock_until_ns_ = now + std::llround(f.knock_duration_s * 1e9);
    ++knocks_;
  }
  if (now >= knock_until_ns_) return Eigen::Vector3d::Zero();
  return -T_world_marker_.linear().col(2) * f.knock_force_n;  // out of the socket
}

Eigen::Vector3d SimulatedWorld::surge_world_mps() const {
  const FaultInjection& f = params_.faults;
  if (!seated_fault_active(f.surge_after_seated_s)) return Eigen::Vector3d::Zero();
  const double rise = since_first_seated_s() - f.surge_after_seated_s;
  const double fraction = f.surge_ramp_s > 0.0 ? std::min(1.0, rise / f.surge_ramp_s) : 1.0;
  return T_world_marker_.linear().col(0) * f.surge_mps * fraction;  // across the docking axis
}

void SimulatedWorld::substep(std::int64_t dt_ns) {
  const double dt = seconds(dt_ns);
  const double t_end = seconds(time_ns_.load() + dt_ns);
  thrusters_.step(t_end, dt);
  current_.step(dt);
  const Eigen::Vector3d surge = surge_world_mps();
  const Eigen::Vector3d surge_rate = (surge - surge_last_world_mps_) / dt;
  surge_last_world_mps_ = surge;
  if (docking_.docked && params_.contact.latch_on_dock) {
    state_.nu_body.setZero();  // the latch holds the vehicle
  } else {
    bool touching = false;
    const Eigen::Vector3d f_world = contact_force_world(state_, touching);
    Eigen::Matrix<double, 6, 1> tau = thrusters_.wrench_body();
    if (touching) {
      const Eigen::Vector3d f_body = state_.q_world_body.conjugate() * f_world;
      tau.head<3>() += f_body;
      tau.tail<3>() += vehicle_.probe_tip_body_m.cross(f_body);
      docking_.max_contact_force_n = std::max(docking_.max_contact_force_n, f_world.norm());
    }
    tau.head<3>() += state_.q_world_body.conjugate() * knock_force_world();
    dynamics_.step(state_, tau, current_.velocity_world_mps() + surge,
                   current_.rate_world_mps2() + surge_rate, dt);
  }
  time_ns_.fetch_add(dt_ns);
  update_docking();
  update_charge(dt);
  record();
}

void SimulatedWorld::update_docking() {
  const Eigen::Matrix3d R = state_.q_world_body.toRotationMatrix();
  const Eigen::Vector3d tip_marker =
      T_marker_world_ * (state_.position_world_m + R * vehicle_.probe_tip_body_m);
  const Eigen::Vector3d d = tip_marker - station_.socket_marker_m;
  docking_.axial_distance_m = -d.z();
  docking_.lateral_error_m = std::hypot(d.x(), d.y());
  const Eigen::Vector3d body_x = R.col(0);
  const Eigen::Vector3d axis = T_world_marker_.linear().col(2);
  docking_.misalignment_rad = std::acos(std::clamp(body_x.dot(axis), -1.0, 1.0));
  docking_.yaw_error_rad =
      wrap_pi(std::atan2(body_x.y(), body_x.x()) - std::atan2(axis.y(), axis.x()));
  bool touching = false;
  contact_force_world(state_, touching);
  docking_.contact = touching;
  const bool centred = docking_.lateral_error_m <= params_.contact.lateral_tolerance_m;
  if (touching && !centred) docking_.collided = true;
  const double seat_radius_m = params_.contact.lateral_tolerance_m +
                               (params_.contact.socket_wall ? params_.contact.wall_band_m : 0.0);
  docking_.seated = docking_.lateral_error_m <= seat_radius_m &&
                    d.z() >= station_.capture_depth_m - params_.recharge.charger.pin_engage_m &&
                    docking_.misalignment_rad <= params_.contact.angle_tolerance_deg * kRadPerDeg;
  if (docking_.seated) {
    if (first_seated_ns_ < 0) first_seated_ns_ = time_ns_.load();
    if (seated_since_ns_ < 0) seated_since_ns_ = time_ns_.load();
  } else {
    seated_since_ns_ = -1;
  }
  if (!docking_.docked && centred && d.z() >= station_.capture_depth_m &&
      docking_.misalignment_rad <= params_.contact.angle_tolerance_deg * kRadPerDeg) {
    docking_.docked = true;
    docking_.docked_at = time();
  }
}

void SimulatedWorld::update_charge(double dt_s) {
  if (FaultInjection::active(params_.faults.charger_fails_at_s, time())) charger_failed_ = true;
  const bool seated = docking_.seated;
  const double scale = seated ? params_.recharge.seated_time_scale : 1.0;
  const double battery_dt_s = dt_s * scale;
  const double thruster_wh_before = battery_.thruster_wh();
  battery_.step(battery_dt_s, charger_.offer_a(seated, charger_failed_),
                thruster_power_w(thrusters_, params_.recharge.battery.thruster_power_w_per_n1_5));
  if (seated) {
    charge_.seated_thruster_wh += battery_.thruster_wh() - thruster_wh_before;
    charge_.seated_s += dt_s;
  }
  charge_.battery_time_s += battery_dt_s;
  charge_.soc_fraction = battery_.soc_fraction();
  charge_.battery_voltage_v = battery_.voltage_v();
  charge_.charge_current_a = battery_.charge_current_a();
  charge_.charged_wh = battery_.charged_wh();
  charge_.thruster_wh = battery_.thruster_wh();
}

void SimulatedWorld::record() {
  history_head_ = history_count_ == 0 ? 0 : (history_head_ + 1) % history_.size();
  history_count_ = std::min(history_count_ + 1, history_.size());
  Sample& s = history_[history_head_];
  s.t_ns = time_ns_.load();
  s.position = state_.position_world_m;
  s.q = state_.q_world_body;
}

Eigen::Isometry3d SimulatedWorld::T_world_body_at(std::chrono::nanoseconds t) const {
  const std::int64_t t_ns = t.count();
  const std::size_t n = history_.size();
  // Walk back from the newest to the first sample not after t; interpolate towards the next.
  std::size_t newer = history_head_;
  for (std::size_t k = 0; k < history_count_; ++k) {
    const std::size_t i = (history_head_ + n - k) % n;
    const Sample& s = history_[i];
    if (s.t_ns <= t_ns || k + 1 == history_count_) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      if (k == 0 || s.t_ns >= t_ns) {
        T.linear() = s.q.toRotationMatrix();
        T.translation() = s.position;
        return T;
      }
      const Sample& b = history_[newer];
      const double a = static_cast<double>(t_ns - s.t_ns) / static_cast<double>(b.t_ns - s.t_ns);
      T.linear() = s.q.slerp(a, b.q).toRotationMatrix();
      T.translation() = (1.0 - a) * s.position + a * b.position;
      return T;
    }
    newer = i;
  }
  return state_.T_world_body();
}

Eigen::Isometry3d SimulatedWorld::T_cl_marker(const Eigen::Isometry3d& T_world_body) const {
  return (T_world_body * T_body_cl_).inverse() * T_world_marker_;
}

Eigen::Isometry3d SimulatedWorld::T_cl_marker_at(std::chrono::nanoseconds t) const {
  return T_cl_marker(T_world_body_at(t));
}

WorldTruth SimulatedWorld::truth() const {
  WorldTruth w;
  w.time = time();
  w.T_world_body = state_.T_world_body();
  w.velocity_body_mps = state_.velocity_body_mps();
  w.omega_body_radps = state_.omega_body_radps();
  w.current_world_mps = current_.velocity_world_mps() + surge_world_mps();
  w.T_cl_marker = T_cl_marker(w.T_world_body);
  w.thrust_wrench_body = thrusters_.wrench_body();
  w.docking = docking_;
  return w;
}

}  // namespace rovctl::hal::mock
