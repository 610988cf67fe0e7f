// The view's smear from its blobs' smears: the largest set that agrees in direction and length.
#include "estimator/motion_smear.hpp"

#include <algorithm>
#include <cmath>

namespace rovctl::estimator {

SharedSmear shared_smear(const std::array<BlobSmear, hal::kColourClassCount>& by_colour) {
  constexpr int n = hal::kColourClassCount;
  std::array<double, n> length{};
  for (int i = 0; i < n; ++i) length[i] = std::hypot(by_colour[i].u_px, by_colour[i].v_px);
  const double cos_agree = std::cos(kSmearAgreeDeg * M_PI / 180.0);
  auto agree = [&](int a, int b) {
    if (length[a] <= 0.0 || length[b] <= 0.0) return false;
    // Sign-free: a smear has no direction along its line.
    const double c =
        std::abs(by_colour[a].u_px * by_colour[b].u_px + by_colour[a].v_px * by_colour[b].v_px) /
        (length[a] * length[b]);
    return c >= cos_agree &&
           std::min(length[a], length[b]) >= kSmearAgreeLength * std::max(length[a], length[b]);
  };
  SharedSmear best;
  int best_count = 1, best_i = -1;
  for (int i = 0; i < n; ++i) {
    if (length[i] <= 0.0) continue;
    int count = 0;
    double min_length = length[i], min_width = by_colour[i].width_px, max_width = min_width;
    for (int j = 0; j < n; ++j) {
      if (j != i && !agree(i, j)) continue;
      // The set around i holds the blobs agreeing with it; i is its longest.
      if (length[j] > length[i]) {
        count = 0;
        break;
      }
      ++count;
      min_length = std::min(min_length, length[j]);
      min_width = std::min(min_width, by_colour[j].width_px);
      max_width = std::max(max_width, by_colour[j].width_px);
    }
    if (count > best_count ||
        (count == best_count && best.valid && length[i] > std::hypot(best.u_px, best.v_px))) {
      best_count = count;
      best_i = i;
      best.valid = true;
      best.u_px = by_colour[i].u_px;
      best.v_px = by_colour[i].v_px;
      best.min_length_px = min_length;
      best.min_width_px = min_width;
      best.max_width_px = max_width;
    }
  }
  // A blob as wide as the smeared ones and hardly smeared says the camera did not move: the
  // elongated ones are spheres cut by an occluder or merged with something of their colour.
  for (int j = 0; j < n && best.valid; ++j) {
    if (j == best_i || agree(best_i, j) || by_colour[j].width_px <= 0.0) continue;
    if (by_colour[j].width_px >= kSmearVetoWidth * best.min_width_px &&
        length[j] < kSmearVetoLength * best.min_length_px) {
      return SharedSmear{};
    }
  }
  return best;
}

}  // namespace rovctl::estimator
