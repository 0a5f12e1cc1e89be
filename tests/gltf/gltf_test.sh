#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# animc decode --format glb|gltf: the files pass the Khronos glTF validator with no error and no
# warning, hold one morph target per frame and one STEP animation at the file's frame rate,
# hold the decoded frames (check_gltf_frames.py against --format pc2 of the same file), and
# three.js plays them: at each frame's time, and halfway through it, it shows that frame
# (play_three.mjs).
# usage: gltf_test.sh ANIMC_BINARY SAMPLES_DIR NODE_MODULES   (exit 77: no validator installed)
set -euo pipefail

ANIMC=${1:?usage: gltf_test.sh ANIMC_BINARY SAMPLES_DIR NODE_MODULES}
SAMPLES=${2:?usage: gltf_test.sh ANIMC_BINARY SAMPLES_DIR NODE_MODULES}
NODE_MODULES=${3:?usage: gltf_test.sh ANIMC_BINARY SAMPLES_DIR NODE_MODULES}
PY=/usr/bin/python3
HERE=$(dirname "$0")
PC2=$SAMPLES/sydney/sydney_50.pc2.xz
MESH=$SAMPLES/sydney/sydney_md2.ply
if [[ ! -d $NODE_MODULES/gltf-validator || ! -d $NODE_MODULES/three ]] || ! command -v node >/dev/null; then
  echo "gltf_test: no node, or no gltf-validator or three in $NODE_MODULES (scripts/setup_node_tools.sh installs them): not run"
  exit 77
fi

source "$HERE/../cli/cli_support.sh"

# validate NAME FILE FRAMES DURATION: no error, no warning, FRAMES targets, one STEP animation.
validate() {
  local name=$1 file=$2 frames=$3 duration=$4
  NODE_PATH=$NODE_MODULES node "$HERE/validate_gltf.mjs" "$file" >"$TMP/$name.json" 2>"$TMP/$name.err" ||
    { check_failed "$name: the validator failed: $(cat "$TMP/$name.err")"; return; }
  json_check "(d['errors'] == 0 and d['warnings'] == 0 and d['meshes'] == 1 and d['targets'] == $frames
              and d['animations'] == 1 and d['interpolation'] == 'STEP'
              and abs(d['duration'] - $duration) < 1e-6)" "$TMP/$name.json"
}

# played NAME FILE FRAMES.pc2 RATE: three.js shows every frame of FRAMES.pc2 at its time.
played() {
  local name=$1
  NODE_PATH=$NODE_MODULES node "$HERE/play_three.mjs" "$2" "$3" "$4" >"$TMP/$name.three.json" 2>"$TMP/$name.three.err" ||
    { check_failed "$name: three.js failed: $(cat "$TMP/$name.three.err")"; return; }
  json_check "(d['wrong_weights'] == 0 and d['worst_error'] <= 1e-6 * d['largest_coordinate']
              and d['frames_checked'] == 2 * d['targets'])" "$TMP/$name.three.json"
}

for codec in auto affine-octree wavelet trajectory; do
  run "encode_$codec" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/$codec.ams" --codec "$codec"
done
run pc2 "$ANIMC" decode "$TMP/auto.ams" -o "$TMP/auto.pc2"
for format in glb gltf; do
  run "decode_$format" "$ANIMC" decode "$TMP/auto.ams" -o "$TMP/auto.$format"  # the extension picks it
  validate "$format" "$TMP/auto.$format" 50 "50 / 25"
  run "frames_$format" "$PY" "$HERE/check_gltf_frames.py" "$TMP/auto.$format" "$TMP/auto.pc2" "$MESH" 25
  played "three_$format" "$TMP/auto.$format" "$TMP/auto.pc2" 25
done
for codec in affine-octree wavelet trajectory; do
  run "glb_$codec" "$ANIMC" decode "$TMP/$codec.ams" -o "$TMP/$codec.glb"
  validate "glb_$codec" "$TMP/$codec.glb" 50 "50 / 25"
done
# A range: its own frames from time 0.
run range "$ANIMC" decode "$TMP/auto.ams" -o "$TMP/part.glb" --frames 10:20
validate range "$TMP/part.glb" 10 "10 / 25"
run range_pc2 "$ANIMC" decode "$TMP/auto.ams" -o "$TMP/part.pc2" --frames 10:20
run range_frames "$PY" "$HERE/check_gltf_frames.py" "$TMP/part.glb" "$TMP/part.pc2" "$MESH" 25
played three_range "$TMP/part.glb" "$TMP/part.pc2" 25
run one "$ANIMC" decode "$TMP/auto.ams" -o "$TMP/one.glb" --frames 7
validate one "$TMP/one.glb" 1 "1 / 25"
# An MDD at 30 frames per second: the .ams keeps the rate, and the glb's times follow it.
"$PY" -c "
import struct, sys
sys.path.insert(0, '$HERE/../../bench')
import pc2
frames, _ = pc2.read_pc2('$TMP/auto.pc2')
with open('$TMP/30fps.mdd', 'wb') as f:
    f.write(struct.pack('>ii', len(frames), frames.shape[1]))
    f.write(struct.pack('>%df' % len(frames), *[k / 30 for k in range(len(frames))]))
    f.write(frames.astype('>f4').tobytes())
" || die "could not write the 30 fps MDD"
run mdd_encode "$ANIMC" encode "$TMP/30fps.mdd" --mesh "$MESH" -o "$TMP/30fps.ams"
run mdd_glb "$ANIMC" decode "$TMP/30fps.ams" -o "$TMP/30fps.glb"
validate mdd_glb "$TMP/30fps.glb" 50 "50 / 30"
run mdd_pc2 "$ANIMC" decode "$TMP/30fps.ams" -o "$TMP/30fps.pc2"
run mdd_frames "$PY" "$HERE/check_gltf_frames.py" "$TMP/30fps.glb" "$TMP/30fps.pc2" "$MESH" 30
played three_30fps "$TMP/30fps.glb" "$TMP/30fps.pc2" 30
# A failed decode leaves no glb.
"$ANIMC" decode "$TMP/auto.ams" -o "$TMP/none.glb" --max-output-bytes 1000 >/dev/null 2>&1 &&
  check_failed "--max-output-bytes 1000 let a glb through"
[[ ! -e $TMP/none.glb ]] || check_failed "a refused decode left none.glb"

finish_checks gltf_test
