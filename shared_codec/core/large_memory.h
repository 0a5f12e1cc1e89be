// SPDX-License-Identifier: Apache-2.0
// Memory for the large buffers of a decode or an encode (frames, coefficients, adjacency) in
// transparent huge pages, on Linux: writing a fresh buffer of 4 KiB pages takes one page fault
// a page, which in a virtual machine can cost more than the writing, and page faults hardly
// run faster on two threads than on one. A 2 MiB page is one fault for 512 of them. Elsewhere
// (and under AddressSanitizer, which checks only what operator new hands out) these are plain
// operator new and no-ops.
#pragma once
#include <cstddef>

namespace animc {

// The size of a huge page: a buffer below it gains nothing from them.
constexpr size_t kHugePageBytes = size_t(2) << 20;
// Buffers from this size on are allocated by allocateLarge(), so that all of them is in huge
// pages. Smaller ones stay with operator new: the C library reuses them between allocations
// (it maps each buffer of this size or more on its own), and a buffer outside its heap changes
// how its heap is reused: the peak memory of an encode grew.
constexpr size_t kLargeBytes = size_t(32) << 20;

// `bytes` of memory aligned for any type; throws std::bad_alloc when there is none.
void* allocateLarge(size_t bytes);
// Frees what allocateLarge(bytes) returned, with the same `bytes`.
void freeLarge(void* memory, size_t bytes) noexcept;
// Whether allocateLarge() maps the memory itself (else it is operator new).
bool largeMemoryIsMapped() noexcept;

// Marks the whole huge pages inside [memory, memory + bytes) for transparent huge pages, for a
// buffer from elsewhere (a std::vector's reserve()) that is about to be written for the first time.
void adviseHugePages(void* memory, size_t bytes) noexcept;

// v.resize(n), with huge pages for the memory when that allocates it: for a std::vector of a
// large buffer about to be written for the first time.
template <class Vector>
void resizeWithHugePages(Vector& v, size_t n) {
  if (v.capacity() < n) {
    v.reserve(n);
    adviseHugePages(v.data(), v.capacity() * sizeof(*v.data()));
  }
  v.resize(n);
}

}  // namespace animc
