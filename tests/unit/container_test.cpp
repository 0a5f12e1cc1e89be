// SPDX-License-Identifier: Apache-2.0
// The .ams reader on untrusted files: every truncation and every single-byte corruption of a
// small valid file must be refused with a Status (never a crash, a hang or a silent success),
// with messages that say what is wrong, and the DecoderLimits must be honoured.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "api.h"
#include "codec_test_support.h"
#include "container/crc32.h"
#include "container/format.h"
#include "io/byte_writer.h"
#include "test_sequences.h"

namespace animc {
namespace {

using Bytes = std::vector<uint8_t>;
using testing_support::gridSequence;
using testing_support::tempPath;

Bytes readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Replaces the file at path with exactly these bytes.
// (Unlinked first: truncating a file in place can force a flush to disk on close.)
void writeBytes(const std::string& path, const Bytes& bytes) {
  std::remove(path.c_str());
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr) << path;
  if (!bytes.empty()) {
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
  }
  ASSERT_EQ(std::fclose(f), 0);
}

// Opens the file and decodes every frame: ok only if all of that succeeds. A reader that
// yields more frames than it announced is a failure too (and cannot loop forever here).
Status decodesFully(const std::string& path, const DecoderLimits& limits = {}) {
  auto ams = AmsSource::open(path, limits);
  if (!ams.ok()) return ams.status();
  std::vector<float> xyz;
  for (int64_t f = 0; f <= ams.value()->frameCount(); ++f) {
    Result<bool> more = ams.value()->next(xyz);
    if (!more.ok()) return more.status();
    if (!more.value())
      return f == ams.value()->frameCount() ? Status() : corrupt("stopped after " + std::to_string(f));
  }
  return corrupt("more frames than announced");
}

constexpr int kNx = 6, kNy = 5, kFrames = 9;

// The files attacked: both profiles in format 1, and format 2 (the connectivity's 40
// triangles in pieces of 8).
struct AttackedFile {
  Profile profile;
  uint32_t connectivity_piece;
  const char* name;
};
const AttackedFile kPaperFile{Profile::kPaper, 0, "paper"};
const AttackedFile kPredictiveFile{Profile::kPredictive, 0, "predictive"};
const AttackedFile kFormat2File{Profile::kPredictive, 8, "format2"};

// A 30-vertex, 9-frame file with an I-frame every 4 frames: three GRUP sections.
const Bytes& validFile(const AttackedFile& kind) {
  static std::map<std::string, Bytes> files;
  Bytes& bytes = files[kind.name];
  if (bytes.empty()) {
    MemorySequence seq = gridSequence(kNx, kNy, kFrames, 1.0, 0.5);
    EncodeSettings settings;
    settings.octree().profile = kind.profile;
    settings.iframe_interval = 4;
    settings.connectivity_piece = kind.connectivity_piece;
    const std::string path = tempPath("valid.ams");
    auto report = encodeSequence(seq, settings, path);
    EXPECT_TRUE(report.ok()) << report.status().message();
    bytes = readBytes(path);
    std::remove(path.c_str());
  }
  return bytes;
}

// Names the field holding a byte of the valid file, for failure messages.
std::string fieldAt(const std::string& path, uint64_t offset) {
  if (offset < 4) return "Magic";
  if (offset < 6) return "Format_Version";
  if (offset < kFileHeaderBytes) return "Reserved";
  auto ams = AmsSource::open(path);
  if (!ams.ok()) return "?";
  for (const SectionInfo& s : ams.value()->info().sections) {
    const uint64_t rel = offset - s.offset;
    if (offset < s.offset || rel >= s.payload_bytes + kSectionOverhead) continue;
    const std::string where = s.tag + " at " + std::to_string(s.offset) + ": ";
    if (rel < 4) return where + "Tag";
    if (rel < 12) return where + "Section_Length";
    if (rel >= 12 + s.payload_bytes) return where + "Section_CRC";
    if (s.tag == kTagGroup && rel < 20) return where + "First_Frame";
    if (s.tag == kTagGroup && rel < 24) return where + "Frame_Count";
    return where + "payload byte " + std::to_string(rel - 12);
  }
  return "outside every section";
}

class ContainerAttack : public ::testing::TestWithParam<AttackedFile> {
 protected:
  void TearDown() override { std::remove(path_.c_str()); }
  const std::string path_ = tempPath("attack.ams");
};

TEST_P(ContainerAttack, ValidFileDecodesWithSeveralGroups) {
  const Bytes& file = validFile(GetParam());
  writeBytes(path_, file);
  Status s = decodesFully(path_);
  ASSERT_TRUE(s.ok()) << s.message();
  auto ams = AmsSource::open(path_);
  ASSERT_TRUE(ams.ok());
  EXPECT_EQ(ams.value()->info().groupCount(), 3u);
  EXPECT_EQ(ams.value()->frameCount(), kFrames);
  EXPECT_EQ(ams.value()->info().file_bytes, file.size());
}

TEST_P(ContainerAttack, EveryTruncationFailsCleanly) {
  const Bytes& file = validFile(GetParam());
  ASSERT_FALSE(file.empty());
  for (size_t n = 0; n < file.size(); ++n) {
    writeBytes(path_, Bytes(file.begin(), file.begin() + n));
    Status s = decodesFully(path_);
    ASSERT_FALSE(s.ok()) << "a " << n << "-byte prefix of a " << file.size() << "-byte file decodes";
    ASSERT_TRUE(s.code() == StatusCode::kTruncated || s.code() == StatusCode::kCorrupt)
        << n << " bytes: " << statusCodeName(s.code()) << ": " << s.message();
  }
}

TEST_P(ContainerAttack, EverySingleByteCorruptionIsDetected) {
  const Bytes& file = validFile(GetParam());
  const std::string valid_path = tempPath("valid_copy.ams");
  writeBytes(valid_path, file);
  std::string undetected;
  for (uint8_t mask : {uint8_t(0x01), uint8_t(0xFF)}) {
    for (size_t i = 0; i < file.size(); ++i) {
      Bytes bad = file;
      bad[i] ^= mask;
      writeBytes(path_, bad);
      if (decodesFully(path_).ok())
        undetected += "\n  byte " + std::to_string(i) + " ^ " + std::to_string(mask) + " (" +
                      fieldAt(valid_path, i) + ")";
    }
  }
  std::remove(valid_path.c_str());
  EXPECT_TRUE(undetected.empty()) << "corruptions that decode without error:" << undetected;
}

TEST_P(ContainerAttack, BytesAfterTheEndSectionAreRejected) {
  const Bytes& file = validFile(GetParam());
  Bytes longer = file;
  longer.push_back(0);
  writeBytes(path_, longer);
  EXPECT_FALSE(decodesFully(path_).ok()) << "one byte appended";
  // A second, valid END section: the last 24 bytes are fine, but INDX is no longer before them.
  longer = file;
  longer.insert(longer.end(), file.end() - kEndSectionBytes, file.end());
  writeBytes(path_, longer);
  EXPECT_FALSE(decodesFully(path_).ok()) << "END section repeated";
}

// Flips payload bytes of every section and repairs that section's CRC, so the damage gets past
// the checksums to the parsers and decoders behind them: they may accept or refuse it, but
// must never crash (ASan build) or hang.
TEST_P(ContainerAttack, DamageBehindAValidCrcNeverCrashes) {
  const Bytes& file = validFile(GetParam());
  writeBytes(path_, file);
  std::vector<SectionInfo> sections;
  {
    auto ams = AmsSource::open(path_);
    ASSERT_TRUE(ams.ok()) << ams.status().message();
    sections = ams.value()->info().sections;
  }
  int cases = 0, refused = 0;
  for (const SectionInfo& sec : sections) {
    // The GRUP CRC covers its frames only, not First_Frame and Frame_Count.
    const size_t begin = size_t(sec.offset) + 12 + (sec.tag == kTagGroup ? kGroupFieldBytes : 0);
    const size_t end = size_t(sec.offset + 12 + sec.payload_bytes);
    for (size_t i = begin; i < end; ++i)
      for (uint8_t mask : {uint8_t(0x01), uint8_t(0xFF)}) {
        Bytes bad = file;
        bad[i] ^= mask;
        const uint32_t crc = crc32Update(0, bad.data() + begin, end - begin);
        for (int k = 0; k < 4; ++k) bad[end + k] = uint8_t(crc >> (8 * k));
        writeBytes(path_, bad);
        ++cases;
        refused += !decodesFully(path_).ok();
      }
  }
  EXPECT_GT(cases, 1000);
  EXPECT_GT(refused, 0) << "the structural checks behind the CRCs never fired";
}

INSTANTIATE_TEST_SUITE_P(Files, ContainerAttack, ::testing::Values(kPaperFile, kPredictiveFile, kFormat2File),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(ContainerFormats, TheConnectivityInPiecesIsFormatTwoAndDecodesTheSame) {
  const Bytes& one = validFile(kPredictiveFile);
  const Bytes& two = validFile(kFormat2File);
  EXPECT_EQ(one[4], 1);
  EXPECT_EQ(two[4], 2);
  std::vector<std::vector<float>> frames[2];
  int i = 0;
  for (const Bytes* file : {&one, &two}) {
    const std::string path = tempPath("format.ams");
    writeBytes(path, *file);
    auto ams = AmsSource::open(path);
    ASSERT_TRUE(ams.ok()) << ams.status().message();
    EXPECT_EQ(ams.value()->info().format_version, i + 1);
    std::vector<float> xyz;
    while (ams.value()->next(xyz).value()) frames[i].push_back(xyz);
    std::remove(path.c_str());
    ++i;
  }
  EXPECT_EQ(frames[0].size(), size_t(kFrames));
  EXPECT_EQ(frames[0], frames[1]);
}

class ContainerErrors : public ::testing::Test {
 protected:
  void TearDown() override { std::remove(path_.c_str()); }
  Status openWith(const Bytes& bytes, const DecoderLimits& limits = {}) {
    writeBytes(path_, bytes);
    return decodesFully(path_, limits);
  }
  const Bytes& file_ = validFile(kPredictiveFile);
  const std::string path_ = tempPath("errors.ams");
};

// A file cut short (an interrupted copy or download) should be reported as such, not only as
// "expected section END": whatever the prefix, the message says "truncated" or "ends".
TEST_F(ContainerErrors, TruncatedFileIsReportedAsTruncated) {
  for (size_t n : {size_t(0), size_t(5), size_t(kFileHeaderBytes + kEndSectionBytes - 1), size_t(40),
                   file_.size() / 2, file_.size() - 1}) {
    Status s = openWith(Bytes(file_.begin(), file_.begin() + n));
    EXPECT_TRUE(s.code() == StatusCode::kTruncated || s.code() == StatusCode::kCorrupt) << n;
    EXPECT_TRUE(s.message().find("truncated") != std::string::npos || s.message().find("ends") != std::string::npos)
        << n << "-byte prefix: " << statusCodeName(s.code()) << ": " << s.message();
  }
}

Bytes goldenBytes(const std::string& name) {
  return readBytes(std::string(ANIMC_SOURCE_DIR) + "/tests/golden/" + name);
}

// docs/format.md section 5, rule 4: a section whose Length runs past the end of the file is
// Truncated, whatever the Length. A cut file whose CONN Length exceeded the cut size was once
// reported as "CONN section too large" (Limit_Exceeded).
TEST_F(ContainerErrors, EveryPrefixOfAGoldenFileIsTruncated) {
  for (const char* name : {"affine_octree_default.v1.ams", "wavelet.v1.ams"}) {
    const Bytes golden = goldenBytes(name);
    ASSERT_FALSE(golden.empty()) << name;
    for (size_t n = 0; n < golden.size(); ++n) {
      Status s = openWith(Bytes(golden.begin(), golden.begin() + n));
      ASSERT_EQ(s.code(), StatusCode::kTruncated)
          << name << " cut to " << n << " bytes: " << statusCodeName(s.code()) << ": " << s.message();
    }
  }
}

// A cut inside CONN names CONN, both where its Length still fits the cut file and where it
// exceeds the whole cut file.
TEST_F(ContainerErrors, ACutInsideConnNamesConn) {
  const Bytes golden = goldenBytes("affine_octree_default.v1.ams");
  writeBytes(path_, golden);
  uint64_t conn = 0, length = 0;
  {
    auto ams = AmsSource::open(path_);
    ASSERT_TRUE(ams.ok()) << ams.status().message();
    for (const SectionInfo& sec : ams.value()->info().sections)
      if (sec.tag == kTagConnectivity) conn = sec.offset, length = sec.payload_bytes;
  }
  ASSERT_GT(length, conn + 12) << "the golden file's CONN no longer outgrows its short prefixes";
  for (uint64_t n : {conn + 12, length - 1, conn + 12 + length / 2, conn + 15 + length}) {
    Status s = openWith(Bytes(golden.begin(), golden.begin() + n));
    EXPECT_EQ(s.code(), StatusCode::kTruncated) << n << ": " << s.message();
    EXPECT_NE(s.message().find("CONN section"), std::string::npos) << n << ": " << s.message();
    EXPECT_NE(s.message().find("truncated"), std::string::npos) << n << ": " << s.message();
  }
}

TEST_F(ContainerErrors, BadMagicVersionAndCrcAreNamed) {
  Bytes bad = file_;
  bad[1] = 'X';
  Status s = openWith(bad);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("not an .ams file"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find(path_), std::string::npos) << "names the file: " << s.message();

  bad = file_;
  bad[4] = uint8_t(kNewestFormatVersion + 1);
  s = openWith(bad);
  EXPECT_EQ(s.code(), StatusCode::kUnsupported) << s.message();
  EXPECT_NE(s.message().find("version " + std::to_string(kNewestFormatVersion + 1)), std::string::npos) << s.message();
  bad[4] = 0;
  EXPECT_EQ(openWith(bad).code(), StatusCode::kUnsupported) << "format version 0";

  bad = file_;
  bad[kFileHeaderBytes + 12] ^= 0x10;  // first HEAD payload byte (Codec_Id), CRC now wrong
  s = openWith(bad);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("CRC"), std::string::npos) << s.message();
}

// The file with byte `at` of the HEAD payload set to `value` and the section's CRC made right
// again: a file a newer encoder could have written.
Bytes withHeadByte(Bytes file, size_t at, uint8_t value) {
  const size_t payload = kFileHeaderBytes + 12;
  uint64_t length = 0;
  for (int k = 0; k < 8; ++k) length |= uint64_t(file[kFileHeaderBytes + 4 + k]) << (8 * k);
  file[payload + at] = value;
  const uint32_t crc = crc32Update(0, file.data() + payload, length);
  for (int k = 0; k < 4; ++k) file[payload + length + k] = uint8_t(crc >> (8 * k));
  return file;
}

// A codec or profile of a later release is reported as unsupported, naming what was found,
// not as a corrupt file; the byte left as it was still decodes (the CRC repair is sound).
TEST_F(ContainerErrors, UnknownCodecAndProfileAreUnsupported) {
  EXPECT_TRUE(openWith(withHeadByte(file_, 0, file_[kFileHeaderBytes + 12])).ok());
  Status s = openWith(withHeadByte(file_, 0, 9));  // Codec_Id
  EXPECT_EQ(s.code(), StatusCode::kUnsupported) << s.message();
  EXPECT_NE(s.message().find("codec id 9"), std::string::npos) << s.message();
  s = openWith(withHeadByte(file_, 2, 7));  // Profile, after the 1-byte Codec_Params_Length
  EXPECT_EQ(s.code(), StatusCode::kUnsupported) << s.message();
  EXPECT_NE(s.message().find("profile 7"), std::string::npos) << s.message();
}

// A File_Header and a HEAD section with a correct CRC, padded so the file is long enough to
// be looked at; the limits must be checked before CONN is read or anything is allocated.
Bytes craftedHead(uint32_t vertex_count, uint64_t triangle_count) {
  ByteWriter head;
  head.u8(uint8_t(CodecId::kAffineOctree));
  ByteWriter params;
  AffineOctreeOptions().write(params);
  head.varint(params.size());
  head.append(params.bytes());
  head.u32(vertex_count);
  head.u64(triangle_count);
  head.f64(25.0);
  head.u32(0);
  ByteWriter file;
  file.append(kMagic, 4);
  file.u16(1);
  file.u16(0);
  file.append(reinterpret_cast<const uint8_t*>(kTagHead), 4);
  file.u64(head.size());
  file.append(head.bytes());
  file.u32(crc32Update(0, head.bytes().data(), head.size()));
  Bytes bytes = file.bytes();
  bytes.resize(bytes.size() + 64, 0);
  return bytes;
}

TEST_F(ContainerErrors, HugeCountsInAValidHeadAreRefused) {
  Status s = openWith(craftedHead(uint32_t(1) << 31, 1));
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
  EXPECT_NE(s.message().find("Vertex_Count"), std::string::npos) << s.message();
  s = openWith(craftedHead(0, 1));  // no vertices: not a limit, a broken file
  EXPECT_EQ(s.code(), StatusCode::kCorrupt) << s.message();
  s = openWith(craftedHead(3, uint64_t(1) << 40));
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
  EXPECT_NE(s.message().find("Triangle_Count"), std::string::npos) << s.message();
  // The crafted header itself is well-formed: with sane counts the reader gets past HEAD.
  s = openWith(craftedHead(3, 1));
  EXPECT_NE(s.code(), StatusCode::kLimitExceeded) << s.message();
}

TEST_F(ContainerErrors, DecoderLimitsAreHonoured) {
  const uint64_t vertices = kNx * kNy, triangles = 2 * (kNx - 1) * (kNy - 1);
  DecoderLimits limits;
  limits.max_vertices = vertices;
  limits.max_triangles = triangles;
  limits.max_frames = kFrames;
  EXPECT_TRUE(openWith(file_, limits).ok()) << "limits equal to the file's counts";
  limits.max_vertices = vertices - 1;
  Status s = openWith(file_, limits);
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
  limits = DecoderLimits();
  limits.max_triangles = triangles - 1;
  s = openWith(file_, limits);
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
}

// StatusCode::kLimitExceeded is documented as "a count or size above the decoder's ceilings";
// the frame count and frame size ceilings must report it too (not as a corrupt file).
TEST_F(ContainerErrors, FrameLimitsReportLimitExceeded) {
  DecoderLimits limits;
  limits.max_frames = kFrames - 1;
  Status s = openWith(file_, limits);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
  limits = DecoderLimits();
  limits.max_frame_bytes = 4;
  s = openWith(file_, limits);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded) << s.message();
}


// The check value of the CRC-32 of ISO-HDLC, and continuing a CRC from any split point gives
// the CRC of the whole (the eight-byte steps and the byte steps agree).
TEST(Crc32, CheckValueAndContinuation) {
  const std::string check = "123456789";
  EXPECT_EQ(crc32Update(0, reinterpret_cast<const uint8_t*>(check.data()), check.size()), 0xCBF43926u);
  EXPECT_EQ(crc32Update(0, nullptr, 0), 0u);
  Bytes data(1000);
  for (size_t i = 0; i < data.size(); ++i) data[i] = uint8_t(i * 37 + (i >> 3));
  uint32_t bitwise = 0xFFFFFFFFu;
  for (uint8_t b : data) {
    bitwise ^= b;
    for (int k = 0; k < 8; ++k) bitwise = (bitwise >> 1) ^ (0xEDB88320u & (0u - (bitwise & 1u)));
  }
  bitwise = ~bitwise;
  for (size_t split : {0, 1, 7, 8, 9, 500, 999, 1000})
    EXPECT_EQ(crc32Update(crc32Update(0, data.data(), split), data.data() + split, data.size() - split), bitwise)
        << split;
}

}  // namespace
}  // namespace animc
