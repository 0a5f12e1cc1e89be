// SPDX-License-Identifier: Apache-2.0
// The file source reads small ranges through a window of the file: every read, small or
// large, across the window's edges and at the file's end, gives the file's bytes.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <random>
#include <vector>

#include "io/byte_source.h"
#include "scratch_folder.h"

namespace animc {
namespace {

class FileSourceTest : public testing_support::ScratchFolderTest {
 protected:
  FileSourceTest() : ScratchFolderTest("animc_byte_source") {}
};

TEST_F(FileSourceTest, EveryReadGivesTheFilesBytes) {
  std::mt19937 random(7);
  std::vector<uint8_t> bytes(300000);
  for (uint8_t& b : bytes) b = uint8_t(random());
  const std::string file = path("bytes.bin");
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));

  auto source = openFileSource(file);
  ASSERT_TRUE(source.ok()) << source.status().message();
  ByteSource& s = *source.value();
  ASSERT_EQ(s.size(), bytes.size());
  // Sizes from none to more than the window, at offsets going forwards, backwards and across
  // the window's edges (64 KiB), up to the last byte.
  std::vector<std::pair<uint64_t, size_t>> reads = {{0, 0},      {0, 1},         {65535, 2},      {65536, 10},
                                                    {10, 40000}, {30000, 40000}, {1000, 70000},   {299990, 10},
                                                    {300000, 0}, {299999, 1},    {131072, 32768}, {131071, 32769}};
  for (int i = 0; i < 2000; ++i) {
    const size_t size = random() % 4 == 0 ? random() % 100000 : random() % 64;
    reads.emplace_back(random() % (bytes.size() - size + 1), size);
  }
  for (const auto& [offset, size] : reads) {
    std::vector<uint8_t> out(size + 1, 0xAB);
    ASSERT_TRUE(s.readAt(offset, out.data(), size).ok()) << offset << " + " << size;
    EXPECT_TRUE(std::equal(out.begin(), out.begin() + std::ptrdiff_t(size), bytes.begin() + std::ptrdiff_t(offset)))
        << offset << " + " << size;
    EXPECT_EQ(out[size], 0xAB) << "written past the read, " << offset << " + " << size;
  }
  std::vector<uint8_t> out(16);
  EXPECT_EQ(s.readAt(299995, out.data(), 6).code(), StatusCode::kTruncated);
  EXPECT_EQ(s.readAt(300001, out.data(), 0).code(), StatusCode::kTruncated);
}

}  // namespace
}  // namespace animc
