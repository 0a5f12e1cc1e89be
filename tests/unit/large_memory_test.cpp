// SPDX-License-Identifier: Apache-2.0
// Large buffers come from their own mapping (huge pages on Linux): they hold what is written
// to them, keep it when a vector grows past the threshold, are freed, and a size no system
// can give is a std::bad_alloc rather than a crash.
#include <gtest/gtest.h>

#include <cstdint>
#include <new>
#include <vector>

#include "core/large_memory.h"
#include "core/uninitialised_vector.h"

namespace animc {
namespace {

TEST(LargeMemory, HoldsEveryByteWritten) {
  const size_t bytes = kLargeBytes * 3 + 12345;
  auto* memory = static_cast<uint8_t*>(allocateLarge(bytes));
  ASSERT_NE(memory, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(memory) % alignof(std::max_align_t), 0u);
  for (size_t i = 0; i < bytes; ++i) memory[i] = uint8_t(i * 7);
  for (size_t i = 0; i < bytes; i += 4093) ASSERT_EQ(memory[i], uint8_t(i * 7)) << i;
  EXPECT_EQ(memory[bytes - 1], uint8_t((bytes - 1) * 7));
  freeLarge(memory, bytes);
  freeLarge(nullptr, bytes);
}

TEST(LargeMemory, ASizeNoSystemHasIsBadAlloc) {
  EXPECT_THROW(DefaultInitAllocator<double>().allocate(SIZE_MAX / 4), std::bad_alloc);
  if (!largeMemoryIsMapped())
    GTEST_SKIP() << "large buffers come from operator new in this build (AddressSanitizer aborts on such sizes)";
  EXPECT_THROW(allocateLarge(SIZE_MAX - 100), std::bad_alloc);
  EXPECT_THROW(allocateLarge(size_t(1) << 62), std::bad_alloc);
}

TEST(LargeMemory, AVectorKeepsItsValuesAcrossTheThreshold) {
  // Grown one value at a time from small buffers to large ones and back by a copy: every
  // reallocation moves the values between the two kinds of memory.
  UninitialisedVector<uint32_t> values;
  const size_t count = 3 * kLargeBytes / sizeof(uint32_t);
  for (size_t i = 0; i < count; ++i) values.push_back(uint32_t(i * 2654435761u));
  for (size_t i = 0; i < count; ++i) ASSERT_EQ(values[i], uint32_t(i * 2654435761u)) << i;
  UninitialisedVector<uint32_t> copy(values.begin(), values.begin() + 1000);
  values.resize(1000);
  values.shrink_to_fit();
  EXPECT_EQ(values, copy);
}

TEST(LargeMemory, ResizingWithHugePagesKeepsTheValues) {
  std::vector<double> values(1000);
  for (size_t i = 0; i < values.size(); ++i) values[i] = double(i) / 3;
  resizeWithHugePages(values, 2 * kLargeBytes / sizeof(double));
  ASSERT_GE(values.capacity(), 2 * kLargeBytes / sizeof(double));
  ASSERT_EQ(values.size(), 2 * kLargeBytes / sizeof(double));
  for (size_t i = 0; i < 1000; ++i) ASSERT_EQ(values[i], double(i) / 3) << i;
  EXPECT_EQ(values[1000], 0.0);  // the new values are value-initialised, as resize() makes them
  const double* data = values.data();
  resizeWithHugePages(values, 1000);  // already large enough: nothing moves
  EXPECT_EQ(values.data(), data);
  EXPECT_EQ(values.size(), 1000u);
  values.resize(values.capacity(), 1.5);
  EXPECT_EQ(values.back(), 1.5);
}

}  // namespace
}  // namespace animc
