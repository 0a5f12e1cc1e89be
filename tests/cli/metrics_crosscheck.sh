#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Cross-checks animc's metrics against the independent numpy implementation in
# ../shared/tools/seqmetrics.py on the sample animation, for both profiles.
# usage: metrics_crosscheck.sh ANIMC SAMPLES_DIR SEQMETRICS_PY
set -euo pipefail
animc=$1 samples=$2 seqmetrics=$3
if [ ! -f "$seqmetrics" ]; then
  # 77 = skipped for ctest (SKIP_RETURN_CODE): the script lives beside the repository only.
  echo "not run: the independent metrics script $seqmetrics is not there (it comes with ../shared/tools)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mesh="$samples/sydney/sydney_md2.ply"
xz -dc "$samples/sydney/sydney_50.pc2.xz" > "$work/orig.pc2"
for profile in paper default; do
  "$animc" encode "$work/orig.pc2" --mesh "$mesh" -o "$work/$profile.ams" --profile "$profile" --max-error 0.02 >/dev/null
  "$animc" decode "$work/$profile.ams" -o "$work/$profile.pc2" >/dev/null
  "$animc" compare "$work/orig.pc2" "$work/$profile.ams" --mesh "$mesh" --json > "$work/ours.json"
  /usr/bin/python3 "$seqmetrics" "$work/orig.pc2" "$work/$profile.pc2" "$work/$profile.ams" > "$work/ref.json"
  /usr/bin/python3 - "$work/ours.json" "$work/ref.json" "$profile" <<'PY'
import json, math, sys
ours, ref, profile = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
pairs = [('ratio', 'ratio'), ('bpvf', 'bpvf'), ('kg_error', 'kg_error'),
         ('max_error_rel_cube', 'max_err_cube'), ('psnr', 'psnr_diag2')]
bad = [f'{a}={ours[a]!r} vs {b}={ref[b]!r}' for a, b in pairs
       if not math.isclose(ours[a], ref[b], rel_tol=1e-6)]
if bad:
    sys.exit(f'{profile}: animc and seqmetrics.py disagree: ' + '; '.join(bad))
print(f'{profile}: ' + ', '.join(f'{a} {ours[a]:.6g}' for a, _ in pairs) + ' (both agree)')
PY
done
