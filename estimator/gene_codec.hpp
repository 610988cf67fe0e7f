// The RM-GA's 72-bit gene (12 bits each for x, y, z, e1, e2, e3) and its mapping to a marker pose
// in the search volume; e1..e3 are the vector part of a unit quaternion, e0 = sqrt(1 - |e|^2).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>

#include "estimator/estimator_params.hpp"

namespace rovctl::estimator {

constexpr int kGeneFields = 6;
constexpr int kBitsPerField = 12;
constexpr int kGeneBits = kGeneFields * kBitsPerField;  // 72
constexpr std::uint16_t kFieldMax = (1u << kBitsPerField) - 1;

// Bit k of the gene is bit (k % 12) of field k / 12; fields are x, y, z, e1, e2, e3.
struct Gene {
  std::array<std::uint16_t, kGeneFields> field{};
  bool operator==(const Gene&) const = default;
};

class GeneCodec {
 public:
  // gray: each field is a reflected Gray code (neighbouring values one bit apart), else plain
  // binary.
  explicit GeneCodec(const SearchVolume& volume, bool gray = false);

  Eigen::Isometry3d decode(const Gene& gene) const;
  // The nearest gene to a pose. Returns false when the pose lies outside the search volume
  // (the gene is then clamped to its boundary).
  bool encode(const Eigen::Isometry3d& T_cl_marker, Gene& gene) const;

  // Size of one step of the least significant bit, per field (m, m, m, -, -, -).
  double resolution(int field) const { return (hi_[field] - lo_[field]) / kFieldMax; }
  const SearchVolume& volume() const { return volume_; }

 private:
  SearchVolume volume_;
  bool gray_ = false;
  std::array<double, kGeneFields> lo_{}, hi_{};
};

// Two-point crossover: bits [cut1, cut2) are exchanged between the parents (0 <= cut1 <= cut2 <=
// 72).
void two_point_crossover(const Gene& a, const Gene& b, int cut1, int cut2, Gene& child_a,
                         Gene& child_b);
inline void flip_bit(Gene& gene, int bit) {
  gene.field[bit / kBitsPerField] ^= static_cast<std::uint16_t>(1u << (bit % kBitsPerField));
}

}  // namespace rovctl::estimator
