#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# OBJ frame sequences through animc, as exporters write them:
#   - Sydney's frames as OBJ with normals, texture coordinates, every corner form and CRLF give
#     the same .ams bytes as the same frames given as PC2 + PLY, as a folder, a numbered
#     pattern and a .txt list;
#   - a quad (and pentagon) mesh encodes and decodes within the max-error bound;
#   - decode --format obj writes frames that read back (compare, encode) as the .ams's frames;
#   - a frame whose faces differ, or a bad line, fails with one line naming file and line.
# usage: obj_sequences_test.sh ANIMC_BINARY SAMPLES_DIR
set -euo pipefail

ANIMC=${1:?usage: obj_sequences_test.sh ANIMC_BINARY SAMPLES_DIR}
SAMPLES=${2:?usage: obj_sequences_test.sh ANIMC_BINARY SAMPLES_DIR}
PY=/usr/bin/python3
PC2=$SAMPLES/sydney/sydney_50.pc2.xz
MESH=$SAMPLES/sydney/sydney_md2.ply
MAKE_OBJ=$(dirname "$0")/make_obj_frames.py
[[ -x $ANIMC && -f $PC2 && -f $MESH ]] || { echo "FAIL: $ANIMC or the samples are missing" >&2; exit 1; }

source "$(dirname "$0")/cli_support.sh"

# --- the same bytes as PC2 + PLY -----------------------------------------------------------
run make_exported "$PY" "$MAKE_OBJ" exported "$PC2" "$MESH" "$TMP/walk"
[[ -f $TMP/walk/walk_0050.obj ]] || die "make_obj_frames.py wrote no walk_0050.obj"
grep -q $'\r' "$TMP/walk/walk_0002.obj" && grep -q '^vn' "$TMP/walk/walk_0001.obj" &&
  grep -q '^f -[0-9]*/-' "$TMP/walk/walk_0001.obj" || die "the OBJ frames lack CRLF, normals or negative indices"
run pc2_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/pc2.ams"
(cd "$TMP/walk" && ls walk_*.obj | sort -r) >"$TMP/walk/reversed.txt"  # a list is taken in its own order
sort "$TMP/walk/reversed.txt" >"$TMP/walk/frames.txt"
for input in "$TMP/walk" "$TMP/walk/walk_%04d.obj" "$TMP/walk/frames.txt"; do
  run obj_encode "$ANIMC" encode "$input" -o "$TMP/obj.ams"
  cmp -s "$TMP/obj.ams" "$TMP/pc2.ams" || check_failed "encode $input: not the bytes of PC2 + PLY"
done
run obj_trajectory "$ANIMC" encode "$TMP/walk" -o "$TMP/obj_t.ams" --codec trajectory --target-kg 0.3
run pc2_trajectory "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/pc2_t.ams" --codec trajectory --target-kg 0.3
cmp -s "$TMP/obj_t.ams" "$TMP/pc2_t.ams" || check_failed "trajectory: OBJ frames and PC2 + PLY differ"
run obj_reversed "$ANIMC" encode "$TMP/walk/reversed.txt" -o "$TMP/reversed.ams"
cmp -s "$TMP/reversed.ams" "$TMP/pc2.ams" && check_failed "a reversed .txt list gave the bytes of the forward frames"

# --- quads, within the bound, and decode --format obj --------------------------------------
run make_quads "$PY" "$MAKE_OBJ" quads 20 30 "$TMP/grid"
for codec in auto affine-octree trajectory; do
  run "quads_$codec" "$ANIMC" encode "$TMP/grid" -o "$TMP/grid_$codec.ams" --codec "$codec" --max-error 0.01
  run "quads_${codec}_compare" "$ANIMC" compare "$TMP/grid" "$TMP/grid_$codec.ams" --json
  json_check 'd["max_error_rel_cube"] <= 0.01 * 1.02 and d["frames"] == 30 and d["vertices"] == 442' \
    "$TMP/quads_${codec}_compare.out"
done
run quads_info "$ANIMC" info "$TMP/grid_auto.ams" --json
json_check 'd["triangles"] == 2 * 400 + 3' "$TMP/quads_info.out"

run decode_obj "$ANIMC" decode "$TMP/grid_auto.ams" -o "$TMP/grid_out" --format obj
[[ -f $TMP/grid_out/frame_00000.obj && -f $TMP/grid_out/frame_00029.obj ]] || check_failed "decode --format obj: no frame_000NN.obj"
run decoded_compare "$ANIMC" compare "$TMP/grid" "$TMP/grid_out" --json
same_kg "$TMP/decoded_compare.out" "$TMP/quads_auto_compare.out"
run decoded_self "$ANIMC" compare "$TMP/grid_out" "$TMP/grid_auto.ams" --json
json_check 'd["max_error"] == 0' "$TMP/decoded_self.out"
run reencode "$ANIMC" encode "$TMP/grid_out/frame_%05d.obj" -o "$TMP/again.ams" --json
json_check 'd["frames"] == 30' "$TMP/reencode.out"
run decode_obj_range "$ANIMC" decode "$TMP/grid_auto.ams" -o "$TMP/part.obj" --frames 3:5
[[ $(ls "$TMP/part.obj") == $'frame_00000.obj\nframe_00001.obj' ]] || check_failed "an output named .obj is not OBJ frames"

# --- errors name the file and the line -----------------------------------------------------
# fails NAME EXPECTED CMD...: CMD exits non-zero with one stderr line holding EXPECTED.
fails() {
  local name=$1 expected=$2 rc=0
  shift 2
  "$@" >"$TMP/$name.out" 2>"$TMP/$name.err" || rc=$?
  ((rc != 0)) || { check_failed "$name: exit 0 from $*"; return; }
  [[ $(wc -l <"$TMP/$name.err") == 1 ]] && grep -qF -- "$expected" "$TMP/$name.err" ||
    check_failed "$name: stderr is not one line with '$expected': $(cat "$TMP/$name.err")"
  [[ ! -s $TMP/$name.out ]] || check_failed "$name: printed on stdout"
}
cp -r "$TMP/grid" "$TMP/bad"
sed -i 's/^f 22 43 44 23$/f 22 44 43 23/' "$TMP/bad/grid7.obj"
line=$(grep -n '^f 22 44 43 23$' "$TMP/bad/grid7.obj" | cut -d: -f1)
[[ -n $line ]] || die "the changed face is not in grid7.obj"
fails faces "bad/grid7.obj (frame 7): face list differs from frame 0 (first at the face on line $line)" \
  "$ANIMC" encode "$TMP/bad" -o "$TMP/bad.ams"
cp "$TMP/grid/grid7.obj" "$TMP/bad/grid7.obj"
sed -i '5s/.*/v 1 2/' "$TMP/bad/grid3.obj"
fails coordinates "bad/grid3.obj: line 5: vertex 4 has fewer than 3 coordinates" \
  "$ANIMC" encode "$TMP/bad" -o "$TMP/bad.ams"
[[ ! -e $TMP/bad.ams ]] || check_failed "a failed encode left bad.ams"
mkdir "$TMP/gap" && cp "$TMP/grid/"grid*.obj "$TMP/gap/" && rm "$TMP/gap/grid3.obj"
fails pattern_gap "frame 3 is missing (the files run from 0 to 29)" \
  "$ANIMC" encode "$TMP/gap/grid%d.obj" -o "$TMP/bad.ams"
fails format "unknown sequence format 'stl' (expected one of ply, off, pc2, mdd, obj, glb, gltf)" \
  "$ANIMC" decode "$TMP/grid_auto.ams" -o "$TMP/x" --format stl

finish_checks obj_sequences_test
