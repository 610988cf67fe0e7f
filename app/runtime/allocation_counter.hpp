// Heap-allocation counting, to prove that the real-time tick allocates nothing after start-up.
// The counters live here; only a test binary installs the hooks that feed them.
#pragma once

#include <cstdint>

namespace rovctl::app {

// True when this binary installed counting hooks (test binaries do, the rovctl executable does
// not); without hooks every count stays 0, so a check of "no allocation" would prove nothing.
bool allocation_counting_active() noexcept;

// Heap allocations (malloc family or operator new) made so far by the whole process.
std::uint64_t allocation_count() noexcept;

// Heap allocations made so far by the calling thread: what a real-time loop is judged by, since
// non-real-time threads (telemetry writer, logging) may allocate freely meanwhile.
std::uint64_t thread_allocation_count() noexcept;

// Counts the calling thread's allocations from construction on.
class AllocationProbe {
 public:
  AllocationProbe() noexcept : start_(thread_allocation_count()) {}
  std::uint64_t allocations() const noexcept { return thread_allocation_count() - start_; }

 private:
  std::uint64_t start_;
};

namespace detail {
// Called by the hooks on every allocation; async-signal-safe and allocation-free.
void note_allocation() noexcept;
// Called once by the hooks at static initialisation.
void mark_allocation_counting_active() noexcept;
}  // namespace detail

}  // namespace rovctl::app
