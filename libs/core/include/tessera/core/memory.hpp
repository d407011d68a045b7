#pragma once
// Large fresh arrays without page-fault storms: huge-page advice, uninitialized growth, parallel first touch.
// Refinement levels and iso-surfaces write hundreds of megabytes of fresh memory; with 4 KiB pages faulted one at a
// time inside a serial value-initialization the page faults cost more than the arithmetic (measured 2-5x on the
// subdivision and marching-cubes benchmarks).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "tessera/core/parallel.hpp"

namespace tessera {

/// Asks the kernel to back the whole 2 MiB pages inside [p, p + bytes) with transparent huge pages, before they are
/// first touched. A hint (Linux madvise); does nothing elsewhere or for blocks smaller than one huge page.
void advise_huge_pages(void* p, size_t bytes);

/// A hint that asks the caches for the line at p (a no-op elsewhere than GCC/Clang). Inline assembly on x86-64,
/// because GCC 12 drops some __builtin_prefetch calls from inlined loops.
inline void prefetch_line(const void* p) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#elif defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

/// An allocator whose resize() leaves new elements uninitialized (for arrays that are written in full afterwards);
/// blocks of 4 MiB or more are aligned to 2 MiB and rounded up to whole 2 MiB pages advised to use huge pages.
template <class T>
struct NoInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = NoInitAllocator<U>;
  };
  NoInitAllocator() = default;
  template <class U>
  NoInitAllocator(const NoInitAllocator<U>&) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  static constexpr size_t kHugePage = size_t(2) << 20;
  T* allocate(size_t n) {
    if (n * sizeof(T) < 2 * kHugePage) return std::allocator<T>::allocate(n);
    const size_t bytes = (n * sizeof(T) + kHugePage - 1) & ~(kHugePage - 1);
    void* p = ::operator new(bytes, std::align_val_t(kHugePage));
    advise_huge_pages(p, bytes);
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n * sizeof(T) < 2 * kHugePage) return std::allocator<T>::deallocate(p, n);
    ::operator delete(p, std::align_val_t(kHugePage));
  }
};

/// A std::vector whose resize() does not initialize (see NoInitAllocator).
template <class T>
using RawVector = std::vector<T, NoInitAllocator<T>>;

/// Resizes `v` to n value-initialized elements in fresh storage that was first advised to use huge pages and touched
/// in parallel (one byte per 4 KiB page), so that the kernel's page zeroing is spread over the threads instead of
/// happening inside resize()'s serial value-initialization. Previous contents are discarded.
template <class T>
void resize_fresh(std::vector<T>& v, size_t n) {
  v.clear();
  v.reserve(n);
  auto* bytes = reinterpret_cast<unsigned char*>(v.data());
  advise_huge_pages(bytes, n * sizeof(T));
  constexpr int64_t kPage = 4096;
  parallel_for(0, (int64_t(n * sizeof(T)) + kPage - 1) / kPage, 64, [&](int64_t b, int64_t e) {
    for (int64_t page = b; page < e; ++page) bytes[page * kPage] = 0;
  });
  v.resize(n);
}

}  // namespace tessera
