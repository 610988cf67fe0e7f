// ArduSub's pilot path on the simulated vehicle: arming, pilot axes to wrench, stabilise, mixer.
#include "hal/mock/mock_ardusub.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace rovctl::hal::mock {

namespace {
constexpr double kGravityMps2 = 9.80665;
}  // namespace

MockArdusub::MockArdusub(SimulatedWorld& world, const MockArdusubParams& params)
    : world_(world), params_(params) {
  const ThrusterLayout& layout = world.vehicle().thrusters;
  const Eigen::Matrix<double, 6, Eigen::Dynamic> b = layout.configuration_matrix();
  count_ = std::min(layout.thrusters.size(), kMaxThrusters);
  const Eigen::MatrixXd pinv = b.completeOrthogonalDecomposition().pseudoInverse();
  for (std::size_t i = 0; i < count_; ++i) {
    pinv_.row(static_cast<Eigen::Index>(i)) = pinv.row(static_cast<Eigen::Index>(i));
    max_forward_n_[i] = layout.thrusters[i].max_forward_n;
    max_reverse_n_[i] = layout.thrusters[i].max_reverse_n;
    channel_[i] = std::clamp<std::size_t>(static_cast<std::size_t>(layout.thrusters[i].channel), 0,
                                          kMaxThrusters - 1);
  }
  command_.count = count_;
  // Full stick along one axis: the mixer's solution for a unit wrench, scaled until the first
  // thruster saturates. Heave's pilot axis is up, body z down.
  const std::array<std::pair<int, double>, 4> axes = {{{0, 1.0}, {1, 1.0}, {2, -1.0}, {5, 1.0}}};
  for (std::size_t a = 0; a < axes.size(); ++a) {
    Eigen::Matrix<double, 6, 1> unit = Eigen::Matrix<double, 6, 1>::Zero();
    unit(axes[a].first) = axes[a].second;
    double worst = 0.0;
    for (std::size_t i = 0; i < count_; ++i) {
      const double t = pinv_.row(static_cast<Eigen::Index>(i)).dot(unit);
      worst = std::max(worst, std::abs(t) / (t >= 0.0 ? max_forward_n_[i] : max_reverse_n_[i]));
    }
    full_stick_(static_cast<Eigen::Index>(a)) = worst > 0.0 ? 1.0 / worst : 0.0;
  }
}

bool MockArdusub::arm(bool armed, std::chrono::nanoseconds now) {
  armed_ = armed;
  if (armed) {
    // Arming restarts the pilot-input timer and clears a past pilot failsafe.
    last_input_ = now;
    pilot_failsafe_ = false;
  } else {
    world_.neutral_thrusters();
  }
  return true;
}

void MockArdusub::pilot_input(const PilotAxes& axes, std::chrono::nanoseconds now) {
  axes_.x = std::clamp(axes.x, -1000, 1000);
  axes_.y = std::clamp(axes.y, -1000, 1000);
  axes_.z = std::clamp(axes.z, 0, 1000);
  axes_.r = std::clamp(axes.r, -1000, 1000);
  last_input_ = now;
}

void MockArdusub::rc_override(const std::array<std::uint16_t, 18>& channels_us,
                              std::chrono::nanoseconds now) {
  override_us_ = channels_us;
  override_seen_ = true;
  last_override_ = now;
  last_input_ = now;
}

void MockArdusub::mix(const Eigen::Matrix<double, 6, 1>& wrench, ThrusterCommand& out) const {
  out.count = count_;
  std::array<double, kMaxThrusters> f{};
  double worst = 0.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const double t = pinv_.row(static_cast<Eigen::Index>(i)).dot(wrench);
    f[i] = t / (t >= 0.0 ? max_forward_n_[i] : max_reverse_n_[i]);
    worst = std::max(worst, std::abs(f[i]));
  }
  const double scale = worst > 1.0 ? 1.0 / worst : 1.0;
  // The bus (and the ESCs behind ArduSub's outputs) is indexed by channel.
  for (std::size_t i = 0; i < count_; ++i) out.thrust_fraction[channel_[i]] = f[i] * scale;
}

void MockArdusub::update(std::chrono::nanoseconds now) {
  if (armed_ &&
      now - last_input_ > std::chrono::duration<double, std::milli>(params_.pilot_timeout_ms)) {
    // FS_PILOT_INPUT 2: neutral and disarm, once per loss.
    pilot_failsafe_ = true;
    armed_ = false;
  }
  demanded_.setZero();
  if (override_seen_ && now - last_override_ <= std::chrono::duration<double, std::milli>(
                                                    params_.rc_override_time_ms)) {
    // Passthrough: the ESC on output c reads RCIN c+1 (1100-1900 us, 1500 neutral). A released
    // or ignored channel (0, 65535) holds nothing in the mock: neutral.
    command_.count = count_;
    for (std::size_t c = 0; c < count_; ++c) {
      const int us = override_us_[c];
      command_.thrust_fraction[c] =
          us >= 1000 && us <= 2000 ? std::clamp((us - 1500) / 400.0, -1.0, 1.0) : 0.0;
    }
    world_.command_thrusters(command_);
    return;
  }
  if (!armed_) {
    command_ = ThrusterCommand{};
    command_.count = count_;
    world_.neutral_thrusters();
    return;
  }
  const double g = params_.pilot_gain / 1000.0;
  demanded_(0) = axes_.x * g * full_stick_(0);
  demanded_(1) = axes_.y * g * full_stick_(1);
  demanded_(2) = -(axes_.z - 500) * 2.0 * g * full_stick_(2);  // throttle up = body -z
  demanded_(5) = axes_.r * g * full_stick_(3);
  if (mode_ != kArdusubModeManual) {
    // Stabilise: roll and pitch held at zero on the AHRS's attitude.
    const VehicleState& s = world_.state();
    // Roll and pitch from where world-down points in the body (no Euler-angle branch flips).
    const Eigen::Vector3d down_body = s.q_world_body.conjugate() * Eigen::Vector3d::UnitZ();
    const double roll = std::atan2(down_body.y(), down_body.z());
    const double pitch = -std::asin(std::clamp(down_body.x(), -1.0, 1.0));
    const Eigen::Vector3d w = s.omega_body_radps();
    demanded_(3) = -params_.level_kp_nm_per_rad * roll - params_.level_kd_nms_per_rad * w.x();
    demanded_(4) = -params_.level_kp_nm_per_rad * pitch - params_.level_kd_nms_per_rad * w.y();
  }
  mix(demanded_, command_);
  world_.command_thrusters(command_);
}

Eigen::Quaterniond MockArdusub::q_ned_body() const { return world_.state().q_world_body; }

Eigen::Vector3d MockArdusub::omega_body_radps() const { return world_.state().omega_body_radps(); }

double MockArdusub::pressure_hpa() const {
  const double depth_m = world_.state().position_world_m.z();
  return params_.surface_pressure_hpa +
         depth_m * params_.water_density_kg_m3 * kGravityMps2 / 100.0;
}

double MockArdusub::battery_voltage_v() const { return world_.charge().battery_voltage_v; }

int MockArdusub::battery_remaining_pct() const {
  return static_cast<int>(std::lround(100.0 * std::clamp(world_.charge().soc_fraction, 0.0, 1.0)));
}

}  // namespace rovctl::hal::mock
