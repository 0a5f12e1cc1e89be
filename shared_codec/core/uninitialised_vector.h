// SPDX-License-Identifier: Apache-2.0
// A std::vector whose resize() leaves new elements of a trivial type as they come from the
// allocator instead of zeroing them: for large buffers written in full before they are read,
// where a zero fill would be a pass over memory, and its page faults, on one thread before
// the threads that write the buffer start. Buffers of a huge page or more are in huge pages
// (core/large_memory.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "core/large_memory.h"

namespace animc {

template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    if (n < kHugePageBytes / sizeof(T)) return std::allocator<T>::allocate(n);
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
    if (n >= kLargeBytes / sizeof(T)) return static_cast<T*>(allocateLarge(n * sizeof(T)));
    T* p = std::allocator<T>::allocate(n);
    adviseHugePages(p, n * sizeof(T));
    return p;
  }
  void deallocate(T* p, size_t n) noexcept {
    if (n < kLargeBytes / sizeof(T)) return std::allocator<T>::deallocate(p, n);
    freeLarge(p, n * sizeof(T));
  }

  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;  // default-initialised: no value for a trivial type
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitialisedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace animc
