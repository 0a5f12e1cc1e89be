// SPDX-License-Identifier: Apache-2.0
#include "container/connectivity_coder.h"

#include <algorithm>
#include <string>

#include "core/large_memory.h"
#include "core/parallel.h"
#include "entropy/bit_tree.h"
#include "entropy/integer_coder.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

enum Choice : uint32_t { kCorner0 = 0, kCorner1, kCorner2, kNextNew, kDelta };

struct ConnectivityModels {
  BitTreeModel<3> choice[3];  // by corner position in the triangle
  IntegerModel<3> delta;
};

// A format-2 piece's entry in CONN's table: its stream's length and the Next_New it starts from.
constexpr uint64_t kPieceEntryBytes = 8 + 4;
// Range coding costs about this many operations a triangle (parallelFor's unit).
constexpr double kTriangleCost = 100;

uint32_t chooseFor(uint32_t index, const Triangle& previous, uint32_t next_new) {
  for (uint32_t k = 0; k < 3; ++k)
    if (previous[k] == index) return k;
  return index == next_new ? kNextNew : kDelta;
}

// One range-coded stream of triangles (format 1's whole CONN, or a piece of format 2), from
// fresh models, no previous triangle and Last = Next_New = next_new.
void encodeStream(const Triangle* begin, const Triangle* end, uint32_t next_new, std::vector<uint8_t>& out) {
  ConnectivityModels m;
  RangeEncoder rc(out);
  Triangle previous = {~0u, ~0u, ~0u};
  int64_t last = next_new;
  for (const Triangle* t = begin; t != end; ++t) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t choice = chooseFor((*t)[c], previous, next_new);
      encodeTree(rc, m.choice[c], choice);
      if (choice == kDelta) encodeInt(rc, m.delta, c, int64_t((*t)[c]) - last);
      last = (*t)[c];
      if ((*t)[c] >= next_new) next_new = (*t)[c] + 1;
    }
    previous = *t;
  }
  rc.finish();
}

// The `count` triangles of a stream encodeStream() wrote, each handed to put(triangle) in
// order; `first` numbers them in messages.
template <class Put>
Status decodeStream(ByteReader in, uint32_t vertex_count, uint64_t first, uint64_t count, uint32_t next_new,
                    const Put& put) {
  ConnectivityModels m;
  RangeDecoder rc(in.cursor(), in.remaining());
  Triangle previous = {~0u, ~0u, ~0u};
  int64_t last = next_new;
  for (uint64_t i = first; i < first + count; ++i) {
    Triangle t;
    for (int c = 0; c < 3; ++c) {
      const uint32_t choice = decodeTree(rc, m.choice[c]);
      int64_t index;
      if (choice < 3) index = previous[choice];
      else if (choice == kNextNew) index = next_new;
      else if (choice == kDelta) index = last + decodeInt(rc, m.delta, c);
      else return corrupt("connectivity: unknown index code in triangle " + std::to_string(i));
      if (index < 0 || index >= int64_t(vertex_count))
        return corrupt("connectivity: triangle " + std::to_string(i) + " uses vertex " + std::to_string(index) +
                       " of " + std::to_string(vertex_count));
      t[c] = uint32_t(index);
      last = index;
      if (t[c] >= next_new) next_new = t[c] + 1;
    }
    if (rc.overran()) return corrupt("connectivity: coded data ends early");
    put(t);
    previous = t;
  }
  return Status();
}

// A stream cannot honestly hold more than ~100 triangles per byte: no more is allocated up
// front, so a forged Triangle_Count costs nothing before its stream runs out.
uint64_t plausibleTriangles(size_t stream_bytes) { return 100 * uint64_t(stream_bytes) + 16; }

// Appends the triangles of a stream, the list growing as they come past what is plausible.
Status appendStream(const ByteReader& in, uint32_t vertex_count, uint64_t first, uint64_t count, uint32_t next_new,
                    std::vector<Triangle>& out) {
  out.reserve(out.size() + size_t(std::min<uint64_t>(count, plausibleTriangles(in.remaining()))));
  return decodeStream(in, vertex_count, first, count, next_new, [&](const Triangle& t) { out.push_back(t); });
}

struct Piece {
  uint64_t first = 0, count = 0;  // triangles
  uint32_t next_new = 0;
  uint64_t bytes = 0;
  ByteReader stream;
};

// Bytes a piece's stream is given before it is coded: a mesh in a poor triangle order codes
// to about 5 bytes a triangle; beyond that the stream grows.
constexpr size_t kReservedBytesPerTriangle = 6;

// A piece's stream while it is coded, on a cache line of its own: the coder moves the end of
// its vector at every byte, which threads coding neighbouring pieces would otherwise share.
struct alignas(64) PieceStream {
  std::vector<uint8_t> bytes;
};

// The table, then each piece's stream. The pieces are coded at once on the calling thread's
// budget, each into a buffer of its own reserved here on the calling thread: one a helper
// thread allocated would stay with that thread's heap once freed.
void encodePieces(const Topology& topology, uint32_t piece_triangles, std::vector<uint8_t>& out) {
  const std::vector<Triangle>& triangles = topology.triangles;
  const size_t pieces = (triangles.size() - 1) / piece_triangles + 1;
  auto beginOf = [&](size_t k) { return std::min(triangles.size(), k * size_t(piece_triangles)); };
  std::vector<uint32_t> next_new(pieces + 1, 0);  // one more than the largest index before each piece
  std::vector<PieceStream> streams(pieces);
  for (size_t k = 0; k < pieces; ++k) {
    streams[k].bytes.reserve(kReservedBytesPerTriangle * (beginOf(k + 1) - beginOf(k)));
    for (size_t i = beginOf(k); i < beginOf(k + 1); ++i)
      for (uint32_t v : triangles[i]) next_new[k + 1] = std::max(next_new[k + 1], v + 1);
    next_new[k + 1] = std::max(next_new[k + 1], next_new[k]);
  }
  parallelFor(pieces, kTriangleCost * piece_triangles, [&](size_t k) {
    encodeStream(triangles.data() + beginOf(k), triangles.data() + beginOf(k + 1), next_new[k], streams[k].bytes);
  });
  ByteWriter table;
  table.u32(piece_triangles);
  for (size_t k = 0; k < pieces; ++k) {
    table.u64(streams[k].bytes.size());
    table.u32(next_new[k]);
  }
  size_t bytes = table.size();
  for (const PieceStream& stream : streams) bytes += stream.bytes.size();
  const size_t at = out.size();
  resizeWithHugePages(out, at + bytes);
  auto to = std::copy(table.bytes().begin(), table.bytes().end(), out.begin() + ptrdiff_t(at));
  for (PieceStream& stream : streams) {
    to = std::copy(stream.bytes.begin(), stream.bytes.end(), to);
    stream.bytes = std::vector<uint8_t>();  // the connectivity is held about once, not twice
  }
}

// Format 2's table, checked: the pieces' streams must fill the rest of the payload exactly.
Result<std::vector<Piece>> readPieces(ByteReader in, uint32_t vertex_count, uint64_t triangle_count) {
  ANIMC_ASSIGN_OR_RETURN(uint32_t piece_triangles, in.u32("Piece_Triangles"));
  if (piece_triangles == 0) return corrupt("connectivity: Piece_Triangles is 0");
  const uint64_t count = triangle_count == 0 ? 0 : (triangle_count - 1) / piece_triangles + 1;
  if (count > in.remaining() / kPieceEntryBytes) return in.truncatedAt("connectivity piece table");
  std::vector<Piece> pieces(count);
  uint64_t stream_bytes = in.remaining() - count * kPieceEntryBytes;
  for (uint64_t k = 0; k < count; ++k) {
    Piece& p = pieces[k];
    p.first = k * piece_triangles;
    p.count = std::min<uint64_t>(piece_triangles, triangle_count - p.first);
    ANIMC_ASSIGN_OR_RETURN(uint64_t length, in.u64("Piece_Length"));
    ANIMC_ASSIGN_OR_RETURN(p.next_new, in.u32("Piece_Start"));
    if (length > stream_bytes) return corrupt("connectivity: piece " + std::to_string(k) + " runs past CONN");
    if (p.next_new > vertex_count)
      return corrupt("connectivity: piece " + std::to_string(k) + " starts past vertex " +
                     std::to_string(vertex_count));
    stream_bytes -= length;
    p.bytes = length;
  }
  if (stream_bytes != 0)
    return corrupt("connectivity: " + std::to_string(stream_bytes) + " bytes after the last piece");
  for (Piece& p : pieces) {  // the streams follow the table
    p.stream = ByteReader(in.cursor(), size_t(p.bytes), in.offset());
    ANIMC_RETURN_IF_ERROR(in.skip(size_t(p.bytes), "connectivity piece"));
  }
  return pieces;
}

// The pieces at once, each writing its own range of the list; or, when the triangle count is
// more than the payload plausibly holds, one after the other as appendStream() (the same
// triangles, or the same first error).
Status decodePieces(ByteReader in, uint32_t vertex_count, uint64_t triangle_count, std::vector<Triangle>& out) {
  const size_t payload_bytes = in.remaining();
  ANIMC_ASSIGN_OR_RETURN(std::vector<Piece> pieces, readPieces(in, vertex_count, triangle_count));
  if (triangle_count > plausibleTriangles(payload_bytes)) {
    for (const Piece& p : pieces)
      ANIMC_RETURN_IF_ERROR(appendStream(p.stream, vertex_count, p.first, p.count, p.next_new, out));
    return Status();
  }
  resizeWithHugePages(out, size_t(triangle_count));
  std::vector<Status> status(pieces.size());
  const double piece_cost = pieces.empty() ? 0 : kTriangleCost * double(pieces[0].count);
  parallelFor(pieces.size(), piece_cost, [&](size_t k) {
    const Piece& p = pieces[k];
    Triangle* next = out.data() + p.first;
    status[k] =
        decodeStream(p.stream, vertex_count, p.first, p.count, p.next_new, [&](const Triangle& t) { *next++ = t; });
  });
  for (const Status& s : status) ANIMC_RETURN_IF_ERROR(s);
  return Status();
}

}  // namespace

uint16_t formatVersionFor(uint64_t triangle_count, uint32_t piece_triangles) {
  return piece_triangles > 0 && triangle_count > piece_triangles ? 2 : 1;
}

void encodeConnectivity(const Topology& topology, uint32_t piece_triangles, std::vector<uint8_t>& out) {
  if (formatVersionFor(topology.triangles.size(), piece_triangles) == 1) {
    encodeStream(topology.triangles.data(), topology.triangles.data() + topology.triangles.size(), 0, out);
    return;
  }
  encodePieces(topology, piece_triangles, out);
}

Status decodeConnectivity(ByteReader in, uint16_t format_version, uint32_t vertex_count, uint64_t triangle_count,
                          Topology& topology) {
  topology.vertex_count = vertex_count;
  topology.triangles.clear();
  Status s = format_version == 1 ? appendStream(in, vertex_count, 0, triangle_count, 0, topology.triangles)
                                 : decodePieces(in, vertex_count, triangle_count, topology.triangles);
  if (!s.ok()) topology.triangles.clear();
  return s;
}

}  // namespace animc
