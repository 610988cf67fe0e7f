// Linear fixed-point mapping of each 12-bit field onto its range of the search volume.
#include "estimator/gene_codec.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::estimator {

namespace {

std::uint16_t gray_to_binary(std::uint16_t g) {
  for (std::uint16_t shift = g >> 1; shift != 0; shift >>= 1) g ^= shift;
  return g;
}

}  // namespace

GeneCodec::GeneCodec(const SearchVolume& v, bool gray) : volume_(v), gray_(gray) {
  lo_ = {v.x_min_m, v.y_min_m, v.z_min_m, -v.epsilon_max, -v.epsilon_max, -v.epsilon_max};
  hi_ = {v.x_max_m, v.y_max_m, v.z_max_m, v.epsilon_max, v.epsilon_max, v.epsilon_max};
}

Eigen::Isometry3d GeneCodec::decode(const Gene& gene) const {
  double p[kGeneFields];
  for (int i = 0; i < kGeneFields; ++i) {
    const std::uint16_t f = gene.field[i] & kFieldMax;
    p[i] = lo_[i] + (hi_[i] - lo_[i]) * (gray_ ? gray_to_binary(f) : f) / kFieldMax;
  }
  Eigen::Vector3d e(p[3], p[4], p[5]);
  const double n2 = e.squaredNorm();
  double w = 0.0;
  if (n2 >= 1.0) {
    e /= std::sqrt(n2);  // outside the unit ball: the nearest unit quaternion (a half turn)
  } else {
    w = std::sqrt(1.0 - n2);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(w, e.x(), e.y(), e.z()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return T;
}

bool GeneCodec::encode(const Eigen::Isometry3d& T, Gene& gene) const {
  Eigen::Quaterniond q(T.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double p[kGeneFields] = {
      T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z()};
  bool inside = true;
  for (int i = 0; i < kGeneFields; ++i) {
    const double s = (p[i] - lo_[i]) / (hi_[i] - lo_[i]);
    if (!(s >= 0.0 && s <= 1.0)) inside = false;
    const double clamped = std::clamp(std::isfinite(s) ? s : 0.5, 0.0, 1.0);
    const auto b = static_cast<std::uint16_t>(std::lround(clamped * kFieldMax));
    gene.field[i] = gray_ ? static_cast<std::uint16_t>(b ^ (b >> 1)) : b;
  }
  return inside;
}

void two_point_crossover(const Gene& a, const Gene& b, int cut1, int cut2, Gene& child_a,
                         Gene& child_b) {
  for (int f = 0; f < kGeneFields; ++f) {
    // Mask of this field's bits that lie in [cut1, cut2).
    const int lo = std::clamp(cut1 - f * kBitsPerField, 0, kBitsPerField);
    const int hi = std::clamp(cut2 - f * kBitsPerField, 0, kBitsPerField);
    const std::uint16_t mask =
        hi > lo ? static_cast<std::uint16_t>(((1u << hi) - 1u) & ~((1u << lo) - 1u)) : 0;
    child_a.field[f] = static_cast<std::uint16_t>((a.field[f] & ~mask) | (b.field[f] & mask));
    child_b.field[f] = static_cast<std::uint16_t>((b.field[f] & ~mask) | (a.field[f] & mask));
  }
}

}  // namespace rovctl::estimator
