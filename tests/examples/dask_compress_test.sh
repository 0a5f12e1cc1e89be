#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# examples/dask_compress.py on a LocalCluster of two workers: two sequences of tests/data (one
# cut into several parts, one shorter than a part), each output byte for byte what `animc
# encode` writes for the whole sequence with the same settings.
# usage: dask_compress_test.sh ANIMC PYTHON DATA_DIR   (PYTHONPATH holds the animcompress module)
set -euo pipefail
ANIMC=$1 PY=$2 DATA=$3
HERE=$(cd "$(dirname "$0")" && pwd)
source "$HERE/../cli/cli_support.sh"

IN=$TMP/in OUT=$TMP/out
mkdir -p "$IN/a" "$IN/b"
for name in sydney_md2 oa_gargoyle_upper; do
  [[ -f $DATA/$name/$name.pc2.xz ]] || die "no $name in $DATA"
done
cp "$DATA/sydney_md2/sydney_md2."{pc2.xz,ply} "$IN/a/"  # 198 frames: parts of 64, 64, 64 and 6
"$PY" - "$DATA/oa_gargoyle_upper/oa_gargoyle_upper.pc2.xz" "$IN/b/short.pc2" <<'PYEOF'
import lzma, struct, sys  # the first 40 frames of gargoyle, with a header saying so
with lzma.open(sys.argv[1]) as f:
    head = bytearray(f.read(32))
    points = struct.unpack_from('<i', head, 16)[0]
    struct.pack_into('<i', head, 28, 40)
    body = f.read(points * 12 * 40)
with open(sys.argv[2], 'wb') as f:
    f.write(head + body)
PYEOF
cp "$DATA/oa_gargoyle_upper/oa_gargoyle_upper.ply" "$IN/b/short.ply"

run dask "$PY" "$HERE/../../examples/dask_compress.py" "$IN" "$OUT" --workers 2 --animc "$ANIMC" \
  --part-frames 64 --iframe-interval 32
for cache in "$IN/a/sydney_md2.pc2.xz" "$IN/b/short.pc2"; do
  name=$(basename "$cache"); name=${name%%.*}
  run "whole_$name" "$ANIMC" encode "$cache" --mesh "$(dirname "$cache")/$name.ply" -o "$TMP/$name.ams" --codec auto \
    --max-error 0.01 --iframe-interval 32
  cmp -s "$TMP/$name.ams" "$OUT/$name.ams" || check_failed "$name: the cluster's file differs from animc encode's"
done
[[ -z $(ls -A "$OUT" | grep -v '\.ams$') ]] || check_failed "left in $OUT: $(ls -A "$OUT")"
finish_checks dask_compress_test
