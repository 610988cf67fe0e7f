// Counting hooks for app_tests only (named *_test.cpp so the tests' glob links it in; the rovctl
// executable never has them). With glibc and no sanitizer the malloc family is interposed, which
// also catches Eigen's and OpenCV's aligned mallocs; under AddressSanitizer, whose runtime owns
// malloc, the global operator new is replaced instead.
#include <cstddef>
#include <cstdlib>
#include <new>

#include "app/runtime/allocation_counter.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define ROVCTL_HOOK_OPERATOR_NEW 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ROVCTL_HOOK_OPERATOR_NEW 1
#endif
#endif

namespace {
struct MarkActive {
  MarkActive() { rovctl::app::detail::mark_allocation_counting_active(); }
} g_mark_active;
}  // namespace

#if defined(ROVCTL_HOOK_OPERATOR_NEW)

namespace {
void* counted_new(std::size_t size) {
  rovctl::app::detail::note_allocation();
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* counted_new_aligned(std::size_t size, std::align_val_t align) {
  rovctl::app::detail::note_allocation();
  const auto a = static_cast<std::size_t>(align);
  const std::size_t rounded = (size + a - 1) / a * a;
  if (void* p = std::aligned_alloc(a, rounded == 0 ? a : rounded)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted_new(n); }
void* operator new[](std::size_t n) { return counted_new(n); }
void* operator new(std::size_t n, std::align_val_t a) { return counted_new_aligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return counted_new_aligned(n, a); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted_new(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

#else

// glibc's own allocator under its exported internal names; the hooks count, then forward.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t align, std::size_t size);
void* __libc_valloc(std::size_t size);
void* __libc_pvalloc(std::size_t size);
void __libc_free(void* p);

void* malloc(std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  if (size != 0) rovctl::app::detail::note_allocation();
  return __libc_realloc(p, size);
}
void* memalign(std::size_t align, std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_memalign(align, size);
}
void* aligned_alloc(std::size_t align, std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_memalign(align, size);
}
int posix_memalign(void** out, std::size_t align, std::size_t size) noexcept {
  if (align < sizeof(void*) || (align & (align - 1)) != 0) return 22;  // EINVAL
  rovctl::app::detail::note_allocation();
  void* p = __libc_memalign(align, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void* valloc(std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_valloc(size);
}
void* pvalloc(std::size_t size) noexcept {
  rovctl::app::detail::note_allocation();
  return __libc_pvalloc(size);
}
void free(void* p) noexcept { __libc_free(p); }
}

#endif
