// SPDX-License-Identifier: Apache-2.0
// animc join: .ams files of consecutive parts of one sequence (encoded apart with the same
// settings, e.g. `animc encode --frames A:B` on a render farm) into one, as joinStreams does.
#include <cstdio>

#include "cli.h"
#include "core/file_identity.h"
#include "report/report.h"

namespace animc::cli {

int runJoin(const std::vector<std::string>& argv) {
  Args args;
  Status s = args.parse(argv, {"output"}, {"json"});
  if (!s.ok()) return fail(s);
  if (args.positional().empty() || !args.has("output"))
    return fail(invalidArgument("usage: animc join PART.ams... -o ALL.ams [--json]"));
  const std::string out = args.get("output");
  if (!(s = refuseOutputOverInput(out, args.positional())).ok()) return fail(s);
  std::vector<StreamPart> parts;
  for (const std::string& path : args.positional()) parts.push_back({path});
  auto sink = fileSink(out);
  if (!sink.ok()) return fail(sink.status());
  auto frames = joinStreams(parts, std::move(sink).value());
  if (!frames.ok()) return fail(frames.status());
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("output", out);
    o.add("parts", uint64_t(parts.size()));
    o.add("frames", frames.value());
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: %llu frames from %zu parts\n", out.c_str(), (unsigned long long)frames.value(), parts.size());
  return 0;
}

}  // namespace animc::cli
