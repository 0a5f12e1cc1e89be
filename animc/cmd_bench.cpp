// SPDX-License-Identifier: Apache-2.0
// animc bench: median encode and decode throughput over R runs on --threads N threads (0 =
// one per core, the default), the encode's and the decode's median CPU time, plus every
// metric of the decoded result. The input is read into memory first so that file reading
// and xz decompression are not timed. Given an .ams file, it times decoding only (the file
// stays in the page cache after the first run): the loop to measure a decoder change with,
// each build decoding the same bytes. With --read-only it times the sequence readers instead:
// opening the input and reading every frame, what a reader change is measured with.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "cli.h"
#include "core/memory_sequence.h"
#include "core/temp_registry.h"
#include "core/uninitialised_vector.h"
#include "metrics/compare_sequences.h"
#include "report/report.h"
#include "seqio/byte_input.h"
#include "seqio/sequence_io.h"

namespace animc::cli {

namespace {

using Clock = std::chrono::steady_clock;

// CPU seconds of the whole process so far, every thread's: across an encode or a decode with
// --threads 1, its own work, which a busy or virtual machine's waits (another process's turn,
// stolen time) do not lengthen as they lengthen the wall clock.
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

// Seconds a piece of work took: on the wall clock, and of the process's CPU time.
struct Timing {
  double wall = 0;
  double cpu = 0;
};

// Times to open a stream and decode all its frames through the public Decoder: in order, in
// the runs of frames a reader takes (decodeChunkEnd(), several groups at once with threads), or
// from the last to the first (every frame then a random access into its group).
Result<Timing> timeDecode(const std::function<Result<Decoder>()>& open, bool backwards = false) {
  const auto t0 = Clock::now();
  const double cpu0 = processCpuSeconds();
  ANIMC_ASSIGN_OR_RETURN(Decoder decoder, open());
  const size_t size = 3 * size_t(decoder.info().vertices);
  // Not zero-filled, as a reader's buffer need not be: the decoder writes every value, on its
  // threads, where a fill would be a serial pass over the whole range first.
  UninitialisedVector<float> xyz;
  const int64_t frames = decoder.info().frames;
  if (backwards) {
    xyz.resize(size);
    for (int64_t i = frames - 1; i >= 0; --i) ANIMC_RETURN_IF_ERROR(decoder.frame(i, xyz.data()));
  }
  for (int64_t first = 0, end = 0; !backwards && first < frames; first = end) {
    end = decodeChunkEnd(decoder, first);
    xyz.resize(size_t(end - first) * size);
    ANIMC_RETURN_IF_ERROR(decoder.frames(first, end, xyz.data()));
  }
  return Timing{std::chrono::duration<double>(Clock::now() - t0).count(), processCpuSeconds() - cpu0};
}

DecoderOptions withThreads(uint32_t threads) {
  DecoderOptions options;
  options.threads = threads;
  return options;
}

// Decoding of an existing .ams, R times from the file and R times from memory, alternating:
// what a decoder change is measured with. --backwards times random access.
int runDecodeBench(const Args& args, long long runs) {
  const bool backwards = args.has("backwards");
  const std::string& path = args.positional()[0];
  auto threads = threadsFrom(args);
  if (!threads.ok()) return fail(threads.status());
  const DecoderOptions options = withThreads(threads.value());
  auto bytes = readWholeFile(path);
  if (!bytes.ok()) return fail(bytes.status());
  const std::vector<uint8_t>& stream = bytes.value();
  std::vector<double> decode_s, decode_cpu_s, memory_s;
  ProgressFn progress = progressLine("bench", args.has("progress"));
  for (long long r = 0; r < runs; ++r) {
    if (progress) progress(int(100 * r / runs), "decoding");
    auto d = timeDecode([&] { return Decoder::openFile(path, options); }, backwards);
    if (!d.ok()) return fail(d.status());
    decode_s.push_back(d.value().wall);
    decode_cpu_s.push_back(d.value().cpu);
    d = timeDecode([&] { return Decoder::openMemory(stream.data(), stream.size(), options, path); }, backwards);
    if (!d.ok()) return fail(d.status());
    memory_s.push_back(d.value().wall);
  }
  if (progress) progress(100, "done");
  endProgressLine();
  auto ams = AmsSource::open(path);
  if (!ams.ok()) return fail(ams.status());
  const ContainerInfo& info = ams.value()->info();
  const uint32_t vertices = info.header.vertex_count;
  const int64_t frames = int64_t(info.frame_count);
  const double decode_mvps = double(vertices) * double(frames) / median(decode_s) / 1e6;
  const double decode_cpu_mvps = double(vertices) * double(frames) / median(decode_cpu_s) / 1e6;
  const double memory_mvps = double(vertices) * double(frames) / median(memory_s) / 1e6;
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("input", path);
    addSettings(o, ams.value()->settings());
    addSizes(o, info.file_bytes, info.static_bytes, vertices, frames);
    o.add("vertices", vertices);
    o.add("frames", frames);
    o.add("runs", runs);
    o.add("order", backwards ? "backwards" : "forwards");
    o.add("decode_seconds_median", median(decode_s));
    o.add("decode_mvps", decode_mvps);
    o.add("decode_cpu_seconds_median", median(decode_cpu_s));
    o.add("decode_cpu_mvps", decode_cpu_mvps);
    o.add("decode_memory_seconds_median", median(memory_s));
    o.add("decode_memory_mvps", memory_mvps);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: %u vertices x %lld frames, %lld runs, decoding only%s\n", path.c_str(), vertices, (long long)frames,
              runs, backwards ? ", last frame first" : "");
  std::printf(
      "decode: %.2f M vertices/s (median %.4f s) from the file, %.2f M vertices/s (median %.4f s) from memory\n",
      decode_mvps, median(decode_s), memory_mvps, median(memory_s));
  return 0;
}

// Reading an input sequence R times (the files stay in the page cache after the first run),
// without encoding: medians in million vertices (× frames) and megabytes of input per second.
int runReadBench(const Args& args, long long runs) {
  const std::string& path = args.positional()[0];
  auto files = sequenceInputFiles(path, args.get("mesh"));
  if (!files.ok()) return fail(files.status());
  uint64_t input_bytes = 0;
  for (const std::string& file : files.value()) {
    std::error_code ec;
    input_bytes += std::filesystem::file_size(file, ec);
  }
  std::vector<double> read_s;
  uint64_t vertices = 0, frames = 0;
  std::vector<float> xyz;
  for (long long r = 0; r < runs; ++r) {
    const auto t0 = Clock::now();
    auto source = openSequence(path, args.get("mesh"));
    if (!source.ok()) return fail(source.status());
    frames = 0;
    for (;;) {
      auto more = source.value()->next(xyz);
      if (!more.ok()) return fail(more.status());
      if (!more.value()) break;
      ++frames;
    }
    read_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    vertices = source.value()->topology().vertex_count;
  }
  const double seconds = median(read_s);
  const double read_mvps = double(vertices) * double(frames) / seconds / 1e6;
  const double read_mbps = double(input_bytes) / seconds / 1e6;
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("input", path);
    o.add("vertices", vertices);
    o.add("frames", frames);
    o.add("input_bytes", input_bytes);
    o.add("runs", runs);
    o.add("read_seconds_median", seconds);
    o.add("read_mvps", read_mvps);
    o.add("read_mbps", read_mbps);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: %llu vertices x %llu frames, %llu bytes, %lld runs, reading only\n", path.c_str(),
              (unsigned long long)vertices, (unsigned long long)frames, (unsigned long long)input_bytes, runs);
  std::printf("read: %.2f M vertices/s, %.1f MB/s (median %.4f s)\n", read_mvps, read_mbps, seconds);
  return 0;
}

}  // namespace

int runBench(const std::vector<std::string>& argv) {
  Args args;
  std::set<std::string> options = encodeOptions();
  options.insert({"mesh", "runs", "output"});
  std::set<std::string> switches = encodeSwitches();
  switches.insert({"progress", "json", "backwards", "read-only"});
  Status s = args.parse(argv, options, switches);
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 1)
    return fail(
        invalidArgument("usage: animc bench IN [--mesh M] [options] [--runs R] | animc bench IN [--mesh M] "
                        "--read-only [--runs R] | animc bench IN.ams [--runs R] [--backwards] [--threads N]"));
  auto runs = args.integer("runs", 5);
  if (!runs.ok() || runs.value() < 1 || runs.value() > 1000)
    return fail(invalidArgument("--runs must be in [1, 1000]"));
  if (isAmsPath(args.positional()[0])) {
    for (const std::set<std::string>* names : {&options, &switches})
      for (const std::string& name : *names)
        if (name != "runs" && name != "json" && name != "progress" && name != "backwards" && name != "threads" &&
            args.has(name))
          return fail(invalidArgument("bench of an .ams file decodes it only: --" + name + " does not apply"));
    return runDecodeBench(args, runs.value());
  }
  if (args.has("backwards")) return fail(invalidArgument("--backwards applies to the bench of an .ams file"));
  if (args.has("read-only")) {
    for (const std::set<std::string>* names : {&options, &switches})
      for (const std::string& name : *names)
        if (name != "runs" && name != "json" && name != "mesh" && name != "read-only" && args.has(name))
          return fail(invalidArgument("bench --read-only reads the input only: --" + name + " does not apply"));
    return runReadBench(args, runs.value());
  }
  auto input = openEncodeInput(args);
  if (!input.ok()) return fail(input.status());
  const EncodeSettings& settings = input.value().settings;
  auto sequence = readAll(*input.value().source);
  if (!sequence.ok()) return fail(sequence.status());
  MemorySequence& seq = sequence.value();
  const std::string out =
      args.has("output") ? args.get("output") : "/tmp/animc-bench-" + std::to_string(getpid()) + ".ams";
  // The scratch output is rewritten every run: an interrupted bench removes it too.
  const int scratch_slot = args.has("output") ? -1 : registerTemporary(out, TemporaryKind::kFile);
  std::vector<double> encode_s, encode_cpu_s, decode_s, decode_cpu_s;
  EncodeSummary report;
  ProgressFn progress = progressLine("bench", args.has("progress"));
  for (long long r = 0; r < runs.value(); ++r) {
    if (progress) progress(int(100 * r / runs.value()), "encoding and decoding");
    seq.rewind();
    const auto t0 = Clock::now();
    const double cpu0 = processCpuSeconds();
    auto rep = encodeSequence(seq, settings, out);
    if (!rep.ok()) return fail(rep.status());
    encode_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    encode_cpu_s.push_back(processCpuSeconds() - cpu0);
    report = rep.value();
    auto d = timeDecode([&] { return Decoder::openFile(out, withThreads(settings.threads)); });
    if (!d.ok()) return fail(d.status());
    decode_s.push_back(d.value().wall);
    decode_cpu_s.push_back(d.value().cpu);
  }
  if (progress) progress(100, "done");
  endProgressLine();
  seq.rewind();
  auto ams = AmsSource::open(out);
  if (!ams.ok()) return fail(ams.status());
  auto metrics = compareSequences(seq, *ams.value(), {}, PerFrameErrors::kDrop);
  if (!args.has("output")) unlink(out.c_str());
  unregisterTemporary(scratch_slot);
  if (!metrics.ok()) return fail(metrics.status());
  const double vertex_frames = double(report.vertices) * double(report.frames);
  const double encode_mvps = vertex_frames / median(encode_s) / 1e6;
  const double decode_mvps = vertex_frames / median(decode_s) / 1e6;
  const double decode_cpu_mvps = vertex_frames / median(decode_cpu_s) / 1e6;
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("input", args.positional()[0]);
    addSettings(o, settings);
    addSizes(o, report.bytes, report.static_bytes, report.vertices, report.frames);
    addMetrics(o, metrics.value(), false);
    o.add("intra_frames", report.intra_frames);
    o.add("cells", report.cells);
    o.add("runs", runs.value());
    o.add("encode_seconds_median", median(encode_s));
    o.add("encode_cpu_seconds_median", median(encode_cpu_s));
    o.add("decode_seconds_median", median(decode_s));
    o.add("encode_mvps", encode_mvps);
    o.add("decode_mvps", decode_mvps);
    o.add("decode_cpu_seconds_median", median(decode_cpu_s));
    o.add("decode_cpu_mvps", decode_cpu_mvps);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: %u vertices x %lld frames, %lld runs\n", args.positional()[0].c_str(), report.vertices,
              (long long)report.frames, runs.value());
  std::fputs(formatEncodeResult(settings, report).c_str(), stdout);
  std::fputs(formatMetricsText(metrics.value()).c_str(), stdout);
  std::printf("encode: %.2f M vertices/s (median %.4f s)\ndecode: %.2f M vertices/s (median %.4f s)\n", encode_mvps,
              median(encode_s), decode_mvps, median(decode_s));
  return 0;
}

}  // namespace animc::cli
