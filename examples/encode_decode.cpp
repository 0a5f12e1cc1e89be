// SPDX-License-Identifier: Apache-2.0
// Encodes 50 frames of a waving sheet from memory, then decodes frame 17 alone from the bytes.
//   encode_decode OUT.ams FRAME17.bin
// writes the stream and frame 17 as raw little-endian floats (x y z per vertex).
#include <animc/animc.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace {

constexpr uint32_t kSide = 40;  // vertices per side of the sheet
constexpr int kFrames = 50;

std::vector<uint32_t> sheetTriangles() {
  std::vector<uint32_t> triangles;
  for (uint32_t y = 0; y + 1 < kSide; ++y)
    for (uint32_t x = 0; x + 1 < kSide; ++x) {
      const uint32_t v = y * kSide + x;
      triangles.insert(triangles.end(), {v, v + 1, v + kSide, v + 1, v + kSide + 1, v + kSide});
    }
  return triangles;
}

std::vector<float> sheetFrame(int frame) {
  std::vector<float> xyz;
  for (uint32_t y = 0; y < kSide; ++y)
    for (uint32_t x = 0; x < kSide; ++x)
      xyz.insert(xyz.end(), {float(x), float(y), 3.0f * std::sin(0.2f * float(x) + 0.15f * float(frame))});
  return xyz;
}

int fail(const animc::Status& status) {
  std::fprintf(stderr, "encode_decode: %s\n", status.message().c_str());
  return 1;
}

bool writeFile(const char* path, const void* data, size_t size) {
  std::FILE* f = std::fopen(path, "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: encode_decode OUT.ams FRAME17.bin\n");
    return 2;
  }
  const std::vector<uint32_t> triangles = sheetTriangles();
  animc::EncoderOptions options;
  options.set("max-error", 0.002);
  options.iframe_interval = 10;  // frame 17 then costs frames 10 to 17, not 0 to 17

  std::vector<uint8_t> stream;
  auto encoder = animc::Encoder::create(options, kSide * kSide, triangles.data(), triangles.size() / 3,
                                        animc::memorySink(&stream));
  if (!encoder.ok()) return fail(encoder.status());
  for (int f = 0; f < kFrames; ++f) {
    animc::Status s = encoder.value().addFrame(sheetFrame(f).data());
    if (!s.ok()) return fail(s);
  }
  auto summary = encoder.value().finish();
  if (!summary.ok()) return fail(summary.status());

  auto decoder = animc::Decoder::openMemory(stream.data(), stream.size());
  if (!decoder.ok()) return fail(decoder.status());
  std::vector<float> frame17(3 * size_t(decoder.value().info().vertices));
  animc::Status s = decoder.value().frame(17, frame17.data());
  if (!s.ok()) return fail(s);

  std::printf("animc %s: %d frames in %llu bytes (%.1f:1), frame 17 decoded\n", animc::animcVersion(), kFrames,
              (unsigned long long)summary.value().bytes,
              animc::sizeFigures(summary.value().bytes, summary.value().static_bytes, kSide * kSide, kFrames).ratio);
  if (!writeFile(argv[1], stream.data(), stream.size()) ||
      !writeFile(argv[2], frame17.data(), frame17.size() * sizeof(float))) {
    std::fprintf(stderr, "encode_decode: cannot write the outputs\n");
    return 1;
  }
  return 0;
}
