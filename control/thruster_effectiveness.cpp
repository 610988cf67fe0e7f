// Effectiveness matrix from the thruster layout, with its sanity checks.
#include "control/thruster_effectiveness.hpp"

#include <stdexcept>
#include <string>

namespace rovctl::control {

ThrusterEffectiveness::ThrusterEffectiveness(const hal::ThrusterLayout& layout, double deadband)
    : deadband_(deadband) {
  if (!(deadband >= 0.0 && deadband < 1.0)) {
    throw std::invalid_argument("thruster deadband " + std::to_string(deadband) +
                                " outside [0, 1)");
  }
  const auto& thrusters = layout.thrusters;
  if (thrusters.empty() || thrusters.size() > hal::kMaxThrusters) {
    throw std::invalid_argument("thruster layout: " + std::to_string(thrusters.size()) +
                                " thrusters (1 to " + std::to_string(hal::kMaxThrusters) +
                                " supported)");
  }
  count_ = thrusters.size();
  std::array<bool, hal::kMaxThrusters> channel_used{};
  for (std::size_t i = 0; i < count_; ++i) {
    const hal::Thruster& t = thrusters[i];
    if (!(t.direction_body.norm() > 1e-6) || !t.direction_body.allFinite()) {
      throw std::invalid_argument("thruster '" + t.name + "': direction is zero or not finite");
    }
    if (t.channel < 0 || t.channel >= static_cast<int>(hal::kMaxThrusters)) {
      throw std::invalid_argument("thruster '" + t.name + "': channel " +
                                  std::to_string(t.channel) + " is off the bus");
    }
    if (channel_used[static_cast<std::size_t>(t.channel)]) {
      throw std::invalid_argument("thruster '" + t.name + "': channel " +
                                  std::to_string(t.channel) + " used twice");
    }
    if (!(t.max_forward_n > 0.0) || !(t.max_reverse_n > 0.0)) {
      throw std::invalid_argument("thruster '" + t.name + "': maximum thrust must be positive");
    }
    channel_used[static_cast<std::size_t>(t.channel)] = true;
    channel_[i] = t.channel;
    max_forward_n_[i] = t.max_forward_n;
    max_reverse_n_[i] = t.max_reverse_n;
  }
  // hal's configuration matrix is already per newton of thrust along each thruster's axis.
  matrix_ = layout.configuration_matrix();
}

Wrench ThrusterEffectiveness::wrench_for_command(const hal::ThrusterCommand& command) const {
  Wrench w = Wrench::Zero();
  for (std::size_t i = 0; i < count_; ++i) {
    const auto ch = static_cast<std::size_t>(channel_[i]);
    const double thrust =
        ch < command.count ? thrust_for_command(i, command.thrust_fraction[ch]) : 0.0;
    w += matrix_.col(static_cast<Eigen::Index>(i)) * thrust;
  }
  return w;
}

}  // namespace rovctl::control
