// SPDX-License-Identifier: Apache-2.0
#include <cstdio>

#include "cli.h"
#include "metrics/compare_sequences.h"
#include "report/report.h"
#include "seqio/sequence_io.h"

namespace animc::cli {

int runCompare(const std::vector<std::string>& argv) {
  Args args;
  Status s = args.parse(argv, {"mesh"}, {"json", "per-frame"});
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 2)
    return fail(invalidArgument("usage: animc compare ORIGINAL RECONSTRUCTED|IN.ams [--mesh M]"));
  const std::string& recon_path = args.positional()[1];
  auto original = openSequence(args.positional()[0], args.get("mesh"));
  if (!original.ok()) return fail(original.status());
  const bool is_ams = isAmsPath(recon_path);
  std::unique_ptr<FrameSource> recon;
  std::unique_ptr<AmsSource> ams;
  if (is_ams) {
    auto r = AmsSource::open(recon_path);
    if (!r.ok()) return fail(r.status());
    ams = std::move(r).value();
  } else {
    auto r = openSequence(recon_path, args.get("mesh"));
    if (!r.ok()) return fail(r.status());
    recon = std::move(r).value();
  }
  FrameSource& other = ams ? static_cast<FrameSource&>(*ams) : *recon;
  StedFigures sted;
  auto metrics = compareSequences(*original.value(), other, {},
                                  args.has("per-frame") ? PerFrameErrors::kKeep : PerFrameErrors::kDrop, &sted);
  if (!metrics.ok()) return fail(metrics.status());
  const SequenceMetrics& m = metrics.value();
  if (args.has("json")) {
    JsonObject o = newReport();
    if (ams) addSizes(o, ams->info().file_bytes, ams->info().static_bytes, m.vertices, m.frames);
    addMetrics(o, m, args.has("per-frame"));
    addSted(o, sted);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  if (ams) std::fputs(formatSizeText(ams->info().file_bytes, ams->info().static_bytes, m.vertices, m.frames).c_str(), stdout);
  std::fputs(formatMetricsText(m).c_str(), stdout);
  std::fputs(formatStedText(sted).c_str(), stdout);
  return 0;
}

}  // namespace animc::cli
