# SPDX-License-Identifier: Apache-2.0
# What the command-line test scripts share (sourced, after set -euo pipefail and PY=...): a
# scratch folder $TMP removed at exit, and assertions that record a failure and go on
# (check_failed, json_check, same_kg) or stop the script (die, run). A script ends with
# finish_checks NAME.
TMP=$(mktemp -d "${TMPDIR:-/tmp}/animc_cli_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

FAILURES=0
# check_failed MESSAGE: records a failed assertion and goes on (so one run shows them all).
check_failed() { echo "FAIL: $*" >&2; FAILURES=$((FAILURES + 1)); }
# die MESSAGE: a step the rest depends on failed.
die() { echo "FAIL: $*" >&2; echo "($FAILURES earlier failures)" >&2; exit 1; }

# run NAME CMD...: runs CMD with stdout in $TMP/NAME.out, stderr in $TMP/NAME.err, and dies
# unless it exits 0.
run() {
  local name=$1 rc=0
  shift
  "$@" >"$TMP/$name.out" 2>"$TMP/$name.err" || rc=$?
  ((rc == 0)) || die "$name: exit $rc from: $*"$'\n'"$(cat "$TMP/$name.err")"
}

# json_check EXPR FILE...: each FILE holds exactly one JSON object (d = the first, e = the
# second) and the Python expression EXPR is true.
json_check() {
  local expr=$1
  shift
  "$PY" - "$expr" "$@" <<'EOF' || check_failed "json_check '$expr' on $*"
import json, math, sys
expr, docs = sys.argv[1], []
for path in sys.argv[2:]:
    with open(path) as f:
        try:
            docs.append(json.load(f))
        except ValueError as err:
            sys.exit(f"{path}: not exactly one JSON document: {err}")
    if not isinstance(docs[-1], dict):
        sys.exit(f"{path}: not a JSON object")
env = {"d": docs[0], "e": docs[1] if len(docs) > 1 else None, "math": math}
try:
    ok = eval(expr, env)
except Exception as err:
    sys.exit(f"{expr}: {type(err).__name__}: {err}\n{docs}")
if not ok:
    sys.exit(f"false: {expr}\n" + "\n".join(json.dumps(d, sort_keys=True) for d in docs))
EOF
}

# same_kg FILE_A FILE_B: equal kg_error to 1e-9 relative.
same_kg() { json_check 'abs(d["kg_error"] - e["kg_error"]) <= 1e-9 * abs(e["kg_error"])' "$1" "$2"; }

# leftovers DIR: the temporary files and folders in DIR (core/atomic_file.h names them
# ".animc-<pid>-<n>.tmp"; releases up to 1.0.0 named them "<name>.tmp-<pid>-<n>").
leftovers() { find "$1" -maxdepth 1 \( -name '.animc-*.tmp' -o -name '*.tmp-*' \) -printf '%f\n'; }

# finish_checks NAME: exits 1 if any check failed, else says that NAME passed.
finish_checks() {
  if ((FAILURES > 0)); then
    echo "$FAILURES check(s) failed" >&2
    exit 1
  fi
  echo "$1: all checks passed"
}
