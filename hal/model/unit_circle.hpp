// N points evenly around the unit circle, cosine and sine computed once: the silhouette and rim
// walks of the per-frame estimator visit the same angles thousands of times a frame.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace rovctl::hal {

// Point k is at angle 2 pi k / N + start_rad.
template <int N>
class UnitCircle {
 public:
  explicit UnitCircle(double start_rad = 0.0) {
    for (int k = 0; k < N; ++k) {
      const double phi = 2.0 * M_PI * k / N + start_rad;
      points_[k] = Eigen::Vector2d(std::cos(phi), std::sin(phi));
    }
  }
  const Eigen::Vector2d& operator[](int k) const { return points_[k]; }

 private:
  std::array<Eigen::Vector2d, N> points_;
};

}  // namespace rovctl::hal
