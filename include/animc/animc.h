// SPDX-License-Identifier: Apache-2.0
// animcompress: compression of animated triangle meshes (one triangle list, moving vertices)
// into .ams streams. This is the library's public interface and the only header a program
// includes; link animcompress::animc (CMake) or `pkg-config --libs animc`.
//
//   Encoder: frames in, an .ams stream out to a file or to memory (or any ByteSink).
//   Decoder: an .ams stream from a file or from memory, frame k out, in any order.
//   MetricsAccumulator: the error figures (KG, PSNR, max error) of a reconstruction.
//   StedAccumulator: its perceptual figure (STED).
//
// Errors: nothing here throws (except std::bad_alloc when memory runs out, and value() of a
// Result that holds an error); every fallible call returns a Status or a Result<T>, whose
// message names what is at fault. A moved-from Encoder or Decoder may only be destroyed or
// assigned to.
// Threads: an object is used by one thread at a time; different objects, on any threads, are
// independent and safe to use in parallel. An Encoder or Decoder may itself use several threads
// for one call (EncoderOptions::threads, DecoderOptions::threads); what it writes or decodes is
// the same, to the bit, whatever their number.
// Frames are 3 * vertex_count floats, x y z of vertex 0, then of vertex 1, ...; triangles are
// 3 * triangle_count vertex indices.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "animc/version.h"

#if defined(_WIN32)
#define ANIMC_API
#else
#define ANIMC_API __attribute__((visibility("default")))
#endif

namespace animc {

// The version of the library actually linked: it differs from ANIMC_VERSION_STRING, the
// version of this header, when a program runs with another shared library than it was built
// with. The .ams format has its own version; every release reads every format-1 stream.
ANIMC_API const char* animcVersion();

// ---- Status -------------------------------------------------------------------------------

// Stable values: animc exits with them, docs/format.md lists them.
enum class StatusCode : int {
  kOk = 0,
  kInvalidArgument = 2,  // the caller asked for something impossible (bad option value)
  kIoError = 3,          // the operating system refused a read, write or rename
  kBadInput = 4,         // an input sequence is unusable (NaN, differing counts, bad faces)
  kTruncated = 5,        // a stream ends before a field it announces
  kCorrupt = 6,          // a stream field or checksum is wrong
  kUnsupported = 7,      // a format version, codec id or codec profile this build does not read
  kLimitExceeded = 8,    // a count or size above the decoder's limits (DecoderLimits)
  kCancelled = 9,        // the progress callback asked to stop
};

ANIMC_API const char* statusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // Prefixes context ("frames/12.ply: ") so messages read outermost first.
  Status withContext(const std::string& context) const {
    return ok() ? *this : Status(code_, context + ": " + message_);
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

// A value or the Status explaining why there is none.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}         // NOLINT: implicit by design, like StatusOr
  Result(Status status) : v_(std::move(status)) {}  // NOLINT
  bool ok() const { return v_.index() == 0; }
  const Status& status() const {
    static const Status kOkStatus;
    return ok() ? kOkStatus : std::get<1>(v_);
  }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }

 private:
  std::variant<T, Status> v_;
};

// Progress: percent 0..100 and what is being done; return false to cancel.
using ProgressFn = std::function<bool(int percent, const char* what)>;

// ---- Encoding -----------------------------------------------------------------------------

// What to write. Codec options are named as `animc encode`'s flags without the dashes
// ("max-error", "target-kg", "bits", "profile", ...; `animc --help` lists each codec's);
// a switch is set with the value "1". An option the chosen codec does not have is an error.
// EncoderOptions::connectivity_piece's default: a few bytes a piece against megabytes of
// connectivity, and a mesh of fewer triangles is written as format 1, as before.
constexpr uint32_t kDefaultConnectivityPiece = 65536;

struct EncoderOptions {
  // "affine-octree" (the default), "wavelet", "trajectory" or "auto". `animc encode` and the
  // MeshLab filter default to "auto", the smallest files at about affine-octree's speed
  // (docs/benchmarks.md); the library keeps 1.0's default so that a program written for 1.0
  // writes the same codec and its options ("profile", "bits") still apply. Say codec = "auto"
  // for what animc writes.
  std::string codec = "affine-octree";
  std::map<std::string, std::string> values;
  uint32_t iframe_interval = 0;  // an intra frame (a random-access point) every K frames; 0 = the first only
  double frame_rate = 25.0;      // stored in the stream for players
  // Threads the encoder may use: 0 = one per core, 1 = the calling thread only. Frame groups
  // are coded several at once (one per thread, so memory grows to one group a thread; the
  // affine-octree and wavelet codecs only for groups of at most 128 MB of frames), and
  // the trajectory codec splits one group's work; the bytes written do not depend on it. The
  // default is 1, unlike animc's and DecoderOptions': with more threads, reconstruction()
  // knows a frame later (reconstructedFrames() says when), and a program written for 1.x that
  // reads the reconstruction of each frame as it adds it keeps working.
  uint32_t threads = 1;
  // Triangles per piece of the connectivity: a mesh of more triangles is written as .ams
  // format 2, whose connectivity pieces a decoder's threads decode at once, and which
  // animcompress before 1.2 cannot read. 0 = one piece: format 1, for those readers.
  uint32_t connectivity_piece = kDefaultConnectivityPiece;

  EncoderOptions& set(const std::string& name, const std::string& value) {
    values[name] = value;
    return *this;
  }
  ANIMC_API EncoderOptions& set(const std::string& name, double value);
  // The options checked against the codec (names, ranges), as an encoder would check them.
  ANIMC_API Status validate() const;
};

// The codecs this library writes and reads, by name ("affine-octree", "wavelet", ...).
ANIMC_API std::vector<std::string> codecNames();

// Where an encoder writes. The stream is written front to back, with seeks back to fill in
// lengths; commit() is called once after the last byte, and a sink destroyed without it must
// leave nothing behind (or its old content).
class ANIMC_API ByteSink {
 public:
  virtual ~ByteSink();
  virtual Status write(const void* data, size_t size) = 0;
  virtual Status seek(uint64_t offset) = 0;
  virtual uint64_t tell() const = 0;
  virtual Status commit() = 0;
};

// A file written atomically: a temporary beside `path` renamed over it by commit(), so
// readers see the old file or the complete new one. A device or FIFO is written in place.
ANIMC_API Result<std::unique_ptr<ByteSink>> fileSink(const std::string& path);
// Bytes gathered in *out (cleared first; *out must outlive the sink, and is cleared again
// if the sink is destroyed without commit()).
ANIMC_API std::unique_ptr<ByteSink> memorySink(std::vector<uint8_t>* out);

struct EncodeSummary {
  uint32_t vertices = 0;
  uint64_t triangles = 0;
  int64_t frames = 0;
  uint64_t intra_frames = 0;
  uint64_t bytes = 0;  // of the whole stream
  // Header, connectivity and the first frame; for a codec that codes whole groups (trajectory,
  // auto), whose first frame record carries its group's motion, header and connectivity only.
  uint64_t static_bytes = 0;
  uint64_t cells = 0;         // affine-octree: octree leaves over all inter frames
  double encode_seconds = 0;  // in the codec, excluding the caller's time between frames
};

class ANIMC_API Encoder {
 public:
  // An encoder of frames of `vertex_count` vertices over these triangles, writing to `sink`.
  static Result<Encoder> create(const EncoderOptions& options, uint32_t vertex_count, const uint32_t* triangles,
                                size_t triangle_count, std::unique_ptr<ByteSink> sink);
  Encoder(Encoder&&) noexcept;
  Encoder& operator=(Encoder&&) noexcept;
  ~Encoder();  // without finish(), the sink is dropped uncommitted

  // Codes the next frame (3 * vertex_count floats, finite).
  Status addFrame(const float* xyz);
  // Frames whose reconstruction is known. A codec that codes frame by frame knows each as
  // soon as it is added; frames coded in groups (the trajectory and auto codecs, and any codec
  // with an I-frame interval on several threads) are known when their group is coded: when it
  // closes (when the next frame would not fit in it, and at finish()), or with several
  // threads when as many groups have closed as there are threads.
  int64_t reconstructedFrames() const;
  // Frame k as every decoder will reconstruct it (3 * vertex_count floats, valid until the
  // next call of addFrame() or reconstruction()): what the caller measures errors on. Known
  // for the last frame added (a frame-by-frame codec on one thread) or the frames of the
  // groups coded last; null for any other frame (and, were the codec's decoder to refuse
  // the encoder's own output, a bug, for that frame too).
  const float* reconstruction(int64_t frame);
  // reconstruction() of the last frame added: null for a frame of a group still open.
  const float* reconstruction();
  // Writes the index and commits the sink; the encoder takes no frames afterwards.
  Result<EncodeSummary> finish();
  // "affine-octree: profile predictive, max error 0.01 of the root cube, bits 16"
  std::string describeSettings() const;

  struct Impl;

 private:
  explicit Encoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend struct EncoderAccess;
};

// ---- Decoding -----------------------------------------------------------------------------

// Ceilings a decoder checks before allocating or working: a stream of a few hundred bytes
// can announce millions of vertices over millions of frames. Raise them for trusted input.
struct DecoderLimits {
  uint64_t max_vertices = uint64_t(1) << 22;
  uint64_t max_triangles = uint64_t(1) << 24;
  uint64_t max_frames = uint64_t(1) << 32;
  uint64_t max_frame_bytes = uint64_t(1) << 31;
  // Vertices x frames one decode of a range may cost, counting the frames decoded to reach
  // the first one asked for (from the start of its frame group): about 50 GB of floats.
  uint64_t max_vertex_frames = uint64_t(1) << 32;
  // Bytes one decode of a range may give (16 GiB): its frames as floats, 12 bytes a
  // vertex-frame, or what the caller says they take in its own form (a file, MeshLab layers).
  uint64_t max_output_bytes = uint64_t(1) << 34;
  // Multiply-adds the reconstruction of one frame group may cost, where a codec's work grows
  // with what its payload claims rather than with the frames it gives: a trajectory group
  // costs 3 x components x vertices x frames, which a few KB can claim at 10^11. The default
  // is above every group the encoder writes (it stays below 2^37).
  uint64_t max_multiply_adds = uint64_t(1) << 37;
};

// Progressive decoding of streams whose frames can be cut (wavelet-coded with bitplanes):
// fewer bitplanes or fewer bytes of each frame give a coarser reconstruction, faster.
// Asking it of another stream is an error.
struct ProgressiveOptions {
  int max_bitplanes = 0;           // decode at most this many bitplanes per frame; 0 = all
  uint64_t max_payload_bytes = 0;  // read at most this many bytes of each frame; 0 = all
  bool partial() const { return max_bitplanes > 0 || max_payload_bytes > 0; }
};

struct DecoderOptions {
  DecoderLimits limits;
  ProgressiveOptions progressive;
  // Threads Decoder::frames() may use: 0 = one per core, 1 = the calling thread only. Frames
  // are the same whatever their number.
  uint32_t threads = 0;
};

// One codec setting of a stream, as `animc info --json` shows it.
struct SettingValue {
  std::string key;
  std::variant<double, int64_t, bool, std::string> value;
};

struct StreamInfo {
  uint16_t format_version = 0;
  std::string codec;  // "affine-octree", "wavelet"
  uint8_t codec_id = 0;
  std::vector<SettingValue> settings;
  std::string settings_text;  // the settings as one line
  uint32_t vertices = 0;
  uint64_t triangles = 0;
  int64_t frames = 0;
  double frame_rate = 0;
  uint32_t iframe_interval = 0;
  uint64_t groups = 0;        // frame groups: random access starts decoding at a group's first frame
  uint64_t bytes = 0;         // of the stream
  uint64_t static_bytes = 0;  // as EncodeSummary::static_bytes
};

class ANIMC_API Decoder {
 public:
  // Opening reads and checks the header, the connectivity, the index and the first frame
  // group; later groups are checked when they are decoded (verify() checks them all).
  static Result<Decoder> openFile(const std::string& path, const DecoderOptions& options = {});
  // `data` is read in place, not copied: it must stay valid and unchanged while the decoder
  // lives. `name` stands for the stream in messages.
  static Result<Decoder> openMemory(const void* data, size_t size, const DecoderOptions& options = {},
                                    const std::string& name = "memory");
  Decoder(Decoder&&) noexcept;
  Decoder& operator=(Decoder&&) noexcept;
  ~Decoder();

  const StreamInfo& info() const;
  // 3 * info().triangles vertex indices.
  const uint32_t* triangles() const;

  // Decodes frame k into xyz (3 * info().vertices floats). The frame after the last one
  // decoded costs one frame; any other costs reading the frames from the start of its group,
  // which a codec that builds each frame on the one before (affine-octree, wavelet) decodes,
  // and the trajectory codec only reads (it computes frame k alone, from its group, which it
  // keeps while the access stays in it).
  Status frame(int64_t k, float* xyz);
  // Decodes frames [first, last) into xyz, one after the other (3 * info().vertices floats
  // each): the same frames as frame() in a loop, with the groups of the range decoded several
  // at once (DecoderOptions::threads). Refused before any work above the limits.
  Status frames(int64_t first, int64_t last, float* xyz);
  // kLimitExceeded, saying how to raise the limit, when decoding frames [first, last) would
  // cost more than DecoderLimits::max_vertex_frames or give more than max_output_bytes:
  // `output_bytes`, the size of the caller's form of those frames, or when 0 their floats.
  // frame() checks each frame; call this before a range to refuse it before any work.
  Status checkDecodeWork(int64_t first, int64_t last, uint64_t output_bytes = 0) const;
  // Checks every group (its CRC, its frame numbers against the index, that nothing follows its
  // last frame) and decodes every frame, keeping none: `animc test`.
  Status verify(const ProgressFn& progress = {});

  struct Impl;

 private:
  explicit Decoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend struct DecoderAccess;
};

// ---- Joining ------------------------------------------------------------------------------

// One part of a sequence to join: an .ams file at `path`, or, when data is not null, `size`
// bytes in memory (valid for the call) that `path` then names in messages.
struct StreamPart {
  std::string path;
  const void* data = nullptr;
  size_t size = 0;
};

// Joins .ams streams of consecutive parts of one sequence, encoded apart with the same codec
// settings, mesh and frame rate (`animc encode --frames A:B` on each part), into one stream
// written to `sink`: the parts' header and connectivity must be identical, and the groups of
// each follow those of the one before, checked (CRC) as they are copied. The bytes are those of
// the whole sequence encoded at once with the same settings when every part but the last is a
// whole number of I-frame intervals long. Returns the frame count of the joined stream.
ANIMC_API Result<uint64_t> joinStreams(const std::vector<StreamPart>& parts, std::unique_ptr<ByteSink> sink);

// The whole frame groups at the start of a stream still arriving (`size` bytes of an .ams
// stream, perhaps all of it), as a stream of their own written to `sink`: the header, the
// connectivity and each GRUP section that lies wholly in those bytes, then a new INDX and END.
// A player opens it with Decoder::openMemory() to show those frames while the rest arrives; of
// a whole stream it writes the same bytes. Returns the frames of those groups: 0, with nothing
// written, while the bytes do not hold one whole group yet. Groups whose frame numbers do not
// follow on are Corrupt; the rest (CRCs, payloads) is checked by the decoder that opens and
// decodes the result.
ANIMC_API Result<uint64_t> wholeGroupsOf(const void* data, size_t size, std::unique_ptr<ByteSink> sink);

// ---- Metrics ------------------------------------------------------------------------------
// The project's one implementation of its quality figures (animc, the MeshLab plugins, the
// benchmarks and the Python module all use it); definitions in docs/metrics.md.

struct FrameError {
  double rms = 0;  // sqrt(mean over the frame's vertices of |v' - v|^2), absolute
  double max = 0;  // max over the frame's vertices of |v' - v|, absolute
};

struct SequenceMetrics {
  int64_t frames = 0;
  uint32_t vertices = 0;
  // Karni-Gotsman, percent: 100 * ||A - A'||_F / ||A - E(A)||_F, E(A) = per-frame centroid of
  // the original replicated over its vertices.
  double kg_error = 0;
  // 10 * log10(dmax^2 / AVGMSE), dmax = bbox_diagonal, AVGMSE = mean over all vertices of all
  // frames of |v' - v|^2. +inf when exact.
  double psnr = 0;
  double max_error = 0;           // max Euclidean vertex error, absolute
  double max_error_rel_diag = 0;  // max_error / dmax
  // Max over frames f of (max vertex error in f) / S_f, S_f = max(largest bbox side of
  // original frame f, of original frame f-1): the Affine-Octree paper's ME scale, since the
  // codec's cube for frame f may come from frame f-1.
  double max_error_rel_cube = 0;
  double rms_error = 0;           // sqrt(AVGMSE)
  double rms_error_rel_diag = 0;  // rms_error / dmax
  double bbox_diagonal = 0;       // dmax: diagonal of the bbox of the whole original sequence
  std::vector<FrameError> per_frame;
};

using VertexErrorFn = std::function<void(uint32_t vertex, double error)>;

// Whether SequenceMetrics::per_frame is kept (16 bytes a frame) or dropped, so that memory
// does not grow with the frame count when only the totals are wanted.
enum class PerFrameErrors { kKeep, kDrop };

// Streams frames one at a time; memory is O(frames) for per_frame only (kKeep), never
// O(N * frames). Degenerate scales (an all-coincident original, so dmax, S_f or the KG
// denominator is 0) give a relative figure of 0 when the error is 0 too, else +inf. An empty
// sequence reads as exact. A NaN in a reconstruction propagates to every figure it touches.
class ANIMC_API MetricsAccumulator {
 public:
  explicit MetricsAccumulator(uint32_t vertex_count, PerFrameErrors per_frame = PerFrameErrors::kKeep);
  // original and reconstructed: 3 * vertex_count floats each. each_vertex, when given, is
  // called with every vertex's error |v' - v|.
  void addFrame(const float* original, const float* reconstructed, const VertexErrorFn& each_vertex = {});
  // The figures so far; frames can still be added afterwards.
  SequenceMetrics finish() const;
  int64_t frames() const { return frames_; }

 private:
  uint32_t vertex_count_;
  int64_t frames_ = 0;
  double sum_sq_error_ = 0;    // sum over all vertices of all frames of |v' - v|^2
  double sum_sq_centred_ = 0;  // sum of |v - centroid of its frame|^2 (the KG denominator)
  double max_error_ = 0;
  double max_error_rel_cube_ = 0;
  double previous_side_ = 0;  // largest bbox side of the previous original frame
  std::array<double, 3> sequence_min_;
  std::array<double, 3> sequence_max_;
  PerFrameErrors keep_;
  std::vector<FrameError> per_frame_;
};

// STED, the spatio-temporal edge difference of Vasa and Skala (IEEE TVCG 17(2), 2011): how
// much a reconstruction distorts the mesh's local shape (relative edge lengths) and its motion
// (lengths of the edges joining a vertex's positions in consecutive frames). Definitions and
// the neighbourhood used here in docs/metrics.md.
struct StedOptions {
  int rings = 1;               // neighbourhood of a vertex: its edges within this many rings (1-3)
  double time_step = 0.01;     // one frame's temporal edge length, times frame 0's bbox diagonal
  double temporal_weight = 1;  // c in STED = sqrt(spatial^2 + c^2 temporal^2)
};

struct StedFigures {
  double spatial = 0;   // mean over frames and vertices of the local deviation of edge change
  double temporal = 0;  // mean over vertices and frame pairs of the relative temporal edge change
  double sted = 0;      // sqrt(spatial^2 + (temporal_weight * temporal)^2)
};

// Streams frames like MetricsAccumulator; memory O(vertices + edges in the neighbourhoods),
// never O(frames). Triangles with an index >= vertex_count are ignored.
class ANIMC_API StedAccumulator {
 public:
  StedAccumulator(uint32_t vertex_count, const uint32_t* triangles, size_t triangle_count,
                  const StedOptions& options = {});
  ~StedAccumulator();
  StedAccumulator(StedAccumulator&&) noexcept;
  StedAccumulator& operator=(StedAccumulator&&) noexcept;
  // original and reconstructed: 3 * vertex_count floats each.
  void addFrame(const float* original, const float* reconstructed);
  StedFigures finish() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct SizeFigures {
  double ratio = 0;        // 12 * N * F / bytes: raw size as 32-bit floats over stream size
  double bpvf = 0;         // 8 * bytes / (N * F)
  double motion_bpvf = 0;  // 8 * (bytes - static_bytes) / (N * F)
};

// Plain IEEE division: a zero denominator gives inf (or NaN for 0/0).
ANIMC_API SizeFigures sizeFigures(uint64_t bytes, uint64_t static_bytes, uint32_t vertices, int64_t frames);

}  // namespace animc
