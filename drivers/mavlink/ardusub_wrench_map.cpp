// Fractions -> wrench -> MANUAL_CONTROL axes for ArduSub's wrench mode.
#include "drivers/mavlink/ardusub_wrench_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rovctl::drivers {

namespace {

std::int16_t clamp_axis(double value, double low, double high) {
  if (!std::isfinite(value)) return static_cast<std::int16_t>(std::lround((low + high) / 2.0));
  return static_cast<std::int16_t>(std::lround(std::clamp(value, low, high)));
}

}  // namespace

ArdusubWrenchMap::ArdusubWrenchMap(const hal::ThrusterLayout& layout, const ArdusubAxisScale& scale,
                                   double pilot_gain)
    : scale_(scale), pilot_gain_(pilot_gain) {
  if (layout.thrusters.size() > hal::kMaxThrusters) {
    throw std::invalid_argument("ardusub: the layout has more than 8 thrusters");
  }
  const Eigen::Matrix<double, 6, Eigen::Dynamic> b = layout.configuration_matrix();
  count_ = layout.thrusters.size();
  for (std::size_t i = 0; i < count_; ++i) {
    column_per_n_[i] = b.col(static_cast<Eigen::Index>(i));
    max_forward_n_[i] = layout.thrusters[i].max_forward_n;
    max_reverse_n_[i] = layout.thrusters[i].max_reverse_n;
  }
}

Eigen::Matrix<double, 6, 1> ArdusubWrenchMap::wrench(const hal::ThrusterCommand& command) const {
  Eigen::Matrix<double, 6, 1> w = Eigen::Matrix<double, 6, 1>::Zero();
  const std::size_t n = std::min(count_, command.count);
  for (std::size_t i = 0; i < n; ++i) {
    const double f = std::clamp(command.thrust_fraction[i], -1.0, 1.0);
    const double thrust_n = f >= 0.0 ? f * max_forward_n_[i] : f * max_reverse_n_[i];
    w += column_per_n_[i] * thrust_n;
  }
  return w;
}

ArdusubAxes ArdusubWrenchMap::axes(const hal::ThrusterCommand& command) const {
  const Eigen::Matrix<double, 6, 1> w = wrench(command);
  ArdusubAxes a;
  a.x = clamp_axis(1000.0 * w(0) / (scale_.surge_full_n * pilot_gain_), -1000.0, 1000.0);
  a.y = clamp_axis(1000.0 * w(1) / (scale_.sway_full_n * pilot_gain_), -1000.0, 1000.0);
  // Body z points down; ArduSub's throttle climbs above 500, its full range is +-500.
  a.z = clamp_axis(500.0 - 500.0 * w(2) / (scale_.heave_full_n * pilot_gain_), 0.0, 1000.0);
  a.r = clamp_axis(1000.0 * w(5) / (scale_.yaw_full_nm * pilot_gain_), -1000.0, 1000.0);
  return a;
}

}  // namespace rovctl::drivers
