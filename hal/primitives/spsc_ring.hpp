// Single-producer single-consumer lock-free ring of trivially copyable items: the real-time tick
// pushes, a non-real-time thread pops. A full ring drops (and counts) the new item rather than
// block the producer.
#pragma once

#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace rovctl::app {

template <class T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "ring items are copied as plain bytes");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);

 public:
  // Storage is allocated here, once; capacity is `min_capacity` rounded up to a power of two.
  explicit SpscRing(std::size_t min_capacity)
      : slots_(std::bit_ceil(min_capacity < 2 ? std::size_t{2} : min_capacity)),
        mask_(slots_.size() - 1) {
    if (min_capacity > (std::size_t{1} << 30)) throw std::invalid_argument("ring too large");
  }
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  std::size_t capacity() const noexcept { return slots_.size(); }

  // Producer only. False when full: the item is dropped and counted.
  bool try_push(const T& item) noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) >= slots_.size()) {
      dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      return false;
    }
    slots_[head & mask_] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. False when empty.
  bool try_pop(T& item) noexcept {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    item = slots_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Items waiting; exact from either side's own thread when the other side is idle.
  std::size_t size() const noexcept {
    return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                    tail_.load(std::memory_order_acquire));
  }
  std::uint64_t pushed() const noexcept { return head_.load(std::memory_order_acquire); }
  std::uint64_t popped() const noexcept { return tail_.load(std::memory_order_acquire); }
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  std::vector<T> slots_;
  std::size_t mask_;
  // Producer and consumer indices on separate cache lines (no false sharing between threads).
  alignas(64) std::atomic<std::uint64_t> head_{0};  // next slot to write; written by the producer
  alignas(64) std::atomic<std::uint64_t> tail_{0};  // next slot to read; written by the consumer
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace rovctl::app
