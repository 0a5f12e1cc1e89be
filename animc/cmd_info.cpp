// SPDX-License-Identifier: Apache-2.0
#include <cstdio>

#include "cli.h"
#include "report/report.h"

namespace animc::cli {

int runInfo(const std::vector<std::string>& argv) {
  Args args;
  Status s = args.parse(argv, {}, {"json"});
  if (!s.ok()) return fail(s);
  if (args.positional().size() != 1) return fail(invalidArgument("usage: animc info IN.ams [--json]"));
  auto source = AmsSource::open(args.positional()[0]);
  if (!source.ok()) return fail(source.status());
  const ContainerInfo& info = source.value()->info();
  const ContainerHeader& h = info.header;
  const uint64_t groups = info.groupCount();
  uint64_t group_bytes = 0;
  for (const SectionInfo& sec : info.sections)
    if (sec.tag == kTagGroup) group_bytes += sec.payload_bytes;
  if (args.has("json")) {
    JsonObject o = newReport();
    // What opening the file checked: not the groups after the first (animc test does).
    o.add("checked", "header, index and first group");
    o.add("format_version", info.format_version);
    addSettings(o, source.value()->settings());
    o.add("vertices", h.vertex_count);
    o.add("triangles", h.triangle_count);
    o.add("frames", info.frame_count);
    o.add("frame_rate", h.frame_rate);
    o.add("groups", groups);
    addSizes(o, info.file_bytes, info.static_bytes, h.vertex_count, int64_t(info.frame_count));
    for (const SectionInfo& sec : info.sections)
      if (sec.tag != kTagGroup) o.add(std::string("section_") + (sec.tag == "END " ? "end" : sec.tag) + "_bytes", sec.payload_bytes);
    o.add("section_grup_bytes", group_bytes);
    std::printf("%s\n", o.str().c_str());
    return 0;
  }
  std::printf("%s: .ams format version %u\n", args.positional()[0].c_str(), info.format_version);
  std::fputs(describeSettings(source.value()->settings()).c_str(), stdout);
  std::printf("vertices: %u, triangles: %llu, frames: %llu at %g fps, groups: %llu\n", h.vertex_count,
              (unsigned long long)h.triangle_count, (unsigned long long)info.frame_count, h.frame_rate,
              (unsigned long long)groups);
  std::fputs(formatSizeText(info.file_bytes, info.static_bytes, h.vertex_count, int64_t(info.frame_count)).c_str(), stdout);
  std::printf("sections:\n");
  for (const SectionInfo& sec : info.sections)
    if (sec.tag != kTagGroup)
      std::printf("  %s at %llu: %llu bytes\n", sec.tag.c_str(), (unsigned long long)sec.offset,
                  (unsigned long long)sec.payload_bytes);
  std::printf("  GRUP x %llu: %llu bytes\n", (unsigned long long)groups, (unsigned long long)group_bytes);
  std::printf("checked: header, index and the first group; `animc test` checks every frame\n");
  return 0;
}

}  // namespace animc::cli
