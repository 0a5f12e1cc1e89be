// SPDX-License-Identifier: GPL-3.0-or-later
// An LD_PRELOAD library for the meshlab_bad_ams test: every allocation above
// $ANIMC_FAIL_ALLOCATIONS_ABOVE bytes fails as if memory had run out, so a real std::bad_alloc
// rises from real code through a plugin to its entry point, where the plugin must turn it
// into a message instead of ending MeshLab. Smaller allocations go to glibc's allocator.
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" {
void* __libc_malloc(size_t bytes);
void* __libc_calloc(size_t count, size_t bytes);
void* __libc_realloc(void* block, size_t bytes);
void* __libc_memalign(size_t alignment, size_t bytes);
}

namespace {

size_t threshold() {
  static const size_t bytes = [] {
    const char* text = std::getenv("ANIMC_FAIL_ALLOCATIONS_ABOVE");
    const unsigned long long value = text != nullptr ? std::strtoull(text, nullptr, 10) : 0;
    return value > 0 ? size_t(value) : SIZE_MAX;
  }();
  return bytes;
}

bool refused(size_t bytes) {
  if (bytes <= threshold()) return false;
  errno = ENOMEM;
  return true;
}

}  // namespace

extern "C" {

void* malloc(size_t bytes) { return refused(bytes) ? nullptr : __libc_malloc(bytes); }

void* calloc(size_t count, size_t bytes) {
  if (bytes != 0 && count > SIZE_MAX / bytes) return nullptr;
  return refused(count * bytes) ? nullptr : __libc_calloc(count, bytes);
}

void* realloc(void* block, size_t bytes) { return refused(bytes) ? nullptr : __libc_realloc(block, bytes); }

void* memalign(size_t alignment, size_t bytes) { return refused(bytes) ? nullptr : __libc_memalign(alignment, bytes); }

void* aligned_alloc(size_t alignment, size_t bytes) { return memalign(alignment, bytes); }

int posix_memalign(void** block, size_t alignment, size_t bytes) {
  void* p = memalign(alignment, bytes);
  if (p == nullptr) return ENOMEM;
  *block = p;
  return 0;
}

}  // extern "C"
