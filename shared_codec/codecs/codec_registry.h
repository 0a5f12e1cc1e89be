// SPDX-License-Identifier: Apache-2.0
// The codec table: one entry per codec holds everything the library, the animc tool and the
// reports need to know of it (its id and name, its options on the command line, in the file
// and in reports, its encoder and decoder), so that a codec, or an option of one, is added in
// one place. docs/adding_a_codec.md lists the steps.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "codecs/codec_ids.h"
#include "codecs/codec_options.h"
#include "codecs/frame_codec.h"
#include "codecs/option_values.h"
#include "core/sequence.h"
#include "core/simd_math.h"
#include "core/status.h"
#include "io/byte_reader.h"
#include "io/byte_writer.h"

namespace animc {

// An entry's encoder factory, or null in a decoder-only build (ANIMC_DECODER_ONLY: the
// WebAssembly decoder of web/), which then links no encoder.
#ifdef ANIMC_DECODER_ONLY
#define ANIMC_ENCODER(factory) nullptr
#else
#define ANIMC_ENCODER(factory) factory
#endif

struct CodecEntry {
  CodecId id;
  const char* name;  // on the command line and in reports: "affine-octree"

  // Command line: the codec's options that take a value, its switches, and its usage (the
  // options, then what their values mean; lines after the first indented by 11 spaces).
  std::vector<std::string> value_flags;
  std::vector<std::string> switch_flags;
  const char* usage;
  // The codec's defaults with the flags of `values` applied (range-checked).
  Result<CodecOptions> (*fromFlags)(const OptionValues& values);

  Status (*validate)(const CodecOptions& options);
  // Codec_Params of the HEAD section (docs/format.md 10.1, 11.1).
  void (*write)(const CodecOptions& options, ByteWriter& out);
  Result<CodecOptions> (*read)(ByteReader& in);
  // "profile predictive, max error 0.01 of the root cube, bits 16", for a settings line.
  std::string (*describe)(const CodecOptions& options);
  std::vector<SettingValue> (*settings)(const CodecOptions& options);

  // Why this codec cannot code a mesh the container accepts, or ok.
  Status (*checkMesh)(const Topology& topology);
  // The coders run the kernels of `path` (core/simd_math.h): chosen once, here, by the
  // caller (the API passes bestSimdPath()), and the same bytes and frames either way. A coder
  // (encoder or decoder) may keep a reference to `topology`: it must outlive the coder (a large
  // mesh is not copied for each coder of a sequence).
  std::unique_ptr<FrameEncoder> (*makeEncoder)(const CodecOptions& options, const Topology& topology, SimdPath path);
  // For a codec that codes whole groups, instead of makeEncoder (which is then null).
  std::unique_ptr<GroupEncoder> (*makeGroupEncoder)(const CodecOptions& options, const Topology& topology,
                                                    SimdPath path);
  // A decoder for the file's options, within decoding's limits; `file` names the file in
  // messages (progressive decoding is refused for codecs and files that cannot be cut).
  Result<std::unique_ptr<FrameDecoder>> (*makeDecoder)(const CodecOptions& options, const Topology& topology,
                                                       const DecoderOptions& decoding, const std::string& file,
                                                       SimdPath path);
};

// CodecEntry's validate, write and read for an options type with the members validate(),
// write(ByteWriter&) and static read(ByteReader&), as both codecs' options have.
template <class Options>
Status validateOptions(const CodecOptions& o) {
  return std::get<Options>(o).validate();
}
template <class Options>
void writeOptions(const CodecOptions& o, ByteWriter& out) {
  std::get<Options>(o).write(out);
}
template <class Options>
Result<CodecOptions> readOptions(ByteReader& in) {
  ANIMC_ASSIGN_OR_RETURN(Options o, Options::read(in));
  return CodecOptions(o);
}

// Every codec, in Codec_Id order.
const std::vector<const CodecEntry*>& allCodecs();
// The entry of a codec id, or null for an id this build does not implement.
const CodecEntry* findCodec(uint8_t id);
// The entry of a codec name, or an error listing the names.
Result<const CodecEntry*> findCodecByName(const std::string& name);
// The entry of the codec whose options these are.
const CodecEntry& codecOf(const CodecOptions& options);

const char* codecName(CodecId id);  // "affine-octree", "wavelet", "trajectory"
std::string knownCodecList();       // "1 (affine-octree), 2 (wavelet), 3 (trajectory), 4 (auto)"

// The entries of the codecs (each in its codec's folder).
extern const CodecEntry kAffineOctreeEntry;
extern const CodecEntry kWaveletEntry;
extern const CodecEntry kTrajectoryEntry;
extern const CodecEntry kAutoEntry;
extern const CodecEntry kTrajectory2Entry;

}  // namespace animc
