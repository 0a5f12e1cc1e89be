// SPDX-License-Identifier: Apache-2.0
// The WebAssembly decoder's C ABI (web/animcompress.mjs calls it): a thin adapter over the
// library's Decoder, as the Python module and the plugins are. Counts cross as doubles (exact
// below 2^53), so that JavaScript needs no BigInt. Errors leave a status code and a message
// that animc_error_code() and animc_error_message() give until the next call.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "animc/animc.h"

#define ANIMC_WEB_EXPORT extern "C" __attribute__((used, visibility("default")))

namespace {

struct WebStream {
  std::vector<uint8_t> bytes;  // what the decoder reads in place (a moved vector keeps its buffer)
  animc::Decoder decoder;
};

int last_code = 0;
std::string last_message;

void remember(const animc::Status& status) {
  last_code = int(status.code());
  last_message = status.message();
}

// The DecoderLimits in the order animcompress.mjs passes them; a value ≤ 0 keeps the default.
animc::DecoderLimits limitsFrom(const double* values) {
  animc::DecoderLimits limits;
  if (values == nullptr) return limits;
  uint64_t* fields[] = {&limits.max_vertices,      &limits.max_triangles,    &limits.max_frames,
                        &limits.max_frame_bytes,   &limits.max_vertex_frames, &limits.max_output_bytes,
                        &limits.max_multiply_adds};
  for (size_t i = 0; i < sizeof(fields) / sizeof(fields[0]); ++i)
    if (values[i] > 0) *fields[i] = uint64_t(values[i]);
  return limits;
}

}  // namespace

ANIMC_WEB_EXPORT void* animc_alloc(size_t size) { return std::malloc(size); }
ANIMC_WEB_EXPORT void animc_free(void* p) { std::free(p); }
ANIMC_WEB_EXPORT int animc_error_code() { return last_code; }
ANIMC_WEB_EXPORT const char* animc_error_message() { return last_message.c_str(); }

// Opens `size` bytes at `data` (from animc_alloc; freed here). whole_groups_only: the bytes are
// the start of a stream still arriving, and the stream opened is their whole groups
// (wholeGroupsOf()); then a null result with error code 0 means no whole group yet.
ANIMC_WEB_EXPORT WebStream* animc_open(uint8_t* data, size_t size, int whole_groups_only, const double* limits) {
  last_code = 0;
  last_message.clear();
  std::vector<uint8_t> bytes;
  if (whole_groups_only) {
    auto frames = animc::wholeGroupsOf(data, size, animc::memorySink(&bytes));
    std::free(data);
    if (!frames.ok()) return remember(frames.status()), nullptr;
    if (frames.value() == 0) return nullptr;
  } else {
    bytes.assign(data, data + size);
    std::free(data);
  }
  animc::DecoderOptions options;
  options.limits = limitsFrom(limits);
  options.threads = 1;  // a Web Worker is the browser's thread; this build has no others
  auto decoder = animc::Decoder::openMemory(bytes.data(), bytes.size(), options, "stream");
  if (!decoder.ok()) return remember(decoder.status()), nullptr;
  return new WebStream{std::move(bytes), std::move(decoder).value()};
}

ANIMC_WEB_EXPORT void animc_close(WebStream* s) { delete s; }
ANIMC_WEB_EXPORT double animc_vertex_count(WebStream* s) { return s->decoder.info().vertices; }
ANIMC_WEB_EXPORT double animc_triangle_count(WebStream* s) { return double(s->decoder.info().triangles); }
ANIMC_WEB_EXPORT double animc_frame_count(WebStream* s) { return double(s->decoder.info().frames); }
ANIMC_WEB_EXPORT double animc_frame_rate(WebStream* s) { return s->decoder.info().frame_rate; }
ANIMC_WEB_EXPORT double animc_group_count(WebStream* s) { return double(s->decoder.info().groups); }
ANIMC_WEB_EXPORT double animc_stream_bytes(WebStream* s) { return double(s->decoder.info().bytes); }
ANIMC_WEB_EXPORT const char* animc_codec(WebStream* s) { return s->decoder.info().codec.c_str(); }
ANIMC_WEB_EXPORT const uint32_t* animc_triangles(WebStream* s) { return s->decoder.triangles(); }

// Decodes frame k into 3 × vertex count floats at xyz; returns the status code (0: done).
ANIMC_WEB_EXPORT int animc_frame(WebStream* s, double k, float* xyz) {
  const animc::Status status = s->decoder.frame(int64_t(k), xyz);
  if (!status.ok()) remember(status);
  return int(status.code());
}
