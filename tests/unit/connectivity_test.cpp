// SPDX-License-Identifier: Apache-2.0
// The CONN section's two layouts (docs/format.md, section 6.2): one stream (format 1) and
// pieces of a fixed number of triangles (format 2). Both must give back the triangle list
// exactly; the pieces must code and decode the same on any number of threads; a damaged piece
// table is refused with a Status before anything is allocated for it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "container/connectivity_coder.h"
#include "core/parallel.h"
#include "io/byte_writer.h"
#include "test_sequences.h"

namespace animc {
namespace {

using Bytes = std::vector<uint8_t>;

Topology grid() { return testing_support::gridTopology(13, 11); }  // 143 vertices, 240 triangles

Result<Topology> decoded(const Bytes& payload, uint16_t version, const Topology& like) {
  Topology out;
  ANIMC_RETURN_IF_ERROR(decodeConnectivity(ByteReader(payload.data(), payload.size()), version, like.vertex_count,
                                           like.triangles.size(), out));
  return out;
}

Bytes coded(const Topology& topology, uint32_t piece) {
  Bytes out;
  encodeConnectivity(topology, piece, out);
  return out;
}

TEST(Connectivity, FormatTwoOnlyWhenThereIsMoreThanOnePiece) {
  EXPECT_EQ(formatVersionFor(240, 0), 1);
  EXPECT_EQ(formatVersionFor(240, 240), 1);
  EXPECT_EQ(formatVersionFor(240, 239), 2);
  EXPECT_EQ(formatVersionFor(0, 1), 1);
  // One piece is format 1's stream, byte for byte.
  EXPECT_EQ(coded(grid(), 0), coded(grid(), 240));
}

TEST(Connectivity, EveryPieceLengthGivesBackTheTriangles) {
  const Topology mesh = grid();
  for (uint32_t piece : {0u, 1u, 2u, 7u, 64u, 239u, 240u, 1000u}) {
    const uint16_t version = formatVersionFor(mesh.triangles.size(), piece);
    auto out = decoded(coded(mesh, piece), version, mesh);
    ASSERT_TRUE(out.ok()) << piece << ": " << out.status().message();
    EXPECT_EQ(out.value().triangles, mesh.triangles) << "pieces of " << piece;
    EXPECT_EQ(out.value().vertex_count, mesh.vertex_count);
  }
}

// Each piece starts afresh from its table entry, so the cut costs a little and no more.
TEST(Connectivity, PiecesCostAFewBytesEach) {
  const Topology mesh = grid();
  const size_t whole = coded(mesh, 0).size(), pieces = coded(mesh, 60).size();
  EXPECT_GT(pieces, whole);
  EXPECT_LT(pieces, whole + 4 * 40 + 4);  // four pieces: table entries plus a short restart each
}

TEST(Connectivity, PiecesDecodeTheSameOnAnyNumberOfThreads) {
  const Topology mesh = testing_support::gridTopology(120, 100);  // 23 562 triangles: worth threads
  const Bytes payload = coded(mesh, 1000);
  for (unsigned threads : {1u, 2u, 3u, 0u}) {
    ThreadBudget budget(resolveThreads(threads));
    auto out = decoded(payload, 2, mesh);
    ASSERT_TRUE(out.ok()) << out.status().message();
    EXPECT_EQ(out.value().triangles, mesh.triangles) << threads << " threads";
  }
}

// The grid with its vertex labels shuffled: a piece's largest index is then often below an
// earlier piece's.
Topology shuffledGrid() {
  Topology mesh = testing_support::gridTopology(120, 100);
  std::vector<uint32_t> label(mesh.vertex_count);
  std::iota(label.begin(), label.end(), 0u);
  std::shuffle(label.begin(), label.end(), std::mt19937(3));
  for (Triangle& t : mesh.triangles)
    for (uint32_t& v : t) v = label[v];
  return mesh;
}

TEST(Connectivity, PiecesCodeTheSameOnAnyNumberOfThreads) {
  const Topology mesh = shuffledGrid();
  Bytes one;
  {
    ThreadBudget budget(1);
    one = coded(mesh, 1000);
  }
  for (unsigned threads : {2u, 3u, 0u}) {
    ThreadBudget budget(resolveThreads(threads));
    EXPECT_EQ(coded(mesh, 1000), one) << threads << " threads";
  }
  auto out = decoded(one, 2, mesh);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out.value().triangles, mesh.triangles);
  // The table (docs/format.md 6.2.2): each piece starts one past the largest index of the
  // triangles before it, and the streams fill the rest of the payload.
  ByteReader table(one.data(), one.size());
  ASSERT_EQ(table.u32("Piece_Triangles").value(), 1000u);
  const size_t pieces = (mesh.triangles.size() + 999) / 1000;
  uint32_t start = 0;
  uint64_t stream_bytes = 0;
  for (size_t k = 0; k < pieces; ++k) {
    stream_bytes += table.u64("Piece_Length").value();
    EXPECT_EQ(table.u32("Piece_Start").value(), start) << "piece " << k;
    for (size_t i = k * 1000; i < std::min(mesh.triangles.size(), (k + 1) * 1000); ++i)
      for (uint32_t v : mesh.triangles[i]) start = std::max(start, v + 1);
  }
  EXPECT_EQ(table.remaining(), stream_bytes);
}

// A list that codes to almost nothing (one triangle over and over) claims more triangles than
// its bytes plausibly hold: the decoder then takes the pieces one after the other, growing the
// list as they come, and must give back the same triangles.
TEST(Connectivity, ATinyPayloadOfManyTrianglesDecodesPieceByPiece) {
  Topology repeated;
  repeated.vertex_count = 3;
  repeated.triangles.assign(100000, Triangle{0, 1, 2});
  const Bytes payload = coded(repeated, 10000);
  ASSERT_LT(100 * payload.size() + 16, repeated.triangles.size()) << "not the case this test is for";
  ThreadBudget budget(2);
  auto out = decoded(payload, 2, repeated);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out.value().triangles, repeated.triangles);
}

// A format-2 payload with its table rewritten.
struct Table {
  uint32_t piece_triangles;
  std::vector<uint64_t> lengths;
  std::vector<uint32_t> next_new;
  Bytes streams;
};

Table tableOf(const Bytes& payload, uint64_t triangles) {
  ByteReader r(payload.data(), payload.size());
  Table t;
  t.piece_triangles = r.u32("").value();
  for (uint64_t k = 0; k < (triangles - 1) / t.piece_triangles + 1; ++k) {
    t.lengths.push_back(r.u64("").value());
    t.next_new.push_back(r.u32("").value());
  }
  t.streams.assign(r.cursor(), r.cursor() + r.remaining());
  return t;
}

Bytes payloadOf(const Table& t) {
  ByteWriter w;
  w.u32(t.piece_triangles);
  for (size_t k = 0; k < t.lengths.size(); ++k) {
    w.u64(t.lengths[k]);
    w.u32(t.next_new[k]);
  }
  w.append(t.streams);
  return w.bytes();
}

StatusCode codeOf(const Table& t, const Topology& mesh) { return decoded(payloadOf(t), 2, mesh).status().code(); }

TEST(Connectivity, ADamagedPieceTableIsRefused) {
  const Topology mesh = grid();
  const Table good = tableOf(coded(mesh, 50), mesh.triangles.size());
  ASSERT_EQ(good.lengths.size(), 5u);
  ASSERT_EQ(codeOf(good, mesh), StatusCode::kOk);

  Table t = good;
  t.piece_triangles = 0;
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kCorrupt) << "no triangles a piece";
  t = good;
  t.lengths[1] += 1;  // the streams no longer fill the payload
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kCorrupt) << "a piece runs past CONN";
  t = good;
  t.lengths[1] -= 1;
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kCorrupt) << "bytes after the last piece";
  t = good;
  t.lengths[4] = ~uint64_t(0);
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kCorrupt) << "a length that would wrap";
  t = good;
  t.next_new[2] = mesh.vertex_count + 1;
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kCorrupt) << "a piece starting past the last vertex";
  // One triangle a piece claims a table of 240 entries that the payload cannot hold.
  t = good;
  t.piece_triangles = 1;
  EXPECT_EQ(codeOf(t, mesh), StatusCode::kTruncated);
  EXPECT_EQ(decoded(Bytes{1, 0}, 2, mesh).status().code(), StatusCode::kTruncated) << "no whole Piece_Triangles";
}

// The format-2 decoder reads a piece's stream only: damage in one piece's bytes shows up in
// that piece's triangles (or its refusal), and a wrong Next_New in the table only shifts the
// indices it codes, each still checked against the vertex count.
TEST(Connectivity, DamageInsideAPieceNeverEscapesIt) {
  const Topology mesh = grid();
  const Table good = tableOf(coded(mesh, 50), mesh.triangles.size());
  for (size_t i = good.lengths[0]; i < good.lengths[0] + good.lengths[1]; ++i) {
    Table t = good;
    t.streams[i] ^= 0xFF;
    auto out = decoded(payloadOf(t), 2, mesh);
    if (!out.ok()) continue;
    for (size_t tri = 0; tri < mesh.triangles.size(); ++tri) {
      if (tri >= 50 && tri < 100) continue;  // the damaged piece
      ASSERT_EQ(out.value().triangles[tri], mesh.triangles[tri]) << i << ", " << tri;
    }
  }
}

}  // namespace
}  // namespace animc
