// SPDX-License-Identifier: Apache-2.0
// animc test: the whole-file check of an .ams, as xz -t and zstd -t do for theirs: every
// section's CRC and every frame decoded, nothing written. One line (or JSON object) and exit 0,
// or the one-line error and exit status every subcommand gives.
#include <cstdio>

#include "cli.h"
#include "report/report.h"

namespace animc::cli {

int runTest(const std::vector<std::string>& argv) {
  Args args;
  Status s = args.parse(argv, {"max-vertex-frames", "max-multiply-adds", "threads"}, {"json"});
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 1)
    return fail(invalidArgument(
        "usage: animc test IN.ams [--json] [--max-vertex-frames V] [--max-multiply-adds W] [--threads N]"));
  auto limits = decoderLimitsFrom(args);
  if (!limits.ok()) return fail(limits.status());
  auto threads = threadsFrom(args);
  if (!threads.ok()) return fail(threads.status());
  const std::string& path = args.positional()[0];
  auto check = checkAmsFile(path, limits.value(), threads.value());
  if (!check.ok()) return fail(check.status());
  const AmsCheck& c = check.value();
  if (args.has("json")) {
    JsonObject o = newReport();
    o.add("input", path);
    o.add("ok", true);
    o.add("checked", "every frame");
    addSettings(o, c.settings);
    o.add("vertices", c.vertices);
    o.add("triangles", c.triangles);
    o.add("frames", c.frames);
    o.add("groups", c.groups);
    o.addRaw("groups_by_codec", groupCodecsJson(c.groups_by_codec));
    o.add("file_bytes", c.file_bytes);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: OK, %lld frames of %u vertices, %llu groups%s\n", path.c_str(), (long long)c.frames, c.vertices,
              (unsigned long long)c.groups, groupCodecsText(c.settings, c.groups_by_codec).c_str());
  return 0;
}

}  // namespace animc::cli
