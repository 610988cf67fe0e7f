// Thruster allocation: a weighted pseudo-inverse of the effectiveness matrix, computed at start-up
// and again, without allocating, when a thruster fails and is removed (as PX4's ControlAllocator
// does); under saturation heave, roll, pitch and yaw are kept whole and surge and sway get what
// the thrusters have left.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>

#include "control/control_params.hpp"
#include "control/thruster_effectiveness.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::control {

// n x 6: thrust [N] per unit of each wrench axis.
using MixMatrix = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, hal::kMaxThrusters, 6>;

class ControlAllocator {
 public:
  // Throws std::invalid_argument for a bad layout or a weight naming no thruster.
  ControlAllocator(const hal::ThrusterLayout& layout, const AllocationParams& params);

  // Thruster commands in [-1, 1] for the wrench, indexed by bus channel (count = highest
  // channel + 1, unused channels neutral). When a thruster would saturate, heave, roll, pitch
  // and yaw are kept and surge and sway scaled by the common share the thrusters leave them;
  // when the kept axes alone are beyond the thrusters, they are scaled by one factor (keeping
  // their direction) and surge and sway get nothing. Returns the smallest share of the wrench
  // achieved along any axis it asks for: 1 when no thruster saturates. A non-finite wrench
  // gives neutral commands and 0. No allocation.
  double allocate(const Wrench& wrench_body, hal::ThrusterCommand& command) const;

  // The thrusts [N] before saturation (min weighted-norm solution). No allocation.
  ThrustVector thrust_for(const Wrench& wrench_body) const { return mix_ * wrench_body; }
  // The largest force (N) or moment (N m) the active thrusters can make along each body axis
  // alone, in the weaker of its two directions. No allocation.
  Wrench axis_capacity() const;
  // Sets every channel of the layout to neutral.
  void neutral(hal::ThrusterCommand& command) const;

  // Takes thruster i (layout index) out of the allocation: its command stays neutral and the
  // pseudo-inverse is recomputed over the others. When they can no longer produce roll and pitch
  // independently, those axes are given up first so x, y, z and yaw stay exact. Returns
  // servo_axes_controllable(). No allocation (it runs in the tick, at the failure).
  bool remove_thruster(std::size_t i);
  bool active(std::size_t i) const { return active_[i]; }
  std::size_t active_count() const;
  // Whether the active thrusters can produce any force in x, y, z and any yaw moment (roll and
  // pitch left free): the axes the visual servo uses.
  bool servo_axes_controllable() const { return servo_axes_controllable_; }

  const ThrusterEffectiveness& effectiveness() const { return effectiveness_; }
  const MixMatrix& mix() const { return mix_; }

 private:
  void compute_mix();
  // The largest |thrust| / limit over the thrusters (over 1: some thruster saturates).
  double busiest(const ThrustVector& thrust) const;
  // The largest share s in [0, 1] of the horizontal thrusts that fits on top of the held ones.
  double horizontal_share(const ThrustVector& held, const ThrustVector& horizontal) const;

  ThrusterEffectiveness effectiveness_;
  MixMatrix mix_;
  std::size_t channel_count_ = 0;
  std::array<double, hal::kMaxThrusters> effort_{};  // W_u, by layout index
  Wrench axis_weights_ = Wrench::Ones();             // W_t
  std::array<bool, hal::kMaxThrusters> active_{};
  bool servo_axes_controllable_ = false;
};

}  // namespace rovctl::control
