#pragma once
// An allocator for the large arrays of the DG solver (block matrix values, preconditioner
// factors): allocations of 4 MiB or more are 2 MiB-aligned and marked MADV_HUGEPAGE, so that
// Linux backs them with transparent huge pages (when /sys/kernel/mm/transparent_hugepage/enabled
// is "madvise" or "always"). This removes most page faults on first touch (one per 2 MiB instead
// of one per 4 KiB) and TLB misses in the memory-bound block sweeps. Elsewhere it is malloc.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace quadapt {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHuge = std::size_t(2) << 20;       // 2 MiB
  static constexpr std::size_t kThreshold = std::size_t(4) << 20;  // use huge pages from 4 MiB

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    void* p = nullptr;
    if (bytes >= kThreshold) {
      const std::size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
      p = std::aligned_alloc(kHuge, rounded);
#ifdef MADV_HUGEPAGE
      if (p) madvise(p, rounded, MADV_HUGEPAGE);
#endif
    } else {
      p = std::malloc(bytes ? bytes : 1);
    }
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) { std::free(p); }
};

template <class T, class U>
bool operator==(const HugePageAllocator<T>&, const HugePageAllocator<U>&) { return true; }
template <class T, class U>
bool operator!=(const HugePageAllocator<T>&, const HugePageAllocator<U>&) { return false; }

/// std::vector on huge pages.
template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace quadapt
