#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# End-to-end tests of the animc command line on the Sydney sample:
#   encode / info / compare / bench (of frames, and of an .ams: decoding only) with --json, decode to every format and a frame range,
#   and the error contract: non-zero exit, nothing on stdout, one "animc: " line on stderr,
#   no output file.
#   and the release version (--version, "animc_version" in every JSON report).
# usage: cli_test.sh ANIMC_BINARY SAMPLES_DIR VERSION
set -euo pipefail

ANIMC=${1:?usage: cli_test.sh ANIMC_BINARY SAMPLES_DIR VERSION}
SAMPLES=${2:?usage: cli_test.sh ANIMC_BINARY SAMPLES_DIR VERSION}
VERSION=${3:?usage: cli_test.sh ANIMC_BINARY SAMPLES_DIR VERSION}
PY=/usr/bin/python3  # stdlib only; a pyenv python3 on PATH may lack modules
PC2=$SAMPLES/sydney/sydney_50.pc2.xz
MESH=$SAMPLES/sydney/sydney_md2.ply
[[ -x $ANIMC ]] || { echo "FAIL: $ANIMC is not executable" >&2; exit 1; }
[[ -f $PC2 && -f $MESH ]] || { echo "FAIL: samples missing in $SAMPLES" >&2; exit 1; }

source "$(dirname "$0")/cli_support.sh"

AMS=$TMP/sydney.ams

# --- encode, info, compare, bench ---------------------------------------------------------
run encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$AMS" --json
[[ -s $AMS ]] || die "encode wrote no $AMS"
json_check 'all(isinstance(d.get(k), (int, float)) for k in ("ratio", "bpvf", "kg_error", "psnr", "max_error"))' \
  "$TMP/encode.out"
json_check 'd["ratio"] > 1 and 0 < d["bpvf"] < 96 and d["kg_error"] > 0 and d["psnr"] > 0 and d["max_error"] > 0' \
  "$TMP/encode.out"
[[ ! -s $TMP/encode.err ]] || check_failed "encode printed on stderr: $(cat "$TMP/encode.err")"

run info "$ANIMC" info "$AMS" --json
json_check 'd["frames"] == 50 and d["vertices"] == 342' "$TMP/info.out"
json_check "d['animc_version'] == e['animc_version'] == '$VERSION'" "$TMP/info.out" "$TMP/encode.out"
grep -qx 'checked: header, index and the first group; `animc test` checks every frame' < <("$ANIMC" info "$AMS") ||
  check_failed "animc info does not say what it checked"
json_check 'd["checked"] == "header, index and first group"' "$TMP/info.out"
run version "$ANIMC" --version
[[ $(cat "$TMP/version.out") == "animc $VERSION (.ams formats up to 2)" ]] ||
  check_failed "animc --version printed '$(cat "$TMP/version.out")', not animc $VERSION"
json_check 'd["file_bytes"] == e["file_bytes"]' "$TMP/info.out" "$TMP/encode.out"

run compare_ams "$ANIMC" compare "$PC2" "$AMS" --mesh "$MESH" --json
same_kg "$TMP/compare_ams.out" "$TMP/encode.out"
json_check 'd["max_error_rel_cube"] <= 0.01 * 1.02 and d["frames"] == 50' "$TMP/compare_ams.out"
json_check "d['animc_version'] == '$VERSION'" "$TMP/compare_ams.out"

run bench "$ANIMC" bench "$PC2" --mesh "$MESH" --runs 1 --json
json_check 'd["encode_mvps"] > 0 and d["decode_mvps"] > 0 and d["encode_cpu_seconds_median"] > 0' "$TMP/bench.out"
json_check 'd["decode_cpu_seconds_median"] > 0 and abs(d["decode_cpu_mvps"] * d["decode_cpu_seconds_median"] - d["vertices"] * d["frames"] / 1e6) < 1e-12 * d["vertices"] * d["frames"]' "$TMP/bench.out"
same_kg "$TMP/bench.out" "$TMP/encode.out"
# Given the .ams itself, bench decodes that file only.
run bench_ams "$ANIMC" bench "$AMS" --runs 2 --json
json_check 'd["decode_mvps"] > 0 and d["runs"] == 2 and d["frames"] == 50 and "encode_mvps" not in d' "$TMP/bench_ams.out"
json_check 'd["decode_cpu_seconds_median"] > 0 and d["decode_cpu_mvps"] > 0' "$TMP/bench_ams.out"
json_check 'd["file_bytes"] == e["file_bytes"] and d["codec"] == e["codec"] == "auto" and d["rate_mode"] == "max error"' \
  "$TMP/bench_ams.out" "$TMP/encode.out"
# --backwards decodes the last frame first: every frame a random access into its group.
run bench_backwards "$ANIMC" bench "$AMS" --runs 1 --backwards --json
json_check 'd["order"] == "backwards" and d["decode_mvps"] > 0 and d["frames"] == 50' "$TMP/bench_backwards.out"
json_check 'd["order"] == "forwards"' "$TMP/bench_ams.out"
"$ANIMC" bench "$PC2" --mesh "$MESH" --runs 1 --backwards >/dev/null 2>&1 &&
  check_failed "bench --backwards of frames (not an .ams) was accepted"
# An auto file in groups of 2 frames: test says which codec coded how many groups.
run encode_mixed "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/mixed.ams" --iframe-interval 2 --json
run test_mixed "$ANIMC" test "$TMP/mixed.ams" --json
json_check 'sum(d["groups_by_codec"].values()) == d["groups"] == 25 and sorted(d["groups_by_codec"]) == ["affine-octree", "trajectory2"]' \
  "$TMP/test_mixed.out"
"$ANIMC" test "$TMP/mixed.ams" | grep -Eq "25 groups \(trajectory2 [0-9]+, affine-octree [0-9]+\)$" ||
  check_failed "animc test of an auto file does not say which codec coded its groups"
# Without --codec: auto, or affine-octree (the 1.x default) when one of its own flags is given.
run default_paper "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/paper.ams" --profile paper --json
json_check 'd["codec"] == "affine-octree" and d["profile"] == "paper"' "$TMP/default_paper.out"

# --- decode to every format; each holds the same frames as the .ams ------------------------
run decode_pc2 "$ANIMC" decode "$AMS" -o "$TMP/full.pc2"
run decode_mdd "$ANIMC" decode "$AMS" -o "$TMP/full.mdd"
run decode_ply "$ANIMC" decode "$AMS" -o "$TMP/ply_frames"
run decode_off "$ANIMC" decode "$AMS" -o "$TMP/off_frames" --format off
for dir in ply off; do
  count=$(find "$TMP/${dir}_frames" -name "*.$dir" | wc -l)
  ((count == 50)) || check_failed "decode to $dir wrote $count frame files, not 50"
done
for decoded in full.pc2 full.mdd ply_frames off_frames; do
  run "compare_$decoded" "$ANIMC" compare "$PC2" "$TMP/$decoded" --mesh "$MESH" --json
  same_kg "$TMP/compare_$decoded.out" "$TMP/compare_ams.out"
done

# --frames 10:20: the same bytes as frames 10..19 of the full decode.
run decode_range "$ANIMC" decode "$AMS" -o "$TMP/range.pc2" --frames 10:20
"$PY" - "$TMP/full.pc2" "$TMP/range.pc2" <<'EOF' || check_failed "--frames 10:20 differs from frames 10..19"
import struct, sys
def pc2(path):
    data = open(path, "rb").read()
    magic, version, points, start, rate, samples = struct.unpack("<12siiffi", data[:32])
    assert magic == b"POINTCACHE2\0" and version == 1, path
    assert len(data) == 32 + 12 * points * samples, f"{path}: {len(data)} bytes"
    return points, samples, data[32:]
points, samples, full = pc2(sys.argv[1])
rpoints, rsamples, part = pc2(sys.argv[2])
assert (points, samples) == (342, 50), (points, samples)
assert (rpoints, rsamples) == (342, 10), (rpoints, rsamples)
frame = 12 * points
assert part == full[10 * frame:20 * frame], "frame data differ"
EOF

# --- the wavelet codec: encode, info, quality vs rate, progressive decoding ------------------
W_AMS=$TMP/wavelet.ams
run w_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$W_AMS" --codec wavelet --step 3e-4 --json
json_check 'd["codec"] == "wavelet" and d["step"] == 3e-4 and d["kg_error"] < 0.2 and d["bpvf"] < 96' "$TMP/w_encode.out"
run w_info "$ANIMC" info "$W_AMS" --json
json_check 'd["codec"] == "wavelet" and d["frames"] == 50 and d["file_bytes"] == e["file_bytes"] and "profile" not in d' \
  "$TMP/w_info.out" "$TMP/w_encode.out"
grep -q "codec: wavelet" < <("$ANIMC" info "$W_AMS") || check_failed "animc info does not name the wavelet codec"
run w_compare "$ANIMC" compare "$PC2" "$W_AMS" --mesh "$MESH" --json
same_kg "$TMP/w_compare.out" "$TMP/w_encode.out"
# Fixed rate: more bits per vertex, less error.
run w_bpv2 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/w2.ams" --codec wavelet --bpv 2 --json
run w_bpv8 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/w8.ams" --codec wavelet --bpv 8 --json
json_check 'd["kg_error"] > e["kg_error"] and d["file_bytes"] < e["file_bytes"]' "$TMP/w_bpv2.out" "$TMP/w_bpv8.out"
# Target error: the sequence's KG stays at or below the target, and a looser one costs less.
run w_kg05 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/wk05.ams" --codec wavelet --target-kg 0.5 --json
run w_kg2 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/wk2.ams" --codec wavelet --target-kg 2 --json
json_check 'd["target_kg_setting"] == 0.5 and d["kg_error"] <= 0.5 and e["kg_error"] <= 2 and e["file_bytes"] < d["file_bytes"]' \
  "$TMP/w_kg05.out" "$TMP/w_kg2.out"
run w_bench "$ANIMC" bench "$PC2" --mesh "$MESH" --codec wavelet --bpv 4 --runs 1 --json
json_check 'd["codec"] == "wavelet" and d["decode_mvps"] > 0 and d["bits_per_vertex_setting"] == 4' "$TMP/w_bench.out"
# Progressive decoding of an I-frames-only file: fewer bitplanes, more error, same frame count.
run w_intra "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/wi.ams" --codec wavelet --step 1e-4 --i-frames-only --json
json_check 'd["temporal_prediction"] == False' "$TMP/w_intra.out"
run w_dec_full "$ANIMC" decode "$TMP/wi.ams" -o "$TMP/wi_full.pc2"
run w_dec_4 "$ANIMC" decode "$TMP/wi.ams" -o "$TMP/wi_4.pc2" --bitplanes 4
run w_dec_bytes "$ANIMC" decode "$TMP/wi.ams" -o "$TMP/wi_bytes.pc2" --max-bytes 100
for part in full 4 bytes; do
  run "w_cmp_$part" "$ANIMC" compare "$PC2" "$TMP/wi_$part.pc2" --mesh "$MESH" --json
done
json_check 'd["frames"] == e["frames"] == 50 and d["kg_error"] > 10 * e["kg_error"]' "$TMP/w_cmp_4.out" "$TMP/w_cmp_full.out"
json_check 'd["frames"] == 50 and d["kg_error"] > e["kg_error"]' "$TMP/w_cmp_bytes.out" "$TMP/w_cmp_full.out"
# ... and of a file with progressive P-frames: cut frames drift, but still decode.
run w_prog "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/wp.ams" --codec wavelet --step 1e-4 --progressive-p-frames --json
json_check 'd["temporal_prediction"] == True and d["progressive_p_frames"] == True' "$TMP/w_prog.out"
# A codec's option on the command line, in the file and in the reports, from its entry alone.
run w_local "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/wl.ams" --codec wavelet --local-frames --json
run w_local_info "$ANIMC" info "$TMP/wl.ams" --json
json_check 'd["local_frames"] == True and e["local_frames"] == False' "$TMP/w_local_info.out" "$TMP/w_prog.out"
run w_prog_info "$ANIMC" info "$TMP/wp.ams"
grep -q "progressive P-frames" "$TMP/w_prog_info.out" || check_failed "animc info does not say the P-frames are progressive"
run w_prog_dec "$ANIMC" decode "$TMP/wp.ams" -o "$TMP/wp_4.pc2" --bitplanes 4
run w_prog_cmp "$ANIMC" compare "$PC2" "$TMP/wp_4.pc2" --mesh "$MESH" --json
json_check 'd["frames"] == 50 and d["kg_error"] > e["kg_error"]' "$TMP/w_prog_cmp.out" "$TMP/w_prog.out"

# --- errors: exit != 0, nothing on stdout, one "animc: " line on stderr, no output ---------
ERRDIR=$TMP/errors
mkdir "$ERRDIR"
BAD_AMS=$TMP/corrupt.ams
cp "$AMS" "$BAD_AMS"
"$PY" - "$BAD_AMS" <<'EOF'
import sys
path = sys.argv[1]
data = bytearray(open(path, "rb").read())
data[len(data) // 2] ^= 0x5A
open(path, "wb").write(data)
EOF

# A damaged last frame group: decoding fails after most frames were written, and the
# partial output must be removed.
run encode_groups "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/groups.ams" --iframe-interval 10
LATE_AMS=$TMP/late_corrupt.ams
"$PY" - "$TMP/groups.ams" "$LATE_AMS" <<'EOF'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
index_offset, = struct.unpack("<Q", data[-12:-4])  # END: tag, length, Index_Offset, CRC
data[index_offset - 40] ^= 0x5A  # in the last GRUP's frames, before its CRC
open(sys.argv[2], "wb").write(data)
EOF

# expect_error NAME OUTPUT CMD...: runs CMD in $ERRDIR (which must stay empty).
expect_error() {
  local name=$1 output=$2 rc=0
  shift 2
  (cd "$ERRDIR" && "$@") >"$TMP/$name.out" 2>"$TMP/$name.err" || rc=$?
  local lines
  lines=$(wc -l <"$TMP/$name.err")
  if ((rc == 0)); then check_failed "$name: exit 0 from: $*"; fi
  if [[ -s $TMP/$name.out ]]; then check_failed "$name: printed on stdout: $(cat "$TMP/$name.out")"; fi
  if ((lines != 1)) || ! head -n 1 "$TMP/$name.err" | grep -q '^animc: '; then
    check_failed "$name: stderr should be one line starting with 'animc: ', got $lines lines:"$'\n'"$(cat "$TMP/$name.err")"
  fi
  if [[ -n $output && -e $output ]]; then check_failed "$name: created $output"; fi
  if [[ -n $(ls -A "$ERRDIR") ]]; then check_failed "$name: left files: $(ls -A "$ERRDIR")"; fi
  rm -rf "${ERRDIR:?}"/* "${ERRDIR:?}"/.[!.]* 2>/dev/null || true
  [[ -z $output ]] || rm -rf "$output"
}

expect_error unknown_command "" "$ANIMC" frobnicate "$AMS"
expect_error unknown_option "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --frobnicate
expect_error missing_output "" "$ANIMC" encode "$PC2" --mesh "$MESH"
expect_error missing_input "$ERRDIR/x.ams" "$ANIMC" encode "$TMP/no_such.pc2" --mesh "$MESH" -o "$ERRDIR/x.ams"
expect_error missing_ams "$ERRDIR/x.pc2" "$ANIMC" decode "$TMP/no_such.ams" -o "$ERRDIR/x.pc2"
expect_error corrupt_ams "$ERRDIR/x.pc2" "$ANIMC" decode "$BAD_AMS" -o "$ERRDIR/x.pc2"
expect_error corrupt_ams_ply "$ERRDIR/frames" "$ANIMC" decode "$BAD_AMS" -o "$ERRDIR/frames"
expect_error late_corrupt_pc2 "$ERRDIR/x.pc2" "$ANIMC" decode "$LATE_AMS" -o "$ERRDIR/x.pc2"
expect_error late_corrupt_off "$ERRDIR/frames" "$ANIMC" decode "$LATE_AMS" -o "$ERRDIR/frames" --format off
expect_error late_corrupt_compare "" "$ANIMC" compare "$PC2" "$LATE_AMS" --mesh "$MESH"
expect_error corrupt_compare "" "$ANIMC" compare "$PC2" "$BAD_AMS" --mesh "$MESH" --json
expect_error max_error_zero "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --max-error 0
expect_error bad_range "$ERRDIR/x.pc2" "$ANIMC" decode "$AMS" -o "$ERRDIR/x.pc2" --frames 20:10
expect_error range_past_end "$ERRDIR/x.pc2" "$ANIMC" decode "$AMS" -o "$ERRDIR/x.pc2" --frames 40:51
expect_error unknown_codec "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec mpeg
expect_error wavelet_profile "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec wavelet --profile paper
expect_error octree_step "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --step 1e-3
expect_error wavelet_step_zero "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec wavelet --step 0
expect_error wavelet_target_too_large "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec wavelet --target-kg 200
expect_error wavelet_bpv_negative "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec wavelet --bpv -1
expect_error progressive_octree "$ERRDIR/x.pc2" "$ANIMC" decode "$AMS" -o "$ERRDIR/x.pc2" --bitplanes 3
expect_error progressive_p_frames "$ERRDIR/x.pc2" "$ANIMC" decode "$W_AMS" -o "$ERRDIR/x.pc2" --bitplanes 4
expect_error progressive_i_frames_only "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" \
  --codec wavelet --i-frames-only --progressive-p-frames
expect_error bench_ams_encode_option "" "$ANIMC" bench "$AMS" --max-error 0.1
expect_error bench_ams_missing "" "$ANIMC" bench "$TMP/no_such.ams"
expect_error negative_bitplanes "$ERRDIR/x.pc2" "$ANIMC" decode "$W_AMS" -o "$ERRDIR/x.pc2" --bitplanes -2
# A missing output folder, named under the output the user gave (not a temporary name).
expect_error missing_out_dir "" "$ANIMC" encode "$PC2" --mesh "$MESH" -o out/x.ams
[[ $(cat "$TMP/missing_out_dir.err") == "animc: out/x.ams: no such directory out" ]] ||
  check_failed "encode -o out/x.ams said: $(cat "$TMP/missing_out_dir.err")"
expect_error missing_out_dir_frames "" "$ANIMC" decode "$AMS" -o out/frames
[[ $(cat "$TMP/missing_out_dir_frames.err") == "animc: out/frames: no such directory out" ]] ||
  check_failed "decode -o out/frames said: $(cat "$TMP/missing_out_dir_frames.err")"
# A folder given as the .ams: named once, with the reason.
expect_error info_directory "" "$ANIMC" info "$TMP"
[[ $(cat "$TMP/info_directory.err") == "animc: $TMP: is a directory, not an .ams file" ]] ||
  check_failed "animc info DIR said: $(cat "$TMP/info_directory.err")"

# --- animc test: every golden file passes; a cut file, a flipped bit, a damaged last group fail
GOLDEN=$(dirname "$SAMPLES")/tests/golden
golden_count=0
for golden in "$GOLDEN"/*.ams; do
  run test_golden "$ANIMC" test "$golden"
  grep -qxE "$(printf '%s' "$golden" | sed 's/[.[\*^$]/\\&/g'): OK, [0-9]+ frames of [0-9]+ vertices, [0-9]+ groups( \([a-z0-9-]+ [0-9]+(, [a-z0-9-]+ [0-9]+)*\))?" \
    "$TMP/test_golden.out" || check_failed "animc test $golden printed: $(cat "$TMP/test_golden.out")"
  golden_count=$((golden_count + 1))
done
((golden_count >= 13)) || check_failed "only $golden_count golden files in $GOLDEN"
run test_json "$ANIMC" test "$AMS" --json
json_check "d['animc_version'] == '$VERSION' and d['ok'] is True and d['checked'] == 'every frame'" "$TMP/test_json.out"
json_check 'd["frames"] == e["frames"] == 50 and d["vertices"] == e["vertices"] and d["file_bytes"] == e["file_bytes"]' \
  "$TMP/test_json.out" "$TMP/info.out"
head -c 1000 "$AMS" >"$TMP/cut.ams"
expect_error test_cut "" "$ANIMC" test "$TMP/cut.ams"
grep -q "truncated" "$TMP/test_cut.err" || check_failed "animc test on a cut file: $(cat "$TMP/test_cut.err")"
rc=0
"$ANIMC" test "$TMP/cut.ams" >/dev/null 2>&1 || rc=$?
((rc == 5)) || check_failed "animc test on a cut file exits $rc, not 5 (Truncated)"
expect_error test_corrupt "" "$ANIMC" test "$BAD_AMS"
# The last group's damage is past what info reads: info accepts the file, test does not.
run info_late "$ANIMC" info "$LATE_AMS"
expect_error test_late "" "$ANIMC" test "$LATE_AMS" --json
grep -q "CRC mismatch" "$TMP/test_late.err" || check_failed "animc test on a damaged last group: $(cat "$TMP/test_late.err")"
expect_error test_usage "" "$ANIMC" test

# --- limits on what a small file may cost, refused before any work: vertex-frames decoded
# (from the start of the group that holds the first frame asked for) and output bytes ---------
expect_error work_limit "$ERRDIR/x.pc2" "$ANIMC" decode "$AMS" -o "$ERRDIR/x.pc2" --max-vertex-frames 10000
grep -q "above the limit of 10000.*--max-vertex-frames" "$TMP/work_limit.err" || check_failed "work_limit: $(cat "$TMP/work_limit.err")"
# 50 frames in one group: frames 45..49 cost all 50 frames; with a group every 10 frames, 10.
expect_error work_limit_range "$ERRDIR/x.pc2" "$ANIMC" decode "$AMS" -o "$ERRDIR/x.pc2" --frames 45:50 --max-vertex-frames 10000
run work_limit_groups "$ANIMC" decode "$TMP/groups.ams" -o "$TMP/last5.pc2" --frames 45:50 --max-vertex-frames 10000
expect_error output_limit "$ERRDIR/frames" "$ANIMC" decode "$AMS" -o "$ERRDIR/frames" --max-output-bytes 100000
grep -q "would take about .*--max-output-bytes" "$TMP/output_limit.err" || check_failed "output_limit: $(cat "$TMP/output_limit.err")"
run output_unlimited "$ANIMC" decode "$AMS" -o "$TMP/unlimited.pc2" --max-output-bytes 0
expect_error test_work_limit "" "$ANIMC" test "$AMS" --max-vertex-frames 100
# A trajectory group's reconstruction counted in multiply-adds (3 x components x vertices x frames).
run traj_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/traj.ams" --codec trajectory
expect_error multiply_add_limit "$ERRDIR/x.pc2" "$ANIMC" decode "$TMP/traj.ams" -o "$ERRDIR/x.pc2" --max-multiply-adds 1000
grep -q "multiply-adds, above the limit of 1000.*--max-multiply-adds" "$TMP/multiply_add_limit.err" ||
  check_failed "multiply_add_limit: $(cat "$TMP/multiply_add_limit.err")"
expect_error test_multiply_add_limit "" "$ANIMC" test "$TMP/traj.ams" --max-multiply-adds 1000
# Codec 5, trajectory2: its parts option, in the JSON settings and in info; another codec's
# flag and a bad count refused; its groups bounded by the same limit.
run traj2_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/traj2.ams" --codec trajectory2 --parts 4 --target-kg 0.5 --json
json_check 'd["codec"] == "trajectory2" and d["parts"] == 4 and d["kg_error"] <= 0.5' "$TMP/traj2_encode.out"
"$ANIMC" info "$TMP/traj2.ams" | grep -q "codec: trajectory2, target KG 0.5 %, groups of up to 512 frames in up to 4 parts" ||
  check_failed "animc info does not describe the trajectory2 file: $("$ANIMC" info "$TMP/traj2.ams")"
expect_error traj2_foreign_flag "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec trajectory --parts 4
expect_error traj2_bad_parts "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --codec trajectory2 --parts 65
expect_error traj2_multiply_add_limit "$ERRDIR/x.pc2" "$ANIMC" decode "$TMP/traj2.ams" -o "$ERRDIR/x.pc2" --max-multiply-adds 1000

# --- --threads: the same bytes and frames for any number; a bad number is refused -----------
for threads in 1 3; do
  run "threads_encode_$threads" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/threads$threads.ams" \
    --iframe-interval 10 --threads "$threads"
  run "threads_decode_$threads" "$ANIMC" decode "$TMP/threads$threads.ams" -o "$TMP/threads$threads.pc2" \
    --threads "$threads"
  run "threads_test_$threads" "$ANIMC" test "$TMP/threads$threads.ams" --threads "$threads"
done
cmp -s "$TMP/threads1.ams" "$TMP/threads3.ams" || check_failed "threads: 1 and 3 threads wrote different bytes"
cmp -s "$TMP/threads1.pc2" "$TMP/threads3.pc2" || check_failed "threads: 1 and 3 threads decoded different frames"
expect_error bad_threads "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --threads -1

# --- encode --frames and join: parts of whole I-frame intervals join into the whole encode ---
run join_whole "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/join_whole.ams" --iframe-interval 10
run join_part0 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/join0.ams" --iframe-interval 10 --frames 0:20
run join_part1 "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$TMP/join1.ams" --iframe-interval 10 --frames 20:
run join "$ANIMC" join "$TMP/join0.ams" "$TMP/join1.ams" -o "$TMP/joined.ams" --json
cmp -s "$TMP/join_whole.ams" "$TMP/joined.ams" || check_failed "join: the joined parts differ from the whole encode"
json_check 'd["frames"] == 50 and d["parts"] == 2' "$TMP/join.out"
expect_error join_mismatch "$ERRDIR/x.ams" "$ANIMC" join "$TMP/join0.ams" "$AMS" -o "$ERRDIR/x.ams"
expect_error join_over_input "" "$ANIMC" join "$TMP/join0.ams" "$TMP/join1.ams" -o "$TMP/join1.ams"
expect_error bad_frames "$ERRDIR/x.ams" "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$ERRDIR/x.ams" --frames 40:60

# --- an output that is one of the inputs is refused, by identity; the inputs stay intact ---
VICTIM=$TMP/victim
mkdir "$VICTIM"
xz -dc "$PC2" >"$VICTIM/in.pc2"
cp "$MESH" "$VICTIM/m.ply"
cp "$AMS" "$VICTIM/x.ams"
ln "$VICTIM/in.pc2" "$VICTIM/hardlink.pc2"
ln -s in.pc2 "$VICTIM/symlink.pc2"
run victim_frames "$ANIMC" decode "$AMS" -o "$VICTIM/frames" --frames 0:5
printf 'frames/frame_00000.ply\nframes/frame_00001.ply\n' >"$VICTIM/list.txt"
cp -a "$VICTIM" "$TMP/victim_before"
# expect_refused NAME CMD...: run in $VICTIM, CMD must fail with one line saying it would
# destroy an input, and leave every file of $VICTIM as it was.
expect_refused() {
  local name=$1 rc=0
  shift
  (cd "$VICTIM" && "$@") >"$TMP/$name.out" 2>"$TMP/$name.err" || rc=$?
  ((rc != 0)) || check_failed "$name: exit 0 from: $*"
  grep -q '^animc: .*would destroy that input' "$TMP/$name.err" ||
    check_failed "$name: no 'would destroy that input' line: $(cat "$TMP/$name.err")"
  diff -r --no-dereference "$TMP/victim_before" "$VICTIM" >/dev/null ||
    check_failed "$name: changed the inputs: $(diff -rq --no-dereference "$TMP/victim_before" "$VICTIM")"
}
expect_refused over_pc2 "$ANIMC" encode in.pc2 --mesh m.ply -o in.pc2
expect_refused over_mesh "$ANIMC" encode in.pc2 --mesh m.ply -o m.ply
expect_refused over_other_spelling "$ANIMC" encode ./in.pc2 --mesh m.ply -o "$VICTIM/../victim/in.pc2"
expect_refused over_hard_link "$ANIMC" encode in.pc2 --mesh m.ply -o hardlink.pc2
expect_refused over_symlink "$ANIMC" encode in.pc2 --mesh m.ply -o symlink.pc2
expect_refused over_frame "$ANIMC" encode frames -o frames/frame_00003.ply
expect_refused over_listed_frame "$ANIMC" encode list.txt -o frames/frame_00001.ply
expect_refused over_list "$ANIMC" encode list.txt -o list.txt
expect_refused decode_over_ams "$ANIMC" decode x.ams -o x.ams --format pc2
expect_refused bench_over_pc2 "$ANIMC" bench in.pc2 --mesh m.ply -o in.pc2 --runs 1

# --- decoding to a folder of frames: only a new or empty folder, or --replace; a decode that
# fails late leaves the old frames exactly as they were --------------------------------------
cp -a "$TMP/off_frames" "$TMP/off_before"
rc=0
"$ANIMC" decode "$AMS" -o "$TMP/off_frames" --frames 0:3 >"$TMP/no_replace.out" 2>"$TMP/no_replace.err" || rc=$?
((rc != 0)) && grep -q "^animc: .*not empty.*--replace" "$TMP/no_replace.err" ||
  check_failed "decode into a folder of frames without --replace: exit $rc, $(cat "$TMP/no_replace.err")"
rc=0
"$ANIMC" decode "$LATE_AMS" -o "$TMP/off_frames" --replace >/dev/null 2>"$TMP/late_replace.err" || rc=$?
((rc != 0)) || check_failed "late_replace: exit 0"
diff -r "$TMP/off_before" "$TMP/off_frames" >/dev/null ||
  check_failed "a decode that failed late changed the folder: $(diff -rq "$TMP/off_before" "$TMP/off_frames")"
[[ -z $(leftovers "$TMP") ]] || check_failed "a temporary folder was left: $(leftovers "$TMP")"
run replace "$ANIMC" decode "$AMS" -o "$TMP/off_frames" --frames 0:3 --replace
[[ $(ls "$TMP/off_frames") == $'frame_00000.ply\nframe_00001.ply\nframe_00002.ply' ]] ||
  check_failed "--replace left: $(ls "$TMP/off_frames" | head -5) ..."

# --- output paths --------------------------------------------------------------------------
OUTS=$TMP/outputs
mkdir "$OUTS"
# The longest valid names (255 bytes): the temporary's name must not grow with the output's.
LONG=$(printf 'n%.0s' {1..251})
run long_name "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$OUTS/$LONG.ams"
cmp -s "$OUTS/$LONG.ams" "$AMS" || check_failed "encode to a 255-byte name wrote other bytes"
run long_pc2 "$ANIMC" decode "$AMS" -o "$OUTS/$LONG.pc2"
cmp -s "$OUTS/$LONG.pc2" "$TMP/full.pc2" || check_failed "decode to a 255-byte .pc2 name wrote other bytes"
run long_folder "$ANIMC" decode "$AMS" -o "$OUTS/${LONG}dirs" --frames 0:2
[[ -f $OUTS/${LONG}dirs/frame_00001.ply ]] || check_failed "decode to a 255-byte folder name wrote no frames"
# A symbolic link as output stays a link: the file (or folder) it leads to gets the output.
echo "old" >"$OUTS/real.ams"
ln -s real.ams "$OUTS/link.ams"
run link_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$OUTS/link.ams"
[[ -L $OUTS/link.ams ]] || check_failed "encode -o LINK replaced the link"
cmp -s "$OUTS/real.ams" "$AMS" || check_failed "encode -o LINK did not write the link's target"
mkdir "$OUTS/real_frames"
ln -s real_frames "$OUTS/link_frames"
run link_decode "$ANIMC" decode "$AMS" -o "$OUTS/link_frames" --frames 0:2
[[ -L $OUTS/link_frames && -f $OUTS/real_frames/frame_00001.ply ]] ||
  check_failed "decode -o LINK_TO_FOLDER replaced the link or missed its folder"
# A device or a FIFO is written in place, never renamed over (as root, -o /dev/null replaced
# /dev/null with a regular file): as root the test uses a private null device, never the system's.
if ((EUID == 0)); then
  NULL_DEV=$OUTS/null
  mknod "$NULL_DEV" c 1 3
else
  NULL_DEV=/dev/null
fi
run null_encode "$ANIMC" encode "$PC2" --mesh "$MESH" -o "$NULL_DEV" --json
[[ -c $NULL_DEV ]] || check_failed "encode -o $NULL_DEV replaced the device"
json_check 'd["file_bytes"] == e["file_bytes"]' "$TMP/null_encode.out" "$TMP/encode.out"
run null_decode "$ANIMC" decode "$AMS" -o "$NULL_DEV" --format pc2
[[ -c $NULL_DEV ]] || check_failed "decode -o $NULL_DEV replaced the device"
[[ $NULL_DEV == /dev/null ]] || rm "$NULL_DEV"
# The .ams writer patches group headers: through a FIFO the reader still gets the file's bytes.
mkfifo "$OUTS/fifo"
timeout 60 cat "$OUTS/fifo" >"$TMP/from_fifo.ams" &
reader=$!
rc=0
"$ANIMC" encode "$PC2" --mesh "$MESH" -o "$OUTS/fifo" >/dev/null 2>"$TMP/fifo.err" || rc=$?
if [[ -p $OUTS/fifo ]]; then
  wait "$reader" || check_failed "reading the FIFO failed"
else
  kill "$reader"
  wait "$reader" 2>/dev/null || true
  check_failed "encode -o FIFO replaced the FIFO"
fi
((rc == 0)) || check_failed "encode -o FIFO: exit $rc: $(cat "$TMP/fifo.err")"
cmp -s "$TMP/from_fifo.ams" "$AMS" || check_failed "the .ams read from the FIFO differs from the file"
rm -f "$OUTS/fifo"
[[ -z $(leftovers "$OUTS") ]] || check_failed "temporaries left in $OUTS: $(leftovers "$OUTS")"

# --- an interrupted run leaves no temporaries and dies of the signal -------------------------
INT=$TMP/interrupted
mkdir "$INT"
ln -s "$SAMPLES/sydney/frames" "$INT/f"
for ((i = 0; i < 2000; ++i)); do printf 'f/frame_%05d.ply\n' {0..23}; done >"$INT/long.txt"  # 48000 frames
head -n 9600 "$INT/long.txt" >"$INT/medium.txt"
head -n 2400 "$INT/long.txt" >"$INT/short.txt"
# wait_for GLOB: polls until a path matches GLOB (at most 60 s, for sanitizer builds).
wait_for() {
  local tries
  for ((tries = 0; tries < 3000; ++tries)); do
    compgen -G "$1" >/dev/null && return 0
    sleep 0.02
  done
  return 1
}
# wait_writing PID DIR: polls until PID writes a file in DIR: an unnamed one (O_TMPFILE; /proc
# shows it as DIR/#<inode> (deleted)) or a named temporary where the file system has none.
wait_writing() {
  local pid=$1 dir tries fd
  dir=$(realpath "$2")
  for ((tries = 0; tries < 3000; ++tries)); do
    compgen -G "$dir/.animc-$pid-*.tmp" >/dev/null && return 0
    for fd in /proc/"$pid"/fd/*; do
      [[ $(readlink "$fd" 2>/dev/null) == "$dir/#"* ]] && return 0
    done
    sleep 0.02
  done
  return 1
}
# has_unnamed_files DIR: whether the file system under DIR makes O_TMPFILE files.
has_unnamed_files() {
  /usr/bin/python3 -c 'import os, sys; os.close(os.open(sys.argv[1], os.O_TMPFILE | os.O_RDWR, 0o600))' "$1" 2>/dev/null
}
# killed_by NAME PID SIGNAL: sends SIGNAL to the background job PID, which must die of it.
killed_by() {
  local name=$1 pid=$2 signal=$3 rc=0
  kill -s "$signal" "$pid"
  { wait "$pid"; } 2>/dev/null || rc=$?  # (no "Hangup" job notice on stderr)
  ((rc == 128 + $(kill -l "$signal"))) ||
    check_failed "$name: exit $rc, not killed by SIG$signal: $(cat "$TMP/$name.err")"
}
# SIGTERM while the .ams is being written.
"$ANIMC" encode "$INT/long.txt" -o "$INT/long.ams" >"$TMP/int_encode.out" 2>"$TMP/int_encode.err" &
pid=$!
wait_writing "$pid" "$INT" || check_failed "int_encode: it never wrote"
killed_by int_encode "$pid" TERM
[[ -z $(leftovers "$INT") && ! -e $INT/long.ams ]] || check_failed "int_encode: SIGTERM left $(ls -A "$INT")"
# SIGKILL, which no handler sees: the unnamed temporary goes with the process.
"$ANIMC" encode "$INT/long.txt" -o "$INT/long.ams" >"$TMP/int_kill.out" 2>"$TMP/int_kill.err" &
pid=$!
wait_writing "$pid" "$INT" || check_failed "int_kill: it never wrote"
killed_by int_kill "$pid" KILL
if has_unnamed_files "$INT"; then
  [[ -z $(leftovers "$INT") && ! -e $INT/long.ams ]] || check_failed "int_kill: SIGKILL left $(ls -A "$INT")"
else
  echo "int_kill: not checked, the file system under $INT has no O_TMPFILE"
fi
# SIGHUP while frames are written into the temporary folder.
run int_medium "$ANIMC" encode "$INT/medium.txt" -o "$INT/medium.ams"
"$ANIMC" decode "$INT/medium.ams" -o "$INT/frames" >"$TMP/int_decode.out" 2>"$TMP/int_decode.err" &
pid=$!
wait_for "$INT/.animc-$pid-*.tmp/frame_00010.ply" || check_failed "int_decode: no temporary folder appeared"
killed_by int_decode "$pid" HUP
[[ -z $(leftovers "$INT") && ! -e $INT/frames ]] || check_failed "int_decode: SIGHUP left $(ls -A "$INT")"
# SIGTERM in bench's second run: its scratch .ams goes too.
"$ANIMC" bench "$INT/short.txt" --runs 5 >"$TMP/int_bench.out" 2>"$TMP/int_bench.err" &
pid=$!
wait_for "/tmp/animc-bench-$pid.ams" && wait_writing "$pid" /tmp ||
  check_failed "int_bench: no scratch output and temporary appeared"
killed_by int_bench "$pid" TERM
! compgen -G "/tmp/.animc-$pid-*.tmp" >/dev/null && [[ ! -e /tmp/animc-bench-$pid.ams ]] ||
  check_failed "int_bench: SIGTERM left $(ls /tmp/animc-bench-$pid.ams /tmp/.animc-$pid-*.tmp 2>&1)"

finish_checks cli_test
