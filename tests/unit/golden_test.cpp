// SPDX-License-Identifier: Apache-2.0
// Frozen .ams files must keep decoding to exactly the same frames, and today's encoder must
// still write them byte for byte: a change to a codec's bytes is a new codec version with new
// golden files beside these (docs/format.md, "Reference files"), never a rewrite of them.
// tests/golden/check_goldens.py checks the other golden files through the animc tool.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "api.h"
#include "codec_test_support.h"
#include "container/crc32.h"
#include "test_sequences.h"

namespace animc {
namespace {

const std::string kGoldenDir = std::string(ANIMC_SOURCE_DIR) + "/tests/golden/";
const std::string kExpected = kGoldenDir + "expected_crc32.txt";

// CRC-32 of every decoded frame's float bytes, in order.
uint32_t decodedCrc(const std::string& path) {
  uint32_t crc = 0;
  for (const std::vector<float>& xyz : testing_support::decodeAll(path))
    crc = crc32Update(crc, reinterpret_cast<const uint8_t*>(xyz.data()), xyz.size() * sizeof(float));
  return crc;
}

std::map<std::string, uint32_t> readExpected() {
  std::map<std::string, uint32_t> out;
  std::ifstream in(kExpected);
  std::string name;
  uint32_t crc;
  while (in >> name >> std::hex >> crc) out[name] = crc;
  return out;
}

struct GoldenFile {
  EncodeSettings settings;
  // False for a file older than the range coder's shorter stream ends (format.md, changelog):
  // today's encoder writes other bytes for it, which decode to the same frames, so it is a
  // decoder golden only (tests/golden/manifest.txt has encoder goldens of every codec).
  bool encoder_golden;
};

// The settings each frozen file was made with (a deforming, rotating 12x10 grid, 20 frames,
// an intra frame every 8).
std::map<std::string, GoldenFile> goldenFiles() {
  std::map<std::string, GoldenFile> files;
  EncodeSettings paper, predictive, wavelet;
  paper.octree().profile = Profile::kPaper;
  predictive.octree().profile = Profile::kPredictive;
  wavelet.options = WaveletOptions();
  wavelet.wavelet().step = 1e-3;
  files["affine_octree_paper.v1.ams"] = {paper, false};
  files["affine_octree_default.v1.ams"] = {predictive, true};
  files["wavelet.v1.ams"] = {wavelet, false};
  for (auto& [name, file] : files) file.settings.iframe_interval = 8;
  return files;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Golden, FrozenFilesDecodeToTheSameFrames) {
  const std::map<std::string, GoldenFile> files = goldenFiles();
  const auto expected = readExpected();
  ASSERT_EQ(expected.size(), files.size()) << "missing " << kExpected;
  for (const auto& [name, file] : files)
    EXPECT_EQ(decodedCrc(kGoldenDir + name), expected.at(name)) << name;
}

TEST(Golden, TheEncoderStillWritesTheFrozenFiles) {
  for (const auto& [name, file] : goldenFiles()) {
    if (!file.encoder_golden) continue;
    MemorySequence seq = testing_support::gridSequence(12, 10, 20, 1.0, 0.5);
    const std::string path = testing_support::tempPath("golden_" + name);
    ASSERT_TRUE(encodeSequence(seq, file.settings, path).ok()) << name;
    const std::string golden = fileBytes(kGoldenDir + name);
    ASSERT_FALSE(golden.empty()) << "missing " << name;
    EXPECT_TRUE(fileBytes(path) == golden) << name << ": the encoder's bytes differ from the golden file";
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace animc
