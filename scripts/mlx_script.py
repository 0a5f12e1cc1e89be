#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""A MeshLab filter script (.mlx) with some parameter values changed. MeshLab needs a script to
list every parameter of its filters, so tests and benchmarks derive theirs from the samples
instead of keeping copies. Every parameter named must occur exactly once: a renamed or removed
parameter fails loudly instead of silently leaving the sample's value in place.

usage: scripts/mlx_script.py SCRIPT NAME=VALUE...   (writes the changed script to stdout)"""
import re
import sys
from xml.sax.saxutils import quoteattr


def with_values(path, values):
    """The text of the script at path with each parameter's value set: values is {name: text}."""
    with open(path) as f:
        script = f.read()
    for name, value in values.items():
        script, found = re.subn(f'(name="{re.escape(name)}" value=)"[^"]*"',
                                lambda m: m.group(1) + quoteattr(value), script)
        if found != 1:
            raise RuntimeError(f'{path}: {found} parameters named {name}, expected 1')
    return script


def main():
    if len(sys.argv) < 3 or any('=' not in a for a in sys.argv[2:]):
        sys.exit(__doc__.split('\n\n')[-1])
    try:
        sys.stdout.write(with_values(sys.argv[1], dict(a.split('=', 1) for a in sys.argv[2:])))
    except (OSError, RuntimeError) as e:
        sys.exit(f'mlx_script: {e}')


if __name__ == '__main__':
    main()
