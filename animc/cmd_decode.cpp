// SPDX-License-Identifier: Apache-2.0
#include <cstdio>

#include "cli.h"
#include "core/file_identity.h"
#include "seqio/sequence_io.h"

namespace animc::cli {
namespace {

// --bitplanes K / --max-bytes N: progressive decoding of a wavelet-coded file.
Result<WaveletDecodeControl> progressiveControl(const Args& args) {
  WaveletDecodeControl c;
  ANIMC_ASSIGN_OR_RETURN(long long planes, args.integer("bitplanes", 0));
  ANIMC_ASSIGN_OR_RETURN(long long bytes, args.integer("max-bytes", 0));
  if (planes < 0 || planes > 64) return invalidArgument("--bitplanes must be in [1, 64] (0 = all)");
  if (bytes < 0) return invalidArgument("--max-bytes must be >= 1 (0 = all)");
  c.max_bitplanes = int(planes);
  c.max_payload_bytes = uint64_t(bytes);
  return c;
}

}  // namespace

int runDecode(const std::vector<std::string>& argv) {
  Args args;
  Status s = args.parse(argv,
                        {"output", "format", "frames", "bitplanes", "max-bytes", "max-vertex-frames",
                         "max-output-bytes", "max-multiply-adds", "threads"},
                        {"progress", "replace"});
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 1 || !args.has("output"))
    return fail(invalidArgument("usage: animc decode IN.ams -o OUT [--format " + formatNames("|") +
                                "] [--frames A:B] "
                                "[--bitplanes K] [--max-bytes N] [--replace] [--max-vertex-frames V] "
                                "[--max-output-bytes B] [--max-multiply-adds W] [--threads N]"));
  const std::string out = args.get("output");
  Result<SequenceFormat> fmt = outputFormatOf(out);
  if (args.has("format")) fmt = formatFromName(args.get("format"));
  if (!fmt.ok()) return fail(fmt.status());
  auto control = progressiveControl(args);
  if (!control.ok()) return fail(control.status());
  if (!(s = refuseOutputOverInput(out, {args.positional()[0]})).ok()) return fail(s);
  auto limits = decoderLimitsFrom(args);
  if (!limits.ok()) return fail(limits.status());
  auto threads = threadsFrom(args);
  if (!threads.ok()) return fail(threads.status());
  auto source = AmsSource::open(args.positional()[0], limits.value(), control.value(), threads.value());
  if (!source.ok()) return fail(source.status());
  AmsSource& ams = *source.value();
  int64_t first = 0, last = 0;
  if (!(s = parseRange(args.get("frames"), ams.frameCount(), first, last)).ok()) return fail(s);
  const uint64_t output_bytes = sequenceOutputBytes(fmt.value(), ams.topology(), last - first);
  if (!(s = ams.checkDecodeWork(first, last, output_bytes)).ok()) return fail(s);
  if (!(s = ams.seek(first)).ok()) return fail(s);
  auto sink = createSequenceSink(out, fmt.value(), ams.topology(), ams.frameRate(), last - first,
                                 args.has("replace") ? ExistingOutput::kReplace : ExistingOutput::kRefuse);
  if (!sink.ok()) return fail(sink.status());
  ProgressFn progress = progressLine("decode", args.has("progress"));
  std::vector<float> xyz;
  for (int64_t f = first; f < last; ++f) {
    auto got = ams.next(xyz);
    if (!got.ok()) return fail(got.status());
    if (!got.value()) return fail(corrupt("file ends before frame " + std::to_string(f)));
    if (!(s = sink.value()->write(xyz.data())).ok()) return fail(s);
    if (progress) progress(int(100 * (f - first + 1) / (last - first)), "decoding");
  }
  if (!(s = sink.value()->finish()).ok()) return fail(s);
  endProgressLine();
  std::printf("%s: %lld frames of %u vertices (%s)\n", out.c_str(), (long long)(last - first),
              ams.topology().vertex_count, formatSpec(fmt.value()).name);
  return 0;
}

}  // namespace animc::cli
