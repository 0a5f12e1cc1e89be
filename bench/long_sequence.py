#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Make a long PC2 sequence from a short one, for memory (streaming) tests.

usage: long_sequence.py SOURCE.pc2[.xz] OUT.pc2 FRAMES

The source frames are played back and forth (0, 1, ..., n-1, n-2, ..., 1, 0, 1, ...) so
that the motion stays continuous at every turn, until FRAMES frames are written. The
output is written frame block by frame block, so memory stays at the size of the source
(100 000 frames of sydney_md2, 342 vertices, is ~410 MB on disk and a few MB in memory).
PC2 layout: README of the data folder (magic, version, point count, start, rate, count,
then float32 x y z frame after frame, little-endian)."""
import sys

import numpy as np

import pc2

BLOCK_FRAMES = 1000  # frames written per write() call


def ping_pong_indices(source_frames, first, count):
    """Source frame index of output frames first .. first+count-1 (back and forth)."""
    if source_frames == 1:
        return np.zeros(count, dtype=np.int64)
    period = 2 * (source_frames - 1)
    phase = np.arange(first, first + count, dtype=np.int64) % period
    return np.where(phase < source_frames, phase, period - phase)


def write_long_sequence(source, out, frames):
    """Write `frames` frames of `source` played back and forth to the PC2 file `out`.
    Returns the number of bytes written."""
    seq, header = pc2.read_pc2(source)
    n = seq.shape[1]
    with open(out, 'wb') as f:
        f.write(pc2.pack_header(header._replace(frames=frames)))
        for first in range(0, frames, BLOCK_FRAMES):
            count = min(BLOCK_FRAMES, frames - first)
            f.write(seq[ping_pong_indices(len(seq), first, count)].tobytes())
    return 32 + frames * n * 12


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    frames = int(sys.argv[3])
    if frames < 1:
        sys.exit('FRAMES must be >= 1')
    size = write_long_sequence(sys.argv[1], sys.argv[2], frames)
    print(f'{sys.argv[2]}: {frames} frames, {size} bytes', file=sys.stderr)


if __name__ == '__main__':
    main()
