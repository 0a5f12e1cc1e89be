// SPDX-License-Identifier: Apache-2.0
#include "core/temp_registry.h"

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace animc {
namespace {

// kClaimed: being filled by registerTemporary(); kRemoving: taken by the signal handler, never
// given back (the process is ending).
enum SlotState : int { kFree, kClaimed, kLiveFile, kLiveFolder, kRemoving };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kMaxTemporaryPathBytes + 1];
};

static_assert(std::atomic<int>::is_always_lock_free,
              "a signal handler may only touch lock-free atomics");

Slot g_slots[kMaxTemporaries];

bool isDotOrDotDot(const char* name) {
  return name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
}

// One pass over the folder unlinking its plain files; whether it unlinked any. getdents64
// rather than readdir(), which may allocate.
bool unlinkFilesIn(int folder) {
  bool unlinked = false;
  alignas(struct dirent64) char buffer[8192];
  if (lseek(folder, 0, SEEK_SET) != 0) return false;
  for (ssize_t n; (n = getdents64(folder, buffer, sizeof buffer)) > 0;) {
    for (ssize_t at = 0; at < n;) {
      const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + at);
      at += entry->d_reclen;
      if (!isDotOrDotDot(entry->d_name) && unlinkat(folder, entry->d_name, 0) == 0) unlinked = true;
    }
  }
  return unlinked;
}

// A temporary folder holds only the frame files written into it (and their temporaries):
// unlinking while listing may skip entries, so passes repeat until one unlinks nothing.
void removeFolder(const char* path) {
  const int folder = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder >= 0) {
    bool unlinked = true;
    for (int pass = 0; pass < 16 && unlinked; ++pass) unlinked = unlinkFilesIn(folder);
    close(folder);
  }
  rmdir(path);
}

// Takes every live slot of one kind and removes its temporary.
void removeLive(int live_state) {
  for (Slot& slot : g_slots) {
    int expected = live_state;
    if (!slot.state.compare_exchange_strong(expected, kRemoving, std::memory_order_acquire)) continue;
    if (live_state == kLiveFile) unlink(slot.path);
    else removeFolder(slot.path);
  }
}

}  // namespace

int registerTemporary(const std::string& path, TemporaryKind kind) {
  std::error_code ec;
  std::string absolute = std::filesystem::absolute(path, ec).string();
  if (ec) absolute = path;
  if (absolute.size() > kMaxTemporaryPathBytes) return -1;
  for (int i = 0; i < kMaxTemporaries; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kClaimed, std::memory_order_acquire))
      continue;
    std::memcpy(g_slots[i].path, absolute.c_str(), absolute.size() + 1);
    g_slots[i].state.store(kind == TemporaryKind::kFile ? kLiveFile : kLiveFolder,
                           std::memory_order_release);
    return i;
  }
  return -1;
}

void unregisterTemporary(int slot) {
  if (slot < 0 || slot >= kMaxTemporaries) return;
  // Only a live slot is freed: one the signal handler has taken stays taken.
  int live = g_slots[slot].state.load(std::memory_order_acquire);
  if (live == kLiveFile || live == kLiveFolder)
    g_slots[slot].state.compare_exchange_strong(live, kFree, std::memory_order_release);
}

void removeRegisteredTemporaries() {
  // Files first: a frame's temporary lives in the folder's temporary.
  removeLive(kLiveFile);
  removeLive(kLiveFolder);
}

}  // namespace animc
