#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The golden files of tests/golden, checked through the animc command line.

usage: check_goldens.py ANIMC            check every line of manifest.txt
       check_goldens.py ANIMC --self-test also show that a changed expectation fails
       check_goldens.py ANIMC --add      make the files and CRCs the manifest lacks

manifest.txt has three kinds of lines:
  encode FILE ARGS...       FILE was written by `animc encode INPUT --mesh MESH -o FILE
                            ARGS...`; the check encodes again and compares the bytes exactly
                            (the encoder golden)
  input INPUT MESH          the INPUT and MESH of the encode lines after it (before the first
                            such line: input/sydney_30.pc2.xz and input/sydney_md2.ply)
  decode FILE CRC [ARGS...] `animc decode FILE -o OUT.pc2 ARGS...` gives frames whose f32 values,
                            in order, have this CRC-32 (the decoder golden)
An `encode` line marked `encode-frozen` is a file of an earlier codec version that today's
encoder no longer writes: only its decodes are checked. Files and CRCs are only ever added:
--add refuses to replace anything (docs/format.md, "Reference files").
"""
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = ["input/sydney_30.pc2.xz", "--mesh", "input/sydney_md2.ply"]
PC2_HEADER_BYTES = 32


def read_manifest(path):
    """(line number, words, input of an encode line) of every encode and decode line."""
    lines, source = [], INPUT
    with open(path) as f:
        for number, text in enumerate(f, 1):
            words = shlex.split(text, comments=True)
            if not words:
                continue
            if words[0] not in ("encode", "encode-frozen", "decode", "input") or len(words) < 3:
                sys.exit(f"{path}:{number}: cannot read: {text.strip()}")
            if words[0] == "input":
                source = [words[1], "--mesh", words[2]]
                continue
            lines.append((number, words, source))
    return lines


def run(animc, args, cwd):
    done = subprocess.run([animc] + args, cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"animc {' '.join(args)}: exit {done.returncode}: {done.stderr.strip()}")


def encode(animc, golden_dir, source, args, out):
    run(animc, ["encode"] + source + ["-o", out] + args, golden_dir)
    with open(out, "rb") as f:
        return f.read()


def first_difference(a, b):
    return next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))


def decoded_crc(animc, golden_dir, name, args, scratch):
    out = os.path.join(scratch, "decoded.pc2")
    run(animc, ["decode", name, "-o", out] + args, golden_dir)
    with open(out, "rb") as f:
        return "%08x" % zlib.crc32(f.read()[PC2_HEADER_BYTES:])


def check(animc, golden_dir, manifest):
    """Returns (passed, failures), failures being one line each."""
    passed, failures = 0, []
    with tempfile.TemporaryDirectory() as scratch:
        for number, words, source in read_manifest(manifest):
            kind, name = words[0], words[1]
            where = f"{os.path.basename(manifest)}:{number} {kind} {name}"
            try:
                if kind == "encode":
                    with open(os.path.join(golden_dir, name), "rb") as f:
                        expected = f.read()
                    got = encode(animc, golden_dir, source, words[2:], os.path.join(scratch, "encoded.ams"))
                    ok = got == expected
                    detail = f"the encoder's {len(got)} bytes differ from the golden's {len(expected)} " \
                             f"from byte {first_difference(got, expected)} on"
                elif kind == "decode":
                    got = decoded_crc(animc, golden_dir, name, words[3:], scratch)
                    ok = got == words[2]
                    detail = f"decoded frames have CRC {got}, expected {words[2]}"
                else:
                    continue
            except (OSError, RuntimeError) as e:
                ok, detail = False, str(e)
            if ok:
                passed += 1
            else:
                failures.append(f"{where}: {detail}")
    return passed, failures


def add_missing(animc, golden_dir, manifest):
    """Writes the golden files and CRCs the manifest names but lacks; replaces nothing."""
    with open(manifest) as f:
        text = f.read().splitlines(keepends=True)
    with tempfile.TemporaryDirectory() as scratch:
        for number, words, source in read_manifest(manifest):
            path = os.path.join(golden_dir, words[1])
            if words[0] == "encode" and not os.path.exists(path):
                encode(animc, golden_dir, source, words[2:], path)
                print(f"added {words[1]}")
            if words[0] == "decode" and words[2] == "-":
                crc = decoded_crc(animc, golden_dir, words[1], words[3:], scratch)
                text[number - 1] = shlex.join(["decode", words[1], crc] + words[3:]) + "\n"
                print(f"added the CRC of line {number}: {crc}")
    with open(manifest, "w") as f:
        f.write("".join(text))


def flip_bit(path, offset):
    with open(path, "r+b") as f:
        f.seek(offset)
        byte = f.read(1)[0]
        f.seek(offset)
        f.write(bytes([byte ^ 0x10]))


def self_test(animc, golden_dir, manifest):
    """A copy of the goldens with one bit flipped in an encoder golden and one in a CRC: the
    check must report exactly those two lines."""
    lines = read_manifest(manifest)
    encode_name = next(words[1] for _, words, _ in lines if words[0] == "encode")
    decode_number, decode_words = next((n, w) for n, w, _ in lines if w[0] == "decode" and w[1] != encode_name)
    with tempfile.TemporaryDirectory() as copy:
        shutil.copytree(golden_dir, copy, dirs_exist_ok=True)
        flip_bit(os.path.join(copy, encode_name), os.path.getsize(os.path.join(copy, encode_name)) // 2)
        with open(manifest) as f:
            text = f.read().splitlines(keepends=True)
        crc = decode_words[2]
        text[decode_number - 1] = text[decode_number - 1].replace(crc, "%08x" % (int(crc, 16) ^ 1), 1)
        copied_manifest = os.path.join(copy, os.path.basename(manifest))
        with open(copied_manifest, "w") as f:
            f.write("".join(text))
        _, failures = check(animc, copy, copied_manifest)
    # The flipped file's own decodes may fail too; those two lines must.
    caught = (any(f" encode {encode_name}:" in f for f in failures) and
              any(f":{decode_number} decode " in f for f in failures))
    return caught, failures


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    animc = os.path.abspath(sys.argv[1])
    manifest = os.path.join(HERE, "manifest.txt")
    if "--add" in sys.argv[2:]:
        add_missing(animc, HERE, manifest)
    passed, failures = check(animc, HERE, manifest)
    for line in failures:
        print("FAIL", line)
    if "--self-test" in sys.argv[2:]:
        caught, seen = self_test(animc, HERE, manifest)
        print("self-test: a flipped bit in an encoder golden and in a CRC", "fail the check" if caught else "went unnoticed")
        for line in seen:
            print("  (expected)", line)
        if caught:
            passed += 1
        else:
            failures.append("self-test")
    print(f"{passed} passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
