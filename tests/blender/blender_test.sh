#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Blender add-on (blender/io_anim_ams) in headless Blender, installed as a user installs it
# (a user script folder holding the add-on), with the animcompress module on PYTHONPATH:
# roundtrip.py exports an armature-animated mesh, imports it back and checks the frames and
# the error reports for bad files.
# usage: blender_test.sh REPO_DIR PYTHON_MODULE_DIR   (exit 77: no blender on this machine)
set -euo pipefail
REPO=${1:?usage: blender_test.sh REPO_DIR PYTHON_MODULE_DIR}
MODULE_DIR=${2:?usage: blender_test.sh REPO_DIR PYTHON_MODULE_DIR}
if ! command -v blender >/dev/null; then
  echo "blender_test: no blender (scripts/setup.sh installs Debian's): not run"
  exit 77
fi
TMP=$(mktemp -d "${TMPDIR:-/tmp}/animc_blender_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$TMP/scripts/addons"
ln -s "$(realpath "$REPO/blender/io_anim_ams")" "$TMP/scripts/addons/io_anim_ams"
BLENDER_USER_SCRIPTS=$TMP/scripts BLENDER_USER_CONFIG=$TMP/config PYTHONPATH=$MODULE_DIR \
  blender -b --factory-startup --python-exit-code 1 --python "$REPO/tests/blender/roundtrip.py" -- "$TMP/out" \
  >"$TMP/blender.log" 2>&1 || { cat "$TMP/blender.log"; echo "blender_test: failed" >&2; exit 1; }
grep -E '^(ok|FAIL): ' "$TMP/blender.log"
grep -qx 'blender_test: 1 passed, 0 failed' "$TMP/blender.log" || { cat "$TMP/blender.log"; exit 1; }
echo "blender_test: 1 passed, 0 failed"
