// Weighted pseudo-inverse allocation with direction-preserving saturation.
#include "control/control_allocation_pseudo_inverse.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rovctl::control {

ControlAllocator::ControlAllocator(const hal::ThrusterLayout& layout,
                                   const AllocationParams& params)
    : effectiveness_(layout, params.deadband) {
  const std::size_t n = effectiveness_.count();
  // Effort weights W_u (min f' W_u f) and axis weights W_t (min |W_t^1/2 (B f - tau)|):
  // f = W_u^-1/2 pinv(W_t^1/2 B W_u^-1/2) W_t^1/2 tau, exact whenever B has full row rank.
  Eigen::VectorXd effort = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(n));
  for (const ThrusterWeight& w : params.thruster_weights) {
    const auto it = std::find_if(layout.thrusters.begin(), layout.thrusters.end(),
                                 [&w](const hal::Thruster& t) { return t.name == w.thruster; });
    if (it == layout.thrusters.end()) {
      throw std::invalid_argument("control.allocation.thruster_weights: no thruster named '" +
                                  w.thruster + "'");
    }
    if (!(w.weight > 0.0)) {
      throw std::invalid_argument("control.allocation.thruster_weights: weight of '" + w.thruster +
                                  "' must be positive");
    }
    effort[it - layout.thrusters.begin()] = w.weight;
  }
  Wrench axis;
  axis << params.axis_weights_force, params.axis_weights_moment;
  if (!(axis.minCoeff() > 0.0)) {
    throw std::invalid_argument("control.allocation: axis weights must be positive");
  }
  const Eigen::VectorXd u_inv_sqrt = effort.cwiseSqrt().cwiseInverse();
  const Wrench t_sqrt = axis.cwiseSqrt();
  const Eigen::MatrixXd B = effectiveness_.matrix();
  const Eigen::MatrixXd scaled = t_sqrt.asDiagonal() * B * u_inv_sqrt.asDiagonal();
  const Eigen::MatrixXd pinv = scaled.completeOrthogonalDecomposition().pseudoInverse();
  mix_ = u_inv_sqrt.asDiagonal() * pinv * t_sqrt.asDiagonal();

  for (std::size_t i = 0; i < n; ++i) {
    channel_count_ =
        std::max(channel_count_, static_cast<std::size_t>(effectiveness_.channel(i)) + 1);
  }
}

void ControlAllocator::neutral(hal::ThrusterCommand& command) const {
  command.thrust_fraction.fill(0.0);
  command.count = channel_count_;
}

double ControlAllocator::allocate(const Wrench& wrench_body, hal::ThrusterCommand& command) const {
  neutral(command);
  if (!wrench_body.allFinite()) return 0.0;
  const ThrustVector thrust = mix_ * wrench_body;
  const std::size_t n = effectiveness_.count();
  double worst = 0.0;  // largest |thrust| / limit over the thrusters
  for (std::size_t i = 0; i < n; ++i) {
    const double f = thrust[static_cast<Eigen::Index>(i)];
    worst = std::max(worst, std::abs(f) / effectiveness_.limit_n(i, f));
  }
  // One common scale for all thrusters keeps the wrench's direction; the clip after it only
  // removes rounding.
  const double scale = worst > 1.0 ? 1.0 / worst : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = thrust[static_cast<Eigen::Index>(i)] * scale;
    command.thrust_fraction[static_cast<std::size_t>(effectiveness_.channel(i))] =
        std::clamp(effectiveness_.command_for_thrust(i, f), -1.0, 1.0);
  }
  return scale;
}

}  // namespace rovctl::control
