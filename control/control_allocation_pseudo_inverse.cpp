// Weighted pseudo-inverse allocation; saturation keeps heave and the moments, scaling surge and
// sway.
#include "control/control_allocation_pseudo_inverse.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
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
  for (std::size_t i = 0; i < n; ++i) {
    effort_[i] = effort[static_cast<Eigen::Index>(i)];
    active_[i] = true;
  }
  axis_weights_ = axis;
  compute_mix();

  for (std::size_t i = 0; i < n; ++i) {
    channel_count_ =
        std::max(channel_count_, static_cast<std::size_t>(effectiveness_.channel(i)) + 1);
  }
}

namespace {

using Full = Eigen::Matrix<double, 6, hal::kMaxThrusters>;

// Singular values above this fraction of the largest count towards the rank.
constexpr double kRankTolerance = 1e-9;

template <int Rows>
int rank_of(const Eigen::Matrix<double, Rows, static_cast<int>(hal::kMaxThrusters)>& m) {
  const Eigen::JacobiSVD<Eigen::Matrix<double, Rows, static_cast<int>(hal::kMaxThrusters)>> svd(m);
  const auto& sigma = svd.singularValues();
  int rank = 0;
  for (Eigen::Index k = 0; k < sigma.size(); ++k) {
    if (sigma[k] > kRankTolerance * sigma[0] && sigma[k] > 0.0) ++rank;
  }
  return rank;
}

}  // namespace

void ControlAllocator::compute_mix() {
  // Effort weights W_u (min f' W_u f) and axis weights W_t (min |W_t^1/2 (B f - tau)|):
  // f = W_u^-1/2 pinv(W_t^1/2 B W_u^-1/2) W_t^1/2 tau, exact whenever B has full row rank. A
  // removed thruster is a zero column, so it gets no thrust. Fixed-size throughout: no heap.
  const std::size_t n = effectiveness_.count();
  Full B = Full::Zero();
  Eigen::Matrix<double, hal::kMaxThrusters, 1> u_inv_sqrt =
      Eigen::Matrix<double, hal::kMaxThrusters, 1>::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    if (!active_[i]) continue;
    B.col(static_cast<Eigen::Index>(i)) = effectiveness_.matrix().col(static_cast<Eigen::Index>(i));
    u_inv_sqrt[static_cast<Eigen::Index>(i)] = 1.0 / std::sqrt(effort_[i]);
  }
  Eigen::Matrix<double, 4, hal::kMaxThrusters> servo_rows;
  servo_rows << B.topRows<3>(), B.row(5);
  servo_axes_controllable_ = rank_of<4>(servo_rows) == 4;
  Wrench t_sqrt = axis_weights_.cwiseSqrt();
  if (active_count() < n && rank_of<6>(B) < 6) {
    // A failure coupled roll and pitch to the servo's axes: let them go rather than x, y, z, yaw
    // (the vehicle is passively stable in roll and pitch).
    t_sqrt[3] *= 1e-3;
    t_sqrt[4] *= 1e-3;
  }
  const Full scaled = t_sqrt.asDiagonal() * B * u_inv_sqrt.asDiagonal();
  const Eigen::JacobiSVD<Full> svd(scaled, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Wrench& sigma = svd.singularValues();
  Wrench sigma_inv = Wrench::Zero();
  for (Eigen::Index k = 0; k < 6; ++k) {
    if (sigma[k] > kRankTolerance * sigma[0] && sigma[k] > 0.0) sigma_inv[k] = 1.0 / sigma[k];
  }
  const Eigen::Matrix<double, hal::kMaxThrusters, 6> pinv =
      svd.matrixV().leftCols<6>() * sigma_inv.asDiagonal() * svd.matrixU().transpose();
  const Eigen::Matrix<double, hal::kMaxThrusters, 6> mix =
      u_inv_sqrt.asDiagonal() * pinv * t_sqrt.asDiagonal();
  mix_ = mix.topRows(static_cast<Eigen::Index>(n));
}

bool ControlAllocator::remove_thruster(std::size_t i) {
  if (i < effectiveness_.count() && active_[i]) {
    active_[i] = false;
    compute_mix();
  }
  return servo_axes_controllable_;
}

std::size_t ControlAllocator::active_count() const {
  std::size_t c = 0;
  for (std::size_t i = 0; i < effectiveness_.count(); ++i) c += active_[i] ? 1 : 0;
  return c;
}

void ControlAllocator::neutral(hal::ThrusterCommand& command) const {
  command.thrust_fraction.fill(0.0);
  command.count = channel_count_;
}

double ControlAllocator::busiest(const ThrustVector& thrust) const {
  double worst = 0.0;  // largest |thrust| / limit over the thrusters
  for (std::size_t i = 0; i < effectiveness_.count(); ++i) {
    const double f = thrust[static_cast<Eigen::Index>(i)];
    worst = std::max(worst, std::abs(f) / effectiveness_.limit_n(i, f));
  }
  return worst;
}

double ControlAllocator::horizontal_share(const ThrustVector& held,
                                          const ThrustVector& horizontal) const {
  // Thruster i takes held_i + s horizontal_i; the largest s in [0, 1] that keeps every thruster
  // within its limit in the direction it is pushed.
  double s = 1.0;
  for (std::size_t i = 0; i < effectiveness_.count(); ++i) {
    const double a = held[static_cast<Eigen::Index>(i)];
    const double b = horizontal[static_cast<Eigen::Index>(i)];
    if (b > 0.0) s = std::min(s, (effectiveness_.max_forward_n(i) - a) / b);
    if (b < 0.0) s = std::min(s, (a + effectiveness_.max_reverse_n(i)) / -b);
  }
  return std::clamp(s, 0.0, 1.0);
}

double ControlAllocator::allocate(const Wrench& wrench_body, hal::ThrusterCommand& command) const {
  neutral(command);
  if (!wrench_body.allFinite()) return 0.0;
  ThrustVector thrust = mix_ * wrench_body;
  double fraction = 1.0;
  if (busiest(thrust) > 1.0) {
    // Heave, roll, pitch and yaw first, surge and sway with what is left (as ArduSub's mixer
    // gives up throttle and forward before attitude): scaling the whole wrench against a current
    // that takes the horizontal thrusters would also cut the heave and yaw that hold the
    // stand-off and the heading, and the vehicle bobs and swings while it holds.
    Wrench held_wrench = wrench_body;
    held_wrench[0] = held_wrench[1] = 0.0;
    const ThrustVector held = mix_ * held_wrench;
    const ThrustVector horizontal = thrust - held;
    const double held_worst = busiest(held);
    if (held_worst >= 1.0) {
      // Those alone are beyond the thrusters: their common scale keeps their direction.
      thrust = held / held_worst;
      fraction = wrench_body.head<2>().isZero() ? 1.0 / held_worst : 0.0;
    } else {
      fraction = horizontal_share(held, horizontal);
      thrust = held + fraction * horizontal;
    }
  }
  for (std::size_t i = 0; i < effectiveness_.count(); ++i) {
    const double f = thrust[static_cast<Eigen::Index>(i)];
    // The clip only removes rounding.
    command.thrust_fraction[static_cast<std::size_t>(effectiveness_.channel(i))] =
        std::clamp(effectiveness_.command_for_thrust(i, f), -1.0, 1.0);
  }
  return fraction;
}

Wrench ControlAllocator::axis_capacity() const {
  const std::size_t n = effectiveness_.count();
  Wrench capacity = Wrench::Zero();
  for (Eigen::Index axis = 0; axis < 6; ++axis) {
    double weakest = std::numeric_limits<double>::infinity();
    for (const double sign : {1.0, -1.0}) {
      for (std::size_t i = 0; i < n; ++i) {
        const double per_unit = sign * mix_(static_cast<Eigen::Index>(i), axis);
        if (std::abs(per_unit) < 1e-12) continue;
        weakest = std::min(weakest, effectiveness_.limit_n(i, per_unit) / std::abs(per_unit));
      }
    }
    capacity[axis] = std::isfinite(weakest) ? weakest : 0.0;
  }
  return capacity;
}

}  // namespace rovctl::control
