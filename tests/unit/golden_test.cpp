// SPDX-License-Identifier: Apache-2.0
// Frozen .ams files must keep decoding to exactly the same frames: any change to the decoder
// or the format that alters them shows up here. Regenerate deliberately (and bump the format
// version if old files would change meaning) with ANIMC_UPDATE_GOLDEN=1.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
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

// The settings each frozen file was made with (a deforming, rotating 12x10 grid, 20 frames,
// an intra frame every 8).
std::map<std::string, EncodeSettings> goldenFiles() {
  std::map<std::string, EncodeSettings> files;
  EncodeSettings paper, predictive, wavelet;
  paper.octree.profile = Profile::kPaper;
  predictive.octree.profile = Profile::kDefault;
  wavelet.codec = CodecId::kWavelet;
  wavelet.wavelet.step = 1e-3;
  files["affine_octree_paper.v1.ams"] = paper;
  files["affine_octree_default.v1.ams"] = predictive;
  files["wavelet.v1.ams"] = wavelet;
  for (auto& [name, settings] : files) settings.iframe_interval = 8;
  return files;
}

TEST(Golden, FrozenFilesDecodeToTheSameFrames) {
  const std::map<std::string, EncodeSettings> files = goldenFiles();
  if (std::getenv("ANIMC_UPDATE_GOLDEN")) {
    std::ofstream expected(kExpected);
    for (const auto& [name, settings] : files) {
      MemorySequence seq = testing_support::gridSequence(12, 10, 20, 1.0, 0.5);
      ASSERT_TRUE(encodeSequence(seq, settings, kGoldenDir + name).ok());
      char line[64];
      std::snprintf(line, sizeof line, "%s %08x\n", name.c_str(), decodedCrc(kGoldenDir + name));
      expected << line;
    }
  }
  const auto expected = readExpected();
  ASSERT_EQ(expected.size(), files.size()) << "missing " << kExpected;
  for (const auto& [name, settings] : files)
    EXPECT_EQ(decodedCrc(kGoldenDir + name), expected.at(name)) << name;
}

}  // namespace
}  // namespace animc
