// SPDX-License-Identifier: Apache-2.0
// A std::vector whose resize() leaves new elements of a trivial type as they come from the
// allocator instead of zeroing them: for large buffers written in full before they are read,
// where a zero fill would be a pass over memory, and its page faults, on one thread before
// the threads that write the buffer start.
#pragma once
#include <memory>
#include <new>
#include <utility>
#include <vector>

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
