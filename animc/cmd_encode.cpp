// SPDX-License-Identifier: Apache-2.0
#include <cstdio>

#include "cli.h"
#include "report/encode_metrics.h"
#include "report/report.h"
#include "seqio/sequence_io.h"

namespace animc::cli {

int runEncode(const std::vector<std::string>& argv) {
  Args args;
  std::set<std::string> options = encodeOptions();
  options.insert({"output", "mesh"});
  std::set<std::string> switches = encodeSwitches();
  switches.insert({"progress", "json"});
  Status s = args.parse(argv, options, switches);
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 1 || !args.has("output"))
    return fail(invalidArgument("usage: animc encode IN -o OUT.ams [options]"));
  auto input = openEncodeInput(args);
  if (!input.ok()) return fail(input.status());
  const EncodeSettings& settings = input.value().settings;
  FrameSource& source = *input.value().source;
  MetricsAccumulator metrics(source.topology().vertex_count, PerFrameErrors::kDrop);
  auto report = encodeSequence(source, settings, args.get("output"),
                               progressLine("encode", args.has("progress")), measuringObserver(metrics));
  if (!report.ok()) return fail(report.status());
  endProgressLine();
  const EncodeSummary& r = report.value();
  const SequenceMetrics m = metrics.finish();
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("output", args.get("output"));
    addSettings(o, settings);
    addSizes(o, r.bytes, r.static_bytes, r.vertices, r.frames);
    addMetrics(o, m, false);
    o.add("intra_frames", r.intra_frames);
    o.add("cells", r.cells);
    o.add("encode_seconds", r.encode_seconds);
    o.add("encode_mvps", encodeMvps(r));
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: %u vertices, %llu triangles, %lld frames (%llu intra)\n", args.get("output").c_str(),
              r.vertices, (unsigned long long)r.triangles, (long long)r.frames,
              (unsigned long long)r.intra_frames);
  std::fputs(formatEncodeSummary(settings, r, m).c_str(), stdout);
  return 0;
}

}  // namespace animc::cli
