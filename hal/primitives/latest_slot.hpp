// Latest-value mailbox between one writer and one reader (a triple buffer): the real-time tick
// overwrites, a non-real-time reader takes the newest. Neither side waits and nothing allocates
// after construction, so a slow reader loses values, never delays the writer.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

namespace rovctl::app {

template <class T>
class LatestSlot {
 public:
  // The three slots are built here (callers preallocate large members through `init`).
  template <class Init>
  explicit LatestSlot(Init init) {
    for (T& s : slots_) init(s);
  }
  LatestSlot() = default;
  LatestSlot(const LatestSlot&) = delete;
  LatestSlot& operator=(const LatestSlot&) = delete;

  // Writer only: the slot to fill, then publish() it. The reader never sees a slot mid-write.
  T& back() noexcept { return slots_[back_]; }
  void publish() noexcept {
    const std::uint8_t previous =
        middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh), std::memory_order_acq_rel);
    back_ = previous & kIndex;
    published_.fetch_add(1, std::memory_order_relaxed);
  }

  // Reader only: the newest published value, or null when nothing new was published since the
  // last call. The returned slot stays the reader's until its next call.
  const T* take() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return nullptr;
    const std::uint8_t previous = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = previous & kIndex;
    taken_ = true;
    return &slots_[front_];
  }
  // Reader only: the value take() last returned (null before the first).
  const T* current() const noexcept { return taken_ ? &slots_[front_] : nullptr; }

  std::uint64_t published() const noexcept { return published_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::uint8_t kIndex = 0x3;
  static constexpr std::uint8_t kFresh = 0x4;

  std::array<T, 3> slots_{};
  // Ownership of the three slots: writer's back_, reader's front_, the one in between (middle_).
  std::uint8_t back_ = 0;
  alignas(64) std::atomic<std::uint8_t> middle_{1};
  alignas(64) std::uint8_t front_ = 2;
  bool taken_ = false;
  std::atomic<std::uint64_t> published_{0};
};

}  // namespace rovctl::app
