// Counts each thread's heap allocations for the allocation-free tests: interposes the malloc
// family over glibc's exported internal names (which also catches Eigen's aligned mallocs).
// Include it in exactly one source file of a test binary; other files of that binary define
// ROVCTL_MALLOC_HOOKS_ELSEWHERE before including it, to read the counter without the hooks. Under
// AddressSanitizer, whose runtime owns malloc, there are no hooks and malloc_hooks_installed() is
// false.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__SANITIZE_ADDRESS__)
#define ROVCTL_NO_MALLOC_HOOKS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ROVCTL_NO_MALLOC_HOOKS 1
#endif
#endif

namespace rovctl::testing {
// Heap allocations made by the calling thread since it started.
inline constinit thread_local std::uint64_t t_allocations = 0;

constexpr bool malloc_hooks_installed() {
#if defined(ROVCTL_NO_MALLOC_HOOKS)
  return false;
#else
  return true;
#endif
}
}  // namespace rovctl::testing

#if !defined(ROVCTL_NO_MALLOC_HOOKS) && !defined(ROVCTL_MALLOC_HOOKS_ELSEWHERE)
// glibc's allocator under its exported internal names; the hooks count, then forward.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t align, std::size_t size);
void __libc_free(void* p);

void* malloc(std::size_t size) noexcept {
  ++rovctl::testing::t_allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  ++rovctl::testing::t_allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  if (size != 0) ++rovctl::testing::t_allocations;
  return __libc_realloc(p, size);
}
void* memalign(std::size_t align, std::size_t size) noexcept {
  ++rovctl::testing::t_allocations;
  return __libc_memalign(align, size);
}
void* aligned_alloc(std::size_t align, std::size_t size) noexcept {
  ++rovctl::testing::t_allocations;
  return __libc_memalign(align, size);
}
int posix_memalign(void** out, std::size_t align, std::size_t size) noexcept {
  if (align < sizeof(void*) || (align & (align - 1)) != 0) return 22;  // EINVAL
  ++rovctl::testing::t_allocations;
  void* p = __libc_memalign(align, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* p) noexcept { __libc_free(p); }
}
#endif
