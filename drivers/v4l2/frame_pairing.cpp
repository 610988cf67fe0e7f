// Stamp-based stereo pairing over two small fixed arrays (at most 8 x 8 comparisons per pair).
#include "drivers/v4l2/frame_pairing.hpp"

#include <algorithm>
#include <stdexcept>

namespace rovctl::drivers {

namespace {
std::chrono::nanoseconds abs_diff(std::chrono::nanoseconds a, std::chrono::nanoseconds b) {
  return a > b ? a - b : b - a;
}
}  // namespace

FramePairing::FramePairing(std::chrono::nanoseconds tolerance, std::size_t held_per_side)
    : tolerance_(tolerance), capacity_(held_per_side) {
  if (held_per_side < 1 || held_per_side > kMaxHeldPerSide) {
    throw std::invalid_argument("FramePairing: held_per_side must be in [1, 8]");
  }
  if (tolerance.count() < 0) throw std::invalid_argument("FramePairing: negative tolerance");
}

void FramePairing::add(Side side, std::chrono::nanoseconds stamp, int token) {
  const std::size_t s = index(side);
  if (count_[s] == capacity_) release(side, 0, true);
  // Keep each side ordered oldest first even if a driver delivers out of order.
  std::size_t at = count_[s];
  while (at > 0 && held_[s][at - 1].stamp > stamp) {
    held_[s][at] = held_[s][at - 1];
    --at;
  }
  held_[s][at] = HeldFrame{stamp, token};
  ++count_[s];
}

std::optional<FramePair> FramePairing::take_newest_pair() {
  constexpr std::size_t L = 0;
  constexpr std::size_t R = 1;
  bool found = false;
  std::size_t best_l = 0;
  std::size_t best_r = 0;
  std::chrono::nanoseconds best_older{0};
  std::chrono::nanoseconds best_diff{0};
  for (std::size_t i = 0; i < count_[L]; ++i) {
    for (std::size_t j = 0; j < count_[R]; ++j) {
      const auto diff = abs_diff(held_[L][i].stamp, held_[R][j].stamp);
      if (diff > tolerance_) continue;
      const auto older = std::min(held_[L][i].stamp, held_[R][j].stamp);
      if (!found || older > best_older || (older == best_older && diff < best_diff)) {
        found = true;
        best_l = i;
        best_r = j;
        best_older = older;
        best_diff = diff;
      }
    }
  }
  if (!found) return std::nullopt;
  const FramePair pair{held_[L][best_l], held_[R][best_r]};
  // Frames older than the pair can only pair with older frames still: release them, each
  // counted as superseded (it had a partner) or unpaired.
  // Classify all of them first, so a frame's partner still counts though released alongside.
  for (std::size_t i = 0; i < best_l; ++i) {
    ++(has_partner(Side::left, held_[L][i].stamp) ? stats_.superseded : stats_.unpaired);
  }
  for (std::size_t j = 0; j < best_r; ++j) {
    ++(has_partner(Side::right, held_[R][j].stamp) ? stats_.superseded : stats_.unpaired);
  }
  for (std::size_t n = 0; n < best_l; ++n) release(Side::left, 0, false);
  for (std::size_t n = 0; n < best_r; ++n) release(Side::right, 0, false);
  // The pair is now at the front of both sides; remove it uncounted.
  for (std::size_t s = 0; s < 2; ++s) {
    std::copy(held_[s].begin() + 1, held_[s].begin() + static_cast<long>(count_[s]),
              held_[s].begin());
    --count_[s];
  }
  ++stats_.pairs;
  return pair;
}

bool FramePairing::pop_released(Side& side, int& token) {
  if (released_count_ == 0) return false;
  --released_count_;
  side = released_[released_count_].side;
  token = released_[released_count_].token;
  return true;
}

void FramePairing::clear() {
  for (Side side : {Side::left, Side::right}) {
    while (count_[index(side)] > 0) release(side, 0, false);
  }
}

bool FramePairing::has_partner(Side side, std::chrono::nanoseconds stamp) const {
  const std::size_t other = 1 - index(side);
  for (std::size_t j = 0; j < count_[other]; ++j) {
    if (abs_diff(held_[other][j].stamp, stamp) <= tolerance_) return true;
  }
  return false;
}

void FramePairing::release(Side side, std::size_t i, bool count) {
  const std::size_t s = index(side);
  const HeldFrame frame = held_[s][i];
  if (count) {
    if (has_partner(side, frame.stamp)) {
      ++stats_.superseded;
    } else {
      ++stats_.unpaired;
    }
  }
  std::copy(held_[s].begin() + static_cast<long>(i) + 1,
            held_[s].begin() + static_cast<long>(count_[s]),
            held_[s].begin() + static_cast<long>(i));
  --count_[s];
  push_released(side, frame.token);
}

void FramePairing::push_released(Side side, int token) {
  // Capacity covers everything that can be held; callers pop after every call anyway.
  if (released_count_ < released_.size()) released_[released_count_++] = Released{side, token};
}

}  // namespace rovctl::drivers
