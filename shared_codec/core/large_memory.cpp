// SPDX-License-Identifier: Apache-2.0
#include "core/large_memory.h"

#include <cstdint>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ANIMC_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define ANIMC_ADDRESS_SANITIZER 1
#endif

#if defined(__linux__) && !defined(__EMSCRIPTEN__) && !defined(ANIMC_ADDRESS_SANITIZER)
#include <sys/mman.h>
#define ANIMC_HUGE_PAGES 1
#endif

namespace animc {

#ifdef ANIMC_HUGE_PAGES
namespace {

constexpr size_t kPageBytes = 4096;

size_t roundUp(size_t bytes, size_t unit) { return (bytes + unit - 1) / unit * unit; }

}  // namespace

// A mapping of the buffer's pages starting on a huge-page boundary (so that every whole 2 MiB
// of it can be one page; the rest, at the end, stays in small pages and costs no more memory).
void* allocateLarge(size_t bytes) {
  const size_t length = roundUp(bytes, kPageBytes);
  if (length < bytes || length + kHugePageBytes < length) throw std::bad_alloc();
  void* mapped = mmap(nullptr, length + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  char* const begin = static_cast<char*>(mapped);
  char* const aligned = begin + (kHugePageBytes - reinterpret_cast<uintptr_t>(begin) % kHugePageBytes) % kHugePageBytes;
  if (aligned > begin) munmap(begin, size_t(aligned - begin));
  char* const end = begin + length + kHugePageBytes;
  if (end > aligned + length) munmap(aligned + length, size_t(end - (aligned + length)));
  madvise(aligned, length, MADV_HUGEPAGE);  // a hint: without it the pages are small
  return aligned;
}

void freeLarge(void* memory, size_t bytes) noexcept {
  if (memory != nullptr) munmap(memory, roundUp(bytes, kPageBytes));
}

bool largeMemoryIsMapped() noexcept { return true; }

void adviseHugePages(void* memory, size_t bytes) noexcept {
  const uintptr_t begin = roundUp(reinterpret_cast<uintptr_t>(memory), kHugePageBytes);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(memory) + bytes) / kHugePageBytes * kHugePageBytes;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}
#else
void* allocateLarge(size_t bytes) { return ::operator new(bytes); }
void freeLarge(void* memory, size_t) noexcept { ::operator delete(memory); }
bool largeMemoryIsMapped() noexcept { return false; }
void adviseHugePages(void*, size_t) noexcept {}
#endif

}  // namespace animc
