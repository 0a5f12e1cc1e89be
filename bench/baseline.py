#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The simple baseline every codec here must beat (DESIGN.md, "Measured on chickenCrossing"):
quantise every coordinate to B bits on the sequence's bounding box, subtract the previous
frame, store the differences as int32 little-endian and compress with xz -9.

usage: baseline.py SEQUENCE.pc2[.xz] BITS [BITS ...]   -> one JSON line per B
(bpvf of the whole compressed stream, KG error of the dequantised sequence)."""
import json, lzma, sys
import numpy as np

import pc2

def read_pc2(path):
    try:
        return pc2.read_pc2(path)[0].astype(np.float64)
    except ValueError as e:
        sys.exit(str(e))

def kg_error(orig, dec):
    centred = orig - orig.mean(axis=1, keepdims=True)
    return 100.0 * np.linalg.norm(dec - orig) / np.linalg.norm(centred)

def baseline(seq, bits):
    lo = seq.reshape(-1, 3).min(axis=0)
    hi = seq.reshape(-1, 3).max(axis=0)
    scale = (2 ** bits - 1) / np.maximum(hi - lo, 1e-30)
    q = np.rint((seq - lo) * scale).astype(np.int64)
    delta = np.diff(q, axis=0, prepend=np.zeros_like(q[:1]))
    packed = lzma.compress(delta.astype('<i4').tobytes(), preset=9 | lzma.PRESET_EXTREME)
    header_bytes = 2 * 3 * 8  # the box, needed to dequantise
    frames, n, _ = seq.shape
    dec = q / scale + lo
    return {'bits': bits, 'bytes': len(packed) + header_bytes,
            'bpvf': 8.0 * (len(packed) + header_bytes) / (n * frames),
            'kg_error': float(kg_error(seq, dec))}

def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    seq = read_pc2(sys.argv[1])
    for b in sys.argv[2:]:
        print(json.dumps(baseline(seq, int(b))))

if __name__ == '__main__':
    main()
