// SPDX-License-Identifier: Apache-2.0
// animc: encode, decode, inspect, compare and benchmark animated-mesh files from a shell.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.h"
#include "version.h"

namespace {

constexpr const char* kUsage =
    "usage: animc <command> ...   (animc --version prints the release)\n"
    "  encode IN -o OUT.ams [--mesh M] [--codec affine-octree|wavelet] [--iframe-interval K]\n"
    "         affine-octree: [--profile paper|default] [--max-error E] [--bits K] [--max-depth D]\n"
    "         wavelet: [--step S] [--bpv B] [--target-kg X] [--parametric-bits P]\n"
    "         [--i-frames-only | --progressive-p-frames]\n"
    "         [--progress] [--json]\n"
    "  decode IN.ams -o OUT [--format ply|off|pc2|mdd] [--frames A:B] [--progress]\n"
    "         PLY/OFF frames go to a new or empty folder OUT, or --replace an existing one\n"
    "         [--bitplanes K] [--max-bytes N]: progressive, fewer bitplanes/bytes per frame\n"
    "         (wavelet files encoded with --progressive-p-frames or --i-frames-only)\n"
    "  info IN.ams [--json]\n"
    "  compare ORIGINAL RECONSTRUCTED|IN.ams [--mesh M] [--json] [--per-frame]\n"
    "  bench IN [--mesh M] [encode options] [--runs R] [--json]\n"
    "  bench IN.ams [--runs R] [--json]: decoding only, of that file\n"
    "IN: .pc2/.mdd (optionally .xz, with --mesh), a .ply/.off frame, a folder of them or a\n"
    ".txt list of frame files. E is a fraction of the root cube's side (0.01 = 1%).\n"
    "S is the wavelet's finest quantisation step as a fraction of the first frame's bounding-box\n"
    "diagonal; B caps each frame at B bits per vertex; X is the KG error (in %) to reach with\n"
    "the fewest bits (down to what S allows).\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace animc::cli;
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "--version" || command == "version") {
    std::printf("animc %s (.ams format %u)\n", animc::animcVersion(), unsigned(animc::kFormatVersion));
    return 0;
  }
  const std::vector<std::string> rest(argv + 2, argv + argc);
  if (command == "encode") return runEncode(rest);
  if (command == "decode") return runDecode(rest);
  if (command == "info") return runInfo(rest);
  if (command == "compare") return runCompare(rest);
  if (command == "bench") return runBench(rest);
  std::fprintf(stderr, "animc: unknown command '%s' (animc --help lists them)\n", command.c_str());
  return 2;
}
