// SPDX-License-Identifier: Apache-2.0
// The .ams container, versions 1 and 2. docs/format.md describes every byte; this header is its
// single home in code. All integers little-endian.
//
//   File_Header  Magic "\x89AMS", Format_Version u16, Reserved u16 (= 0)
//   Section*     Tag[4], Length u64, Payload[Length], CRC32(Payload) u32
//     HEAD  codec, its parameters, vertex and triangle counts, frame rate, I-frame interval
//     CONN  the triangle list, order preserved, range coded: one stream (format 1) or
//           independent pieces of a fixed number of triangles (format 2, its only change)
//     GRUP  one per frame group: First_Frame u64, Frame_Count u32, then per frame
//           Frame_Length varint + codec payload (the first frame of a group is intra);
//           its CRC covers the frames only, the two counts are checked against INDX
//     INDX  Frame_Count u64, Group_Count u32, then per group Offset u64 + First_Frame u64
//     END   Index_Offset u64; always the last 24 bytes of the file
#pragma once
#include <cstdint>

#include "animc/animc.h"

namespace animc {

constexpr uint8_t kMagic[4] = {0x89, 'A', 'M', 'S'};
// Readers take every version up to this one; writers pick one (formatVersionFor()).
constexpr uint16_t kNewestFormatVersion = 2;
constexpr uint64_t kFileHeaderBytes = 8;
constexpr uint64_t kSectionOverhead = 4 + 8 + 4;  // tag, length, CRC
constexpr uint64_t kEndSectionBytes = kSectionOverhead + 8;
// GRUP's payload starts with First_Frame (u64) and Frame_Count (u32); its CRC skips them.
constexpr uint64_t kGroupFieldBytes = 8 + 4;

constexpr char kTagHead[5] = "HEAD";
constexpr char kTagConnectivity[5] = "CONN";
constexpr char kTagGroup[5] = "GRUP";
constexpr char kTagIndex[5] = "INDX";
constexpr char kTagEnd[5] = "END ";

// An intra frame spends at least 3 adaptive binary decisions per vertex, and no decision
// costs less than ~0.0014 bits (the coder's most skewed probability), so a frame of B bytes
// cannot describe more than this many vertices: a bound that needs no trust in the header.
constexpr uint64_t kMaxVerticesPerIntraByte = 2048;

// The decoder ceilings are DecoderLimits (animc/animc.h): a file asking for more is refused
// before anything is allocated. The decoder keeps ~200 bytes per vertex, so the default vertex
// ceiling caps it near 1 GB.

}  // namespace animc
