// Thruster response: static map (deadband, saturation, asymmetry), first-order lag, ESC timeout,
// injected thruster failures.
#include "hal/mock/thruster_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rovctl::hal::mock {

ThrusterModel::ThrusterModel(const ThrusterLayout& layout, const ThrusterModelParams& params)
    : p_(params), count_(layout.thrusters.size()) {
  if (count_ > kMaxThrusters) {
    throw std::invalid_argument("thruster model: " + std::to_string(count_) +
                                " thrusters, at most " + std::to_string(kMaxThrusters));
  }
  const Eigen::Matrix<double, 6, Eigen::Dynamic> B = layout.configuration_matrix();
  for (std::size_t i = 0; i < count_; ++i) {
    const Thruster& t = layout.thrusters[i];
    config_.col(static_cast<Eigen::Index>(i)) = B.col(static_cast<Eigen::Index>(i));
    max_forward_n_[i] = t.max_forward_n;
    max_reverse_n_[i] = t.max_reverse_n;
    channel_[i] = t.channel;
  }
}

void ThrusterModel::reset() {
  command_.fill(0.0);
  thrust_n_.fill(0.0);
  last_command_s_ = -1e9;
}

void ThrusterModel::command(const ThrusterCommand& cmd, double time_s) {
  for (std::size_t i = 0; i < count_; ++i) {
    const auto ch = static_cast<std::size_t>(channel_[i]);
    const double c = ch < cmd.count ? cmd.thrust_fraction[ch] : 0.0;
    command_[i] = std::isfinite(c) ? std::clamp(c, -1.0, 1.0) : 0.0;
  }
  last_command_s_ = time_s;
}

void ThrusterModel::neutral(double time_s) {
  command_.fill(0.0);
  last_command_s_ = time_s;
}

double ThrusterModel::static_thrust_n(std::size_t i, double fraction) const {
  const double c = std::clamp(fraction, -1.0, 1.0);
  const double past = (std::abs(c) - p_.deadband) / (1.0 - p_.deadband);
  if (past <= 0.0) return 0.0;
  const double shaped = p_.curve_exponent == 1.0 ? past : std::pow(past, p_.curve_exponent);
  return c > 0.0 ? shaped * max_forward_n_[i] : -shaped * max_reverse_n_[i];
}

void ThrusterModel::step(double time_s, double dt_s) {
  const bool stale = timed_out(time_s);
  const double alpha = p_.time_constant_s > 0.0 ? 1.0 - std::exp(-dt_s / p_.time_constant_s) : 1.0;
  for (std::size_t i = 0; i < count_; ++i) {
    if (failing(faults_.thruster_dead_index, faults_.thruster_dead_at_s, i, time_s)) {
      thrust_n_[i] = 0.0;
      continue;
    }
    if (failing(faults_.thruster_stuck_index, faults_.thruster_stuck_at_s, i, time_s)) continue;
    double target = stale ? 0.0 : static_thrust_n(i, command_[i]);
    if (failing(faults_.thruster_weak_index, faults_.thruster_weak_at_s, i, time_s)) {
      target *= faults_.thruster_weak_fraction;
    }
    thrust_n_[i] += alpha * (target - thrust_n_[i]);
  }
}

void ThrusterModel::set_faults(const FaultInjection& faults) {
  const auto check = [this](const char* key, int index, double at_s) {
    if (at_s >= 0.0 && (index < 0 || static_cast<std::size_t>(index) >= count_)) {
      throw std::invalid_argument(std::string("sim.faults.") + key + ": thruster " +
                                  std::to_string(index) + " of " + std::to_string(count_));
    }
  };
  check("thruster_dead_index", faults.thruster_dead_index, faults.thruster_dead_at_s);
  check("thruster_weak_index", faults.thruster_weak_index, faults.thruster_weak_at_s);
  check("thruster_stuck_index", faults.thruster_stuck_index, faults.thruster_stuck_at_s);
  faults_ = faults;
}

bool ThrusterModel::fault_flagged(std::size_t i, double time_s) const {
  return failing(faults_.thruster_dead_index, faults_.thruster_dead_at_s, i, time_s);
}

Eigen::Matrix<double, 6, 1> ThrusterModel::wrench_body() const {
  Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Zero();
  for (std::size_t i = 0; i < count_; ++i) {
    w += config_.col(static_cast<Eigen::Index>(i)) * thrust_n_[i];
  }
  return w;
}

void describe(ParamVisitor& v, ThrusterModelParams& p) {
  v.param("time_constant_s", p.time_constant_s,
          {"s", 0.0, 2.0, "first-order lag of thrust behind command (0: instantaneous)"});
  v.param("deadband", p.deadband,
          {"-", 0.0, 0.5, "command fraction around neutral that gives no thrust (ESC deadband)"});
  v.param("curve_exponent", p.curve_exponent,
          {"-", 0.5, 3.0, "thrust ~ (command past the deadband)^exponent; 1 = linear"});
  v.param("command_timeout_s", p.command_timeout_s,
          {"s", 0.01, 10.0, "ESCs go neutral when no command arrives for this long"});
}

}  // namespace rovctl::hal::mock
