#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The WebAssembly decoder's tests (web/test/): `decoder`, in Node, against ANIMC's frames;
# `player`, the player page in headless Chromium. Listed as not run (77) when what they need
# is missing: web/dist/animc.wasm (scripts/build_web.sh), Chromium and web/node_modules
# (scripts/setup.sh).
#   usage: web_test.sh decoder|player ANIMC
set -euo pipefail
kind=$1
export ANIMC=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
if [[ ! -f $root/web/dist/animc.wasm ]]; then
  echo "web_test: no web/dist/animc.wasm (bash scripts/build_web.sh builds it): not run"
  exit 77
fi
if [[ $kind == decoder ]]; then
  exec node --test "$root/web/test/decode.test.mjs"
fi
if [[ ! -x /usr/bin/chromium || ! -d $root/web/node_modules/puppeteer-core ]]; then
  echo "web_test: no /usr/bin/chromium or no web/node_modules (bash scripts/setup.sh installs both): not run"
  exit 77
fi
exec node "$root/web/test/player_browser.mjs"
