#!/usr/bin/env bash
# --version, --help, a missing input file and a missing argument.
set -euo pipefail
matpoint=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

version=$("$matpoint" --version)
[[ $version == "matpoint 0.1.0" ]] || fail "--version printed '$version', expected 'matpoint 0.1.0'"

status=0
"$matpoint" --help >"$tmp/help" 2>&1 || status=$?
[[ $status -eq 0 ]] || fail "--help exited $status"
for command in run check plot; do
  grep -qw "$command" "$tmp/help" || fail "--help does not list '$command':"$'\n'"$(cat "$tmp/help")"
done

missing="$tmp/no-such-input.json"
expect_missing_file_error() {  # $1: the command, for messages; then the full command line
  local what=$1 status=0
  shift
  "$@" >"$tmp/missing.out" 2>&1 || status=$?
  [[ $status -eq 2 ]] || fail "$what on a missing file exited $status, expected 2"
  grep -qF "no-such-input.json" "$tmp/missing.out" ||
    fail "$what: the message does not name the file:"$'\n'"$(cat "$tmp/missing.out")"
}
expect_missing_file_error check "$matpoint" check "$missing"
expect_missing_file_error run "$matpoint" run "$missing" --out "$tmp/out"
[[ ! -e "$tmp/out/summary.json" ]] || fail "run on a missing file wrote summary.json"

status=0
(cd "$tmp" && "$matpoint" run) >/dev/null 2>&1 || status=$?
[[ $status -ne 0 ]] || fail "'matpoint run' with no input exited 0"
echo "PASS: version, help and missing-input handling"
