// SPDX-License-Identifier: Apache-2.0
// checkAmsFile(), the whole-file check behind `animc test`: it accepts every golden file, and
// refuses every truncation of each and single-bit flips spread over each, including damage
// past the first group, which opening a file (and `animc info`) does not look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "api.h"
#include "codec_test_support.h"

namespace animc {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

const std::string kGoldenDir = std::string(ANIMC_SOURCE_DIR) + "/tests/golden/";

Bytes readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const Bytes& bytes) {
  std::remove(path.c_str());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::vector<std::string> goldenAmsFiles() {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(kGoldenDir))
    if (e.path().extension() == ".ams") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class AmsCheckTest : public testing::Test {
 protected:
  void TearDown() override { std::remove(path_.c_str()); }
  const std::string path_ = testing_support::tempPath("checked.ams");
};

TEST_F(AmsCheckTest, AcceptsEveryGoldenFile) {
  const std::vector<std::string> names = goldenAmsFiles();
  ASSERT_GE(names.size(), 13u);
  for (const std::string& name : names) {
    const std::string path = kGoldenDir + name;
    auto check = checkAmsFile(path);
    ASSERT_TRUE(check.ok()) << name << ": " << check.status().message();
    auto ams = AmsSource::open(path);
    ASSERT_TRUE(ams.ok()) << name;
    EXPECT_EQ(check.value().frames, ams.value()->frameCount()) << name;
    EXPECT_EQ(check.value().vertices, ams.value()->topology().vertex_count) << name;
    EXPECT_EQ(check.value().triangles, ams.value()->topology().triangles.size()) << name;
    EXPECT_GE(check.value().groups, 1u) << name;
    EXPECT_EQ(check.value().file_bytes, fs::file_size(path)) << name;
  }
}

TEST_F(AmsCheckTest, RefusesEveryTruncation) {
  for (const std::string& name : goldenAmsFiles()) {
    const Bytes golden = readBytes(kGoldenDir + name);
    ASSERT_FALSE(golden.empty()) << name;
    writeBytes(path_, golden);
    for (size_t n = golden.size(); n-- > 0;) {
      fs::resize_file(path_, n);  // cuts the file in place: far cheaper than writing each prefix
      auto check = checkAmsFile(path_);
      ASSERT_FALSE(check.ok()) << name << " cut to " << n << " bytes passes";
      ASSERT_EQ(check.status().code(), StatusCode::kTruncated)
          << name << " cut to " << n << ": " << check.status().message();
    }
  }
}

// Flips one bit of every stride-th byte (bit (i / stride) % 8 of byte i, so every bit position
// is hit). Within the bytes a section's CRC-32 covers, the CRC detects any single-bit error,
// whichever the bit, so a sample is enough for CI; ANIMC_FLIP_STRIDE=1 flips a bit of every
// byte (tests/fuzz/README.md records that sweep).
size_t flipStride() {
  const char* env = std::getenv("ANIMC_FLIP_STRIDE");
  const long stride = env ? std::atol(env) : 0;
  return stride > 0 ? size_t(stride) : 97;
}

TEST_F(AmsCheckTest, RefusesSingleBitFlips) {
  const size_t stride = flipStride();
  for (const std::string& name : goldenAmsFiles()) {
    const Bytes golden = readBytes(kGoldenDir + name);
    ASSERT_FALSE(golden.empty()) << name;
    int flips = 0;
    for (size_t i = 0; i < golden.size(); i += stride, ++flips) {
      Bytes bad = golden;
      bad[i] ^= uint8_t(1u << ((i / stride) % 8));
      writeBytes(path_, bad);
      EXPECT_FALSE(checkAmsFile(path_).ok()) << name << ": bit " << (i / stride) % 8 << " of byte " << i;
    }
    EXPECT_GE(flips, 24) << name;
  }
}

// Damage in the last frame group: opening the file checks the first group only, so it opens;
// the whole-file check finds it.
TEST_F(AmsCheckTest, FindsDamageOpeningDoesNotLookAt) {
  const std::string name = "affine_octree_default.v1.groups.ams";
  Bytes bad = readBytes(kGoldenDir + name);
  auto ams = AmsSource::open(kGoldenDir + name);
  ASSERT_TRUE(ams.ok()) << ams.status().message();
  ASSERT_GE(ams.value()->info().sections.size(), 5u);
  uint64_t last_group = 0;
  for (const SectionInfo& sec : ams.value()->info().sections)
    if (sec.tag == kTagGroup) last_group = sec.offset;
  ASSERT_GT(last_group, 0u);
  bad[size_t(last_group) + 30] ^= 0x10;  // a frame byte, under the group's CRC
  writeBytes(path_, bad);
  EXPECT_TRUE(AmsSource::open(path_).ok());
  auto check = checkAmsFile(path_);
  ASSERT_FALSE(check.ok());
  EXPECT_EQ(check.status().code(), StatusCode::kCorrupt) << check.status().message();
  EXPECT_NE(check.status().message().find("CRC mismatch"), std::string::npos) << check.status().message();
  EXPECT_NE(check.status().message().find(path_), std::string::npos) << check.status().message();
}

}  // namespace
}  // namespace animc
