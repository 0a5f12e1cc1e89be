#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A fuzzing campaign: every libFuzzer harness of a fuzz build (ANIMC_BUILD_FUZZERS=ON: ASan,
# UBSan) for SECONDS each, starting from the in-tree corpus tests/fuzz/corpus/<harness>
# (read only; new inputs go to WORK/<harness>). Prints each harness's executions and exits
# non-zero, naming the input left in WORK/artifacts, when one crashes, leaks, hangs or runs out
# of memory. CI runs a short one; tests/fuzz/README.md records the long ones.
#   usage: tests/fuzz/campaign.sh FUZZ_BUILD_DIR SECONDS [WORK] [--parallel]
# --parallel runs the harnesses side by side (one core each) instead of one after another.
# ANIMC_FUZZ_TIMEOUT (seconds, default 10) is the wall-clock time one input may take: raise it
# on a loaded machine, where a starved run otherwise reports a hang that is not there.
set -euo pipefail
build=$(realpath "$1")
seconds=$2
work=$(realpath -m "${3:-/tmp/animc_fuzz_campaign}")
parallel=${4:-}
corpus=$(cd "$(dirname "$0")" && pwd)/corpus
harnesses=(ams_decode sequence_readers round_trip layer_checks)
# ams_decode: 2 KB, so that most time goes to mutated streams rather than to rebuilding the
# wavelet hierarchy of a real mesh (tests/fuzz/README.md, "Campaigns").
declare -A max_len=([ams_decode]=2048 [sequence_readers]=8192 [round_trip]=4096 [layer_checks]=8192)
mkdir -p "$work/artifacts"

# run HARNESS: one libFuzzer run; its log in WORK/HARNESS.log.
run() {
  local h=$1 program=$build/tests/fuzz/fuzz_$1
  [[ -x $program ]] || { echo "campaign: no $program (build with -DANIMC_BUILD_FUZZERS=ON)" >&2; return 2; }
  mkdir -p "$work/$h"
  "$program" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout="${ANIMC_FUZZ_TIMEOUT:-10}" \
    -max_len="${max_len[$h]}" -print_final_stats=1 -artifact_prefix="$work/artifacts/$h-" \
    "$work/$h" "$corpus/$h" >"$work/$h.log" 2>&1
}

# report HARNESS STATUS: one line; the crash's first lines when it failed.
report() {
  local h=$1 status=$2 execs
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/$h.log" | tail -1)
  if [[ $status == 0 ]]; then
    printf 'fuzz_%s: %s executions in %s s, no failure\n' "$h" "${execs:-?}" "$seconds"
    return 0
  fi
  printf 'FAIL: fuzz_%s (exit %s) after %s executions; input: %s\n' "$h" "$status" "${execs:-?}" \
    "$(ls "$work/artifacts/$h-"* 2>/dev/null | head -1)"
  grep -m 5 -E 'ERROR|SUMMARY|round trip|runtime error' "$work/$h.log" || tail -5 "$work/$h.log"
  return 1
}

declare -A status
if [[ $parallel == --parallel ]]; then
  declare -A pids
  for h in "${harnesses[@]}"; do run "$h" & pids[$h]=$!; done
  for h in "${harnesses[@]}"; do status[$h]=0; wait "${pids[$h]}" || status[$h]=$?; done
else
  for h in "${harnesses[@]}"; do status[$h]=0; run "$h" || status[$h]=$?; done
fi
failed=0
for h in "${harnesses[@]}"; do report "$h" "${status[$h]}" || failed=1; done
exit $failed
