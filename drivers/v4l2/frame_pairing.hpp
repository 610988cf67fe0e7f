// Left/right frame pairing for two free-running cameras: matches capture stamps within a
// tolerance, hands out only the newest pair, and counts the frames that never found a partner.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace rovctl::drivers {

enum class Side { left = 0, right = 1 };

// A frame waiting for its partner; `token` is the caller's handle (a V4L2 buffer index).
struct HeldFrame {
  std::chrono::nanoseconds stamp{0};
  int token = -1;
};

struct FramePair {
  HeldFrame left;
  HeldFrame right;
};

struct PairingStats {
  std::uint64_t pairs = 0;       // pairs handed out
  std::uint64_t unpaired = 0;    // released with no frame of the other side within tolerance
  std::uint64_t superseded = 0;  // had a partner, but a newer pair was handed out instead
};

// Pure logic, fixed capacity, no allocation. The caller adds frames as it dequeues them, takes
// the newest pair, and gives back (requeues) every released token it pops.
class FramePairing {
 public:
  static constexpr std::size_t kMaxHeldPerSide = 8;

  // `held_per_side` in [1, kMaxHeldPerSide]: how many frames one side may keep waiting for a
  // partner (each is a device buffer the driver cannot fill meanwhile).
  FramePairing(std::chrono::nanoseconds tolerance, std::size_t held_per_side);

  // A newly captured frame. When the side is full its oldest frame is released.
  void add(Side side, std::chrono::nanoseconds stamp, int token);

  // The newest pair whose stamps differ by at most the tolerance (newest = the larger of the two
  // pairs' older stamps; ties go to the closer pair). The pair leaves the pairing and every older
  // frame of either side is released: there is never a backlog.
  std::optional<FramePair> take_newest_pair();

  // Pops one released frame whose token the caller must give back; false when none is left.
  bool pop_released(Side& side, int& token);

  // Releases everything still held (e.g. before a device is reopened), without counting them.
  void clear();

  std::size_t held(Side side) const { return count_[index(side)]; }
  std::chrono::nanoseconds tolerance() const { return tolerance_; }
  const PairingStats& stats() const { return stats_; }

 private:
  static std::size_t index(Side s) { return static_cast<std::size_t>(s); }
  bool has_partner(Side side, std::chrono::nanoseconds stamp) const;
  void release(Side side, std::size_t i, bool count);
  void push_released(Side side, int token);

  std::chrono::nanoseconds tolerance_;
  std::size_t capacity_;
  std::array<std::array<HeldFrame, kMaxHeldPerSide>, 2> held_{};  // oldest first
  std::array<std::size_t, 2> count_{0, 0};
  struct Released {
    Side side;
    int token;
  };
  std::array<Released, 2 * kMaxHeldPerSide + 2> released_{};
  std::size_t released_count_ = 0;
  PairingStats stats_;
};

}  // namespace rovctl::drivers
