// Process-wide and per-thread allocation counters; plain atomics and a thread_local integer, so
// updating them from inside malloc neither allocates nor recurses.
#include "app/runtime/allocation_counter.hpp"

#include <atomic>

namespace rovctl::app {
namespace {

constinit std::atomic<bool> g_active{false};
constinit std::atomic<std::uint64_t> g_process_count{0};
constinit thread_local std::uint64_t t_thread_count = 0;

}  // namespace

bool allocation_counting_active() noexcept { return g_active.load(std::memory_order_relaxed); }

std::uint64_t allocation_count() noexcept {
  return g_process_count.load(std::memory_order_relaxed);
}

std::uint64_t thread_allocation_count() noexcept { return t_thread_count; }

namespace detail {

void note_allocation() noexcept {
  g_process_count.fetch_add(1, std::memory_order_relaxed);
  ++t_thread_count;
}

void mark_allocation_counting_active() noexcept { g_active.store(true, std::memory_order_relaxed); }

}  // namespace detail
}  // namespace rovctl::app
