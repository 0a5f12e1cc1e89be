// SPDX-License-Identifier: Apache-2.0
// The WebAssembly decoder's C ABI (web/animcompress.mjs calls it): a thin adapter over the
// library's Decoder, as the Python module and the plugins are. Counts cross as doubles (exact
// below 2^53), so that JavaScript needs no BigInt. A call that fails leaves its status code and
// message for animc_error_code() and animc_error_message(), until another call fails (or
// animc_open() starts).
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "animc/animc.h"

#define ANIMC_WEB_EXPORT extern "C" __attribute__((used, visibility("default")))

namespace {

// What the decoder reads in place: the caller's buffer, or the whole groups made of it.
struct WebStream {
  std::unique_ptr<uint8_t, decltype(&std::free)> given;
  std::vector<uint8_t> whole_groups;  // a moved vector keeps its buffer
  std::optional<animc::Decoder> decoder;
};

int last_code = 0;
std::string last_message;

void remember(const animc::Status& status) {
  last_code = int(status.code());
  last_message = status.message();
}

// The DecoderLimits in the order animcompress.mjs passes them (which refuses NaN): 0 keeps
// the default, 2^64 and above (Infinity) mean none.
animc::DecoderLimits limitsFrom(const double* values) {
  animc::DecoderLimits limits;
  if (values == nullptr) return limits;
  uint64_t* fields[] = {&limits.max_vertices,      &limits.max_triangles,    &limits.max_frames,
                        &limits.max_frame_bytes,   &limits.max_vertex_frames, &limits.max_output_bytes,
                        &limits.max_multiply_adds};
  for (size_t i = 0; i < sizeof(fields) / sizeof(fields[0]); ++i) {
    if (!(values[i] > 0)) continue;
    *fields[i] = values[i] >= 18446744073709551616.0 ? UINT64_MAX : uint64_t(values[i]);
  }
  return limits;
}

}  // namespace

ANIMC_WEB_EXPORT void* animc_alloc(size_t size) { return std::malloc(size); }
ANIMC_WEB_EXPORT void animc_free(void* p) { std::free(p); }
ANIMC_WEB_EXPORT int animc_error_code() { return last_code; }
ANIMC_WEB_EXPORT const char* animc_error_message() { return last_message.c_str(); }

// Opens `size` bytes at `data` (from animc_alloc; the stream owns them, or frees them when the
// open fails). whole_groups_only: the bytes are the start of a stream still arriving, and the
// stream opened is their whole groups (wholeGroupsOf()); then a null result with error code 0
// means no whole group yet.
ANIMC_WEB_EXPORT WebStream* animc_open(uint8_t* data, size_t size, int whole_groups_only, const double* limits) {
  last_code = 0;
  last_message.clear();
  auto stream = std::make_unique<WebStream>(WebStream{{data, &std::free}, {}, std::nullopt});
  if (whole_groups_only) {
    auto frames = animc::wholeGroupsOf(data, size, animc::memorySink(&stream->whole_groups));
    stream->given.reset();
    if (!frames.ok()) return remember(frames.status()), nullptr;
    if (frames.value() == 0) return nullptr;
    data = stream->whole_groups.data();
    size = stream->whole_groups.size();
  }
  animc::DecoderOptions options;
  options.limits = limitsFrom(limits);
  options.threads = 1;  // a Web Worker is the browser's thread; this build has no others
  auto decoder = animc::Decoder::openMemory(data, size, options, "stream");
  if (!decoder.ok()) return remember(decoder.status()), nullptr;
  stream->decoder.emplace(std::move(decoder).value());
  return stream.release();
}

ANIMC_WEB_EXPORT void animc_close(WebStream* s) { delete s; }
ANIMC_WEB_EXPORT double animc_vertex_count(WebStream* s) { return s->decoder->info().vertices; }
ANIMC_WEB_EXPORT double animc_triangle_count(WebStream* s) { return double(s->decoder->info().triangles); }
ANIMC_WEB_EXPORT double animc_frame_count(WebStream* s) { return double(s->decoder->info().frames); }
ANIMC_WEB_EXPORT double animc_frame_rate(WebStream* s) { return s->decoder->info().frame_rate; }
ANIMC_WEB_EXPORT double animc_group_count(WebStream* s) { return double(s->decoder->info().groups); }
ANIMC_WEB_EXPORT double animc_stream_bytes(WebStream* s) { return double(s->decoder->info().bytes); }
ANIMC_WEB_EXPORT const char* animc_codec(WebStream* s) { return s->decoder->info().codec.c_str(); }
ANIMC_WEB_EXPORT const uint32_t* animc_triangles(WebStream* s) { return s->decoder->triangles(); }

// Decodes frame k into 3 × vertex count floats at xyz; returns the status code (0: done).
ANIMC_WEB_EXPORT int animc_frame(WebStream* s, double k, float* xyz) {
  const animc::Status status = s->decoder->frame(int64_t(k), xyz);
  if (!status.ok()) remember(status);
  return int(status.code());
}
