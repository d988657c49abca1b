#!/usr/bin/env bash
# Command-line mistakes get short, useful messages and exit 2: a mistyped command or option names
# the nearest one, `matpoint help [COMMAND]` works, a bad --threads says what is allowed in one
# line, and a named pipe given as the input is refused at once (opening it would wait forever).
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

expect() {  # $1: expected status, $2: text the output must contain, then the command's arguments
  local want=$1 text=$2 status=0
  shift 2
  timeout 20 "$matpoint" "$@" >"$tmp/out" 2>&1 || status=$?
  [[ $status -eq $want ]] || fail "matpoint $* exited $status, expected $want:"$'\n'"$(head -c 2000 "$tmp/out")"
  grep -qF -- "$text" "$tmp/out" || fail "matpoint $*: no '$text' in:"$'\n'"$(head -c 2000 "$tmp/out")"
}

expect 2 "did you mean 'run'?" runn x.json
expect 2 "did you mean 'check'?" chekc x.json
expect 0 "Subcommands:" help
expect 0 "--threads" help run
expect 2 "did you mean '--threads'?" run x.json --thread 1
expect 2 "did you mean '--out'?" run x.json --outt here

expect 2 "expected a whole number from 0 (all cores) to 4096" run x.json --threads -1
lines=$(wc -c <"$tmp/out")
[[ $lines -lt 300 ]] || fail "--threads -1 gave a $lines-character message:"$'\n'"$(cat "$tmp/out")"
expect 2 "expected a whole number" run x.json --threads abc

mkfifo "$tmp/pipe.json"
expect 2 "a named pipe" check "$tmp/pipe.json"
echo "PASS: command-line mistakes get suggestions and short messages"
