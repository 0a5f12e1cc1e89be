#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Compress every sequence of a folder on a Dask cluster: each sequence cut into parts of whole
frame groups, each part encoded by `animc encode --frames A:B` as a task of its own on any
worker, the parts joined into one .ams (animcompress.join) whose bytes are those `animc encode`
writes for the whole sequence with the same settings.

usage: dask_compress.py IN_DIR OUT_DIR [--scheduler ADDRESS | --workers W] [--animc PATH]
                        [--part-frames N] [--iframe-interval K] [--codec C] [--max-error E]

IN_DIR holds point caches NAME.pc2 or NAME.pc2.xz (in any subfolder), each with its
connectivity NAME.ply beside it; OUT_DIR receives NAME.ams for each. Without --scheduler a
LocalCluster of W single-threaded workers (default: one per core) runs here; with it, the tasks go to that
scheduler (any Dask deployment: `dask scheduler` and `dask worker ADDRESS` on each machine, or a
Kubernetes, SLURM or cloud cluster), whose workers must see IN_DIR and OUT_DIR at the same paths
and run animc (--animc) and the animcompress module. Parts are --part-frames long, a multiple of
--iframe-interval, so that the joined bytes equal the whole sequence's encode."""
import argparse
import lzma
import os
import shutil
import struct
import subprocess
import sys
import tempfile

PC2_HEADER = struct.Struct('<12siiffi')  # magic, version, points, start, rate, frames


def pc2_frame_count(path):
    """The frame count in a PC2 file's header (read through lzma for .pc2.xz)."""
    with (lzma.open if path.endswith('.xz') else open)(path, 'rb') as f:
        head = f.read(PC2_HEADER.size)
    if len(head) < PC2_HEADER.size or head[:12] != b'POINTCACHE2\0':
        raise ValueError(f'{path}: not a PC2 file')
    return PC2_HEADER.unpack(head)[5]


def find_sequences(in_dir):
    """[(name, point cache, mesh)] of IN_DIR, sorted by name."""
    found = []
    for folder, _dirs, files in os.walk(in_dir):
        for file in files:
            for ext in ('.pc2.xz', '.pc2'):
                name = file[:-len(ext)]
                if file.endswith(ext) and f'{name}.ply' in files:
                    found.append((name, os.path.join(folder, file), os.path.join(folder, f'{name}.ply')))
                    break
    return sorted(found)


def encode_part(animc, cache, mesh, first, last, settings, out):
    """A task: frames [first, last) of a sequence into `out` on one thread (the cluster gives
    each task its core); returns out."""
    subprocess.run([animc, 'encode', cache, '--mesh', mesh, '-o', out, '--frames', f'{first}:{last}',
                    '--threads', '1'] + settings, check=True, capture_output=True)
    return out


def join_parts(out, *parts):
    """A task: the parts, in order, joined into `out` (written whole or not at all)."""
    import animcompress
    data = animcompress.join(list(parts))
    partial = out + '.partial'
    with open(partial, 'wb') as f:
        f.write(data)
    os.replace(partial, out)
    return out


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('in_dir')
    p.add_argument('out_dir')
    p.add_argument('--scheduler', help='address of a Dask scheduler (default: a LocalCluster here)')
    p.add_argument('--workers', type=int, default=os.cpu_count(), help='workers of the LocalCluster')
    p.add_argument('--animc', default=shutil.which('animc') or os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'build', 'animc', 'animc'))
    p.add_argument('--part-frames', type=int, default=512)
    p.add_argument('--iframe-interval', type=int, default=128)
    p.add_argument('--codec', default='auto')
    p.add_argument('--max-error', default='0.01')
    args = p.parse_args()
    if args.iframe_interval < 1 or args.part_frames < 1 or args.part_frames % args.iframe_interval:
        p.error('--part-frames must be a positive multiple of --iframe-interval')
    return args


def main():
    args = parse_args()
    from dask.distributed import Client, LocalCluster
    settings = ['--codec', args.codec, '--max-error', args.max_error, '--iframe-interval', str(args.iframe_interval)]
    sequences = find_sequences(args.in_dir)
    if not sequences:
        sys.exit(f'{args.in_dir}: no NAME.pc2[.xz] with NAME.ply beside it')
    os.makedirs(args.out_dir, exist_ok=True)
    cluster = None if args.scheduler else LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                                       processes=True, dashboard_address=None)
    with Client(args.scheduler or cluster) as client, \
            tempfile.TemporaryDirectory(prefix='.parts-', dir=args.out_dir) as parts_dir:
        joined = []
        for name, cache, mesh in sequences:
            frames = pc2_frame_count(cache)
            parts = [client.submit(encode_part, args.animc, cache, mesh, first, min(first + args.part_frames, frames),
                                   settings, os.path.join(parts_dir, f'{name}.{first}.ams'), pure=False)
                     for first in range(0, frames, args.part_frames)]
            joined.append(client.submit(join_parts, os.path.join(args.out_dir, f'{name}.ams'), *parts, pure=False))
        for future, (name, _cache, _mesh) in zip(joined, sequences):
            print(f'{future.result()}: {name}', flush=True)
    if cluster:
        cluster.close()


if __name__ == '__main__':
    main()
