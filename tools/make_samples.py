#!/usr/bin/python3
"""Rebuilds samples/ from ../shared/data: the first FRAMES frames of sydney_md2 as a PC2 point
cache (xz-compressed) beside its PLY mesh. Run from the repository root."""
import lzma, os, shutil, struct, sys

FRAMES = 50
SRC = os.path.join('..', 'shared', 'data', 'sydney_md2')
DST = os.path.join('samples', 'sydney')

def main():
    with lzma.open(os.path.join(SRC, 'sydney_md2.pc2.xz'), 'rb') as f:
        head = f.read(32)
        magic, version, points, start, rate, count = struct.unpack('<12siiffi', head)
        if magic != b'POINTCACHE2\0':
            sys.exit('not a PC2 file')
        body = f.read(FRAMES * points * 12)
    os.makedirs(DST, exist_ok=True)
    out = struct.pack('<12siiffi', magic, version, points, start, rate, FRAMES) + body
    with lzma.open(os.path.join(DST, 'sydney_50.pc2.xz'), 'wb', preset=9) as f:
        f.write(out)
    shutil.copyfile(os.path.join(SRC, 'sydney_md2.ply'), os.path.join(DST, 'sydney_md2.ply'))

if __name__ == '__main__':
    main()
