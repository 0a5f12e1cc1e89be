#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Writes the seed corpora of the fuzz harnesses, OUT/ams_decode, OUT/sequence_readers and
# OUT/layer_checks (named after their harnesses), from which the in-tree corpus tests/fuzz/corpus
# grew.
#   usage: tests/fuzz/make_seeds.sh path/to/animc OUT
# Sources: a 20-vertex grid made here, the first 3 frames of samples/sydney, and two patches of
# sydney's surface (60 and 90 vertices, cut here) whose files stay under fuzz_ams_decode's
# max_len (campaign.sh), encoded by the project's own animc with several settings of every
# codec and decoded back to every format; for layer_checks, layers written here and the smaller
# golden files of tests/golden.
set -euo pipefail
ANIMC=$(realpath "$1")
OUT=$(realpath -m "$2")
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
mkdir -p "$OUT/ams_decode" "$OUT/sequence_readers" "$OUT/layer_checks"

# The grid (binary PLY + PC2) and sydney cut to 3 frames (PC2).
/usr/bin/python3 - "$WORK" "$ROOT/samples/sydney/sydney_50.pc2.xz" "$ROOT/samples/sydney/sydney_md2.ply" <<'PY'
import collections, lzma, math, struct, sys
work, sydney, sydney_mesh = sys.argv[1], sys.argv[2], sys.argv[3]
nx, ny, frames = 5, 4, 8
faces = []
for y in range(ny - 1):
    for x in range(nx - 1):
        a = y * nx + x
        faces += [(a, a + 1, a + nx + 1), (a, a + nx + 1, a + nx)]
def frame(f):
    return [c for y in range(ny) for x in range(nx)
            for c in (x / (nx - 1) + 0.02 * f, y / (ny - 1), 0.2 * math.sin(3 * x / nx + 0.4 * f))]
header = ('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
          'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'
          % (nx * ny, len(faces))).encode()
with open(work + '/grid.ply', 'wb') as f:
    f.write(header + struct.pack('<%df' % (3 * nx * ny), *frame(0)))
    for t in faces:
        f.write(struct.pack('<B3i', 3, *t))
with open(work + '/grid.pc2', 'wb') as f:
    f.write(struct.pack('<12siiffi', b'POINTCACHE2\0', 1, nx * ny, 0.0, 1.0, frames))
    for i in range(frames):
        f.write(struct.pack('<%df' % (3 * nx * ny), *frame(i)))
with lzma.open(sydney, 'rb') as f:
    magic, version, points, start, rate, count = struct.unpack('<12siiffi', f.read(32))
    body = f.read(3 * points * 12)
with open(work + '/sydney3.pc2', 'wb') as f:
    f.write(struct.pack('<12siiffi', magic, version, points, start, rate, 3) + body)
# Patches: the first `size` vertices met breadth-first from `seed`, and the triangles among them.
ply = open(sydney_mesh, 'rb').read()
at = ply.index(b'end_header\n') + len(b'end_header\n')
triangles = [struct.unpack_from('<3i', ply, at + 12 * points + 13 * k + 1)
             for k in range((len(ply) - at - 12 * points) // 13)]
around = collections.defaultdict(set)
for t in triangles:
    for v in t:
        around[v].update(t)
for size, seed in ((60, 0), (90, 200)):
    kept, queue = [seed], collections.deque([seed])
    while queue and len(kept) < size:
        for w in sorted(around[queue.popleft()]):
            if w not in kept and len(kept) < size:
                kept.append(w)
                queue.append(w)
    inside = [t for t in triangles if all(v in kept for v in t)]
    used = sorted({v for t in inside for v in t})
    index = {v: i for i, v in enumerate(used)}
    name = work + '/patch%d' % size
    with open(name + '.ply', 'wb') as f:
        f.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
                 'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n'
                 % (len(used), len(inside))).encode())
        f.write(b''.join(ply[at + 12 * v:at + 12 * v + 12] for v in used))
        f.write(b''.join(struct.pack('<B3i', 3, *(index[v] for v in t)) for t in inside))
    with open(name + '.pc2', 'wb') as f:
        f.write(struct.pack('<12siiffi', magic, version, len(used), start, rate, 3))
        for frame in range(3):
            f.write(b''.join(body[12 * (points * frame + v):12 * (points * frame + v) + 12] for v in used))
PY

# Control bytes of fuzz_ams_decode: repair CRCs (1), progressive (2), seek (4); seek frame;
# bitplanes; payload bytes / 4.
prefix() { printf "\\x$(printf %02x "$1")\\x$(printf %02x "$2")\\x$(printf %02x "$3")\\x$(printf %02x "$4")"; }
ams_seed() {  # name, cuttable (1/0), file
  { prefix 1 0 0 0; cat "$3"; } > "$OUT/ams_decode/$1"
  { prefix 5 2 0 0; cat "$3"; } > "$OUT/ams_decode/$1.seek2"
  if [ "$2" = 1 ]; then
    { prefix 7 1 3 0; cat "$3"; } > "$OUT/ams_decode/$1.planes3"
    { prefix 3 0 0 8; cat "$3"; } > "$OUT/ams_decode/$1.bytes32"
  fi
}
encode() {  # name, cuttable, input, mesh, options...
  local name=$1 cuttable=$2 input=$3 mesh=$4
  shift 4
  "$ANIMC" encode "$input" --mesh "$mesh" -o "$WORK/$name.ams" "$@" >/dev/null
  ams_seed "$name" "$cuttable" "$WORK/$name.ams"
}
G=("$WORK/grid.pc2" "$WORK/grid.ply")
S=("$WORK/sydney3.pc2" "$ROOT/samples/sydney/sydney_md2.ply")
encode grid_octree 0 "${G[@]}" --codec affine-octree --max-error 0.02
encode grid_octree_i3 0 "${G[@]}" --codec affine-octree --max-error 0.02 --iframe-interval 3
encode grid_octree_paper 0 "${G[@]}" --max-error 0.02 --profile paper --iframe-interval 4
encode grid_octree_bits10 0 "${G[@]}" --max-error 0.05 --bits 10 --max-depth 4
encode grid_wavelet 0 "${G[@]}" --codec wavelet --step 1e-2
encode grid_wavelet_pp 1 "${G[@]}" --codec wavelet --step 1e-2 --iframe-interval 3 --progressive-p-frames
encode grid_wavelet_ionly 1 "${G[@]}" --codec wavelet --step 1e-2 --i-frames-only
encode grid_wavelet_bpv 1 "${G[@]}" --codec wavelet --bpv 8 --progressive-p-frames
encode grid_wavelet_kg 0 "${G[@]}" --codec wavelet --target-kg 1 --parametric-bits 10
encode sydney_octree 0 "${S[@]}" --codec affine-octree --max-error 0.02
encode sydney_wavelet_pp 1 "${S[@]}" --codec wavelet --step 1e-2 --progressive-p-frames
encode grid_trajectory 0 "${G[@]}" --codec trajectory --target-kg 1
encode grid_trajectory_i3 0 "${G[@]}" --codec trajectory --max-error 0.02 --iframe-interval 3
encode grid_auto_i2 0 "${G[@]}" --codec auto --max-error 0.02 --iframe-interval 2
encode grid_trajectory2 0 "${G[@]}" --codec trajectory2 --target-kg 1 --parts 3
encode sydney_trajectory2 0 "${S[@]}" --codec trajectory2 --bpvf 4
# Groups of several parts (labels and part tables), within the harness's max_len.
T=("$ROOT/tests/golden/input/two_motions.pc2.xz" "$ROOT/tests/golden/input/two_motions.ply")
encode two_motions_trajectory2 0 "${T[@]}" --codec trajectory2 --target-kg 1
encode two_motions_trajectory2_i16 0 "${T[@]}" --codec trajectory2 --target-kg 2 --parts 4 --iframe-interval 16
encode sydney_trajectory 0 "${S[@]}" --codec trajectory --bpvf 4
encode sydney_auto 0 "${S[@]}" --codec auto --target-kg 0.5
encode grid_octree_format2 0 "${G[@]}" --codec affine-octree --max-error 0.02 --connectivity-piece 5
for size in 60 90; do
  P=("$WORK/patch$size.pc2" "$WORK/patch$size.ply")
  encode "patch${size}_octree" 0 "${P[@]}" --codec affine-octree --max-error 0.02
  encode "patch${size}_wavelet_pp" 1 "${P[@]}" --codec wavelet --step 1e-2 --progressive-p-frames
  encode "patch${size}_wavelet_ionly" 1 "${P[@]}" --codec wavelet --step 1e-2 --i-frames-only
  encode "patch${size}_trajectory" 0 "${P[@]}" --codec trajectory --bpvf 4
  encode "patch${size}_trajectory2" 0 "${P[@]}" --codec trajectory2 --target-kg 0.3 --parts 4
  encode "patch${size}_auto" 0 "${P[@]}" --codec auto --target-kg 0.5
done
encode patch90_trajectory_format2 0 "$WORK/patch90.pc2" "$WORK/patch90.ply" --codec trajectory --bpvf 4 \
  --connectivity-piece 40

# Sequence readers: control byte 0 picks .ply .off .pc2 .mdd .pc2.xz .mdd.xz .obj, byte 1 is the
# point caches' vertex count - 1 (the grid has 20 vertices).
seq_seed() {  # name, kind, file
  { printf "\\x$(printf %02x "$2")\\x13"; cat "$3"; } > "$OUT/sequence_readers/$1"
}
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_out.pc2" >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_out.mdd" >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_off" --format off --frames 0 >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_ply" --format ply --frames 0 >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_obj" --format obj --frames 0 >/dev/null
seq_seed grid.ply 0 "$WORK/grid.ply"
seq_seed grid_decoded.ply 0 "$WORK/grid_ply/frame_00000.ply"
seq_seed grid.off 1 "$WORK/grid_off/frame_00000.off"
seq_seed grid.pc2 2 "$WORK/grid_out.pc2"
seq_seed grid.mdd 3 "$WORK/grid_out.mdd"
xz --check=crc32 -c "$WORK/grid_out.pc2" > "$WORK/grid.pc2.xz"
xz --check=none -c "$WORK/grid_out.mdd" > "$WORK/grid.mdd.xz"
seq_seed grid.pc2.xz 4 "$WORK/grid.pc2.xz"
seq_seed grid.mdd.xz 5 "$WORK/grid.mdd.xz"
seq_seed grid.obj 6 "$WORK/grid_obj/frame_00000.obj"
# Several files, joined by the harness's separator: frame folders, .txt lists and point caches
# with a mesh (control byte 0 = format + 7 * layout, see fuzz_sequence_readers.cpp).
files_seed() {  # name, control byte, files...
  local name=$1 control=$2 first=1
  shift 2
  { printf "\\x$(printf %02x "$control")\\x00"
    for file in "$@"; do
      [ $first = 1 ] || printf '#next#'
      first=0
      cat "$file"
    done; } > "$OUT/sequence_readers/$name"
}
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_ply2" --format ply --frames 0:2 >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_off2" --format off --frames 0:2 >/dev/null
"$ANIMC" decode "$WORK/grid_octree.ams" -o "$WORK/grid_obj2" --format obj --frames 0:2 >/dev/null
printf 'f0.ply\n# a comment\n\nf1.ply\n' > "$WORK/list.txt"
printf 'f0.obj\r\nf1.obj\n' > "$WORK/list_obj.txt"
PLY2=("$WORK/grid_ply2/frame_00000.ply" "$WORK/grid_ply2/frame_00001.ply")
OBJ2=("$WORK/grid_obj2/frame_00000.obj" "$WORK/grid_obj2/frame_00001.obj")
files_seed folder.ply 7 "${PLY2[@]}"
files_seed folder.off 8 "$WORK/grid_off2/frame_00000.off" "$WORK/grid_off2/frame_00001.off"
files_seed folder.obj 13 "${OBJ2[@]}"
files_seed list.ply 14 "$WORK/list.txt" "${PLY2[@]}"
files_seed list.obj 20 "$WORK/list_obj.txt" "${OBJ2[@]}"
files_seed mesh_folder.ply 21 "$WORK/grid.ply" "${PLY2[@]}"
files_seed mesh_folder.obj 27 "$WORK/grid.ply" "${OBJ2[@]}"
files_seed mesh.pc2 9 "$WORK/grid.ply" "$WORK/grid_out.pc2"
files_seed mesh_off.mdd 17 "$WORK/grid_off/frame_00000.off" "$WORK/grid_out.mdd"
files_seed mesh.pc2.xz 25 "$WORK/grid.ply" "$WORK/grid.pc2.xz"
# PLY in ASCII and big-endian, with extra properties and a quad, written by hand.
{ printf '\x00\x00'
  printf 'ply\nformat ascii 1.0\ncomment fuzz seed\nelement vertex 5\nproperty float x\nproperty float y\n'
  printf 'property float z\nproperty uchar red\nelement face 2\nproperty list uchar int vertex_indices\n'
  printf 'property float quality\nend_header\n0 0 0 1\n1 0 0 2\n1 1 0 3\n0 1 0 4\n2 2 1 5\n4 0 1 2 3 0.5\n3 2 3 4 1\n'
} > "$OUT/sequence_readers/quad_ascii.ply"
/usr/bin/python3 - "$OUT/sequence_readers/quad_be.ply" <<'PY'
import struct, sys
head = (b'ply\nformat binary_big_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n'
        b'property double z\nelement face 1\nproperty list uint8 uint16 vertex_indices\nend_header\n')
body = struct.pack('>12d', 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack('>B4H', 4, 0, 1, 2, 3)
open(sys.argv[1], 'wb').write(b'\x00\x00' + head + body)
PY
{ printf '\x01\x00'
  printf 'OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n'
} > "$OUT/sequence_readers/square.off"
{ printf '\x06\x00'
  printf '# fuzz seed\r\nmtllib a.mtl\r\no A\r\nv 0 0 0\r\nv 1 0 0 1\r\nv 1 1 0 0.5 0.5 0.5\r\nv 0 1 0\r\n'
  printf 'vt 0 0\r\nvt 1 1\r\nvn 0 0 1\r\ng g\r\ns 1\r\nusemtl m\r\nf 1/1/1 2/2/1 3//1 4/1 # quad\r\n'
  printf 'l 1 2\r\nf -4 -2 -1'
} > "$OUT/sequence_readers/square.obj"
# Layer checks: four layers (slot 1 deleted, a deleted face; the first again; again with a
# deleted vertex appended; another mesh), then a golden file with the whole range, a range
# above the memory limit and one above the work limit (control bytes: fuzz_layer_checks.cpp).
/usr/bin/python3 - "$OUT/layer_checks" "$ROOT/tests/golden" <<'PY'
import os, sys
out, golden = sys.argv[1], sys.argv[2]
first = bytes([5, 2, 0]) + bytes(range(6)) + bytes([3, 0, 2, 3, 0x80, 1, 2, 2, 3, 4])
layers = first + bytes([0]) + bytes(6) + bytes([2]) + bytes(6) + bytes([1, 3, 0, 0, 1, 2, 3, 4, 1, 0, 1, 2])
ranges = {'all': (0, 255, 255, 7, 18), 'memory': (1, 2, 0, 7, 18), 'work': (0, 255, 255, 7, 0)}
for name in ('affine_octree_default.v1', 'wavelet.v1', 'trajectory.v1.target_kg', 'trajectory.v1.max_error',
             'affine_octree_paper.v1'):
    stream = open(os.path.join(golden, name + '.ams'), 'rb').read()
    for kind, (first_frame, last_frame, megabytes, element, work) in ranges.items():
        control = bytes([3, first_frame, last_frame, megabytes, element, work, 0, len(layers)])
        open(os.path.join(out, name + '.' + kind), 'wb').write(control + layers + stream)
PY
echo "seeds: $(ls "$OUT/ams_decode" | wc -l) in $OUT/ams_decode ($(du -sh "$OUT/ams_decode" | cut -f1)),"\
  "$(ls "$OUT/sequence_readers" | wc -l) in $OUT/sequence_readers, $(ls "$OUT/layer_checks" | wc -l) in $OUT/layer_checks"
