// The body wrench the allocation asked of the vehicle's thrusters, as ArduSub's pilot axes: what
// lets the allocator's thruster fractions drive ArduSub's own mixer through MANUAL_CONTROL.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

#include "drivers/mavlink/ardusub_params.hpp"
#include "hal/interfaces/thruster_bus.hpp"
#include "hal/model/thruster_layout.hpp"

namespace rovctl::drivers {

// MANUAL_CONTROL's four pilot axes: x, y, r in -1000..1000, z in 0..1000 with 500 neutral.
struct ArdusubAxes {
  std::int16_t x = 0;
  std::int16_t y = 0;
  std::int16_t z = 500;
  std::int16_t r = 0;
  bool operator==(const ArdusubAxes&) const = default;
};

// The geometry (hal's thruster layout) stays apart from the solver: the allocator shares the
// servo's wrench among the vehicle's thrusters as on any bus, and this map rebuilds that wrench
// from the fractions (force = B * thrust) and hands its surge, sway, heave and yaw to ArduSub,
// whose mixer allocates again and whose stabilise loop holds roll and pitch (which it drops).
class ArdusubWrenchMap {
 public:
  // Throws std::invalid_argument when the layout has more thrusters than a bus carries.
  ArdusubWrenchMap(const hal::ThrusterLayout& layout, const ArdusubAxisScale& scale,
                   double pilot_gain);

  // The body wrench [F; M] (body: x fwd, y stbd, z down) the fractions produce. No allocation.
  Eigen::Matrix<double, 6, 1> wrench(const hal::ThrusterCommand& command) const;
  // The axes for the fractions, clamped to MANUAL_CONTROL's ranges. No allocation.
  ArdusubAxes axes(const hal::ThrusterCommand& command) const;

 private:
  std::size_t count_ = 0;
  std::array<Eigen::Matrix<double, 6, 1>, hal::kMaxThrusters> column_per_n_{};
  std::array<double, hal::kMaxThrusters> max_forward_n_{};
  std::array<double, hal::kMaxThrusters> max_reverse_n_{};
  ArdusubAxisScale scale_;
  double pilot_gain_ = 1.0;
};

}  // namespace rovctl::drivers
