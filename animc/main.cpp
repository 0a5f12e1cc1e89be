// SPDX-License-Identifier: Apache-2.0
// animc: encode, decode, inspect, test, compare and benchmark animated-mesh files from a shell.
#include <cstdio>
#include <string>
#include <vector>

#include "animc/animc.h"
#include "cli.h"
#include "seqio/sequence_formats.h"

namespace {

std::string usageAfterEncode() {
  return "         [--connectivity-piece T]: triangles per independently decoded piece of the\n"
         "         mesh (default " +
         std::to_string(animc::kDefaultConnectivityPiece) +
         "; more triangles write .ams format 2, 0 = always format 1)\n"
         "         [--progress] [--json]\n"
         "  decode IN.ams -o OUT [--format " +
         animc::formatNames("|") +
         "] [--frames A:B] [--progress]\n"
         "         [--replace]\n"
         "         [--bitplanes K] [--max-bytes N]: progressive, fewer bitplanes/bytes per frame\n"
         "         (wavelet files encoded with --progressive-p-frames or --i-frames-only)\n"
         "         frame files (" +
         animc::frameFileExtensionList() +
         ") go to a new or empty folder OUT,\n"
         "         or --replace an existing one\n"
         "         [--max-vertex-frames V] [--max-output-bytes B] [--max-multiply-adds W]: refuse\n"
         "         more decoding work or output than that (defaults 2^32 vertex-frames, 2^34\n"
         "         bytes, 2^37 multiply-adds a frame group; 0 bytes = no limit)\n"
         "  info IN.ams [--json]: header, index and first group only\n"
         "  test IN.ams [--json] [--max-vertex-frames V] [--max-multiply-adds W]: checks every\n"
         "         section's CRC and decodes\n"
         "         every frame, writes nothing\n"
         "  compare ORIGINAL RECONSTRUCTED|IN.ams [--mesh M] [--json] [--per-frame]\n"
         "  join PART.ams... -o ALL.ams [--json]: one file of consecutive parts encoded with the\n"
         "         same settings (encode --frames A:B); the bytes of the whole sequence's encode\n"
         "         when every part but the last is a whole number of I-frame intervals\n"
         "  bench IN [--mesh M] [encode options] [--runs R] [--json]\n"
         "  bench IN [--mesh M] --read-only [--runs R] [--json]: reading the sequence only\n"
         "  bench IN.ams [--runs R] [--json] [--backwards]: decoding only, of that file\n"
         "--threads N (encode, decode, test, bench): the threads to use, 0 (the default) = one per\n"
         "         core; the bytes written and the frames decoded are the same for any N\n"
         "IN: .pc2/.mdd (optionally .xz, with --mesh), a " +
         animc::frameFileExtensionList() +
         " frame, a folder of\n"
         "them, a numbered pattern (frame_%04d.obj) or a .txt list of frame files.\n";
}

std::string usage() {
  std::string codecs;
  for (const animc::CodecEntry* codec : animc::allCodecs())
    codecs += (codecs.empty() ? "" : "|") + std::string(codec->name);
  return "usage: animc <command> ...   (animc --version prints the release)\n"
         "  encode IN -o OUT.ams [--mesh M] [--codec " +
         codecs + "] [--iframe-interval K]\n" + "         [--frames A:B]: frames A to B-1 of IN only\n" +
         "         (the codec is auto by default, affine-octree when --profile, --bits or\n"
         "         --max-depth is given)\n" +
         animc::cli::codecUsage() + usageAfterEncode();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace animc::cli;
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(usage().c_str(), argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "--version" || command == "version") {
    std::printf("animc %s (.ams formats up to %u)\n", animc::animcVersion(), unsigned(animc::kNewestFormatVersion));
    return 0;
  }
  removeTemporariesOnSignals();
  const std::vector<std::string> rest(argv + 2, argv + argc);
  if (command == "encode") return runEncode(rest);
  if (command == "decode") return runDecode(rest);
  if (command == "info") return runInfo(rest);
  if (command == "test") return runTest(rest);
  if (command == "compare") return runCompare(rest);
  if (command == "bench") return runBench(rest);
  if (command == "join") return runJoin(rest);
  std::fprintf(stderr, "animc: unknown command '%s' (animc --help lists them)\n", command.c_str());
  return 2;
}
