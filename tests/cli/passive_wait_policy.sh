#!/usr/bin/env bash
# matpoint's OpenMP threads sleep rather than spin while they wait (docs/user_guide.md "Threads"):
# without a user setting the running program has OMP_WAIT_POLICY=passive (libgomp reads it at
# load time, so the program re-executes itself with it); a user's own setting is kept.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
# shellcheck source=restart_common.bash
source "$(dirname "${BASH_SOURCE[0]}")/restart_common.bash"

restart_input "$tmp/input.json"
policy_of_run() {  # $1: out folder; the rest: env assignments. Echoes the running program's policy.
  local out=$1 pid policy=""
  shift
  env "$@" "$matpoint" run "$tmp/input.json" --quiet --threads 2 --out "$out" >/dev/null 2>&1 &
  pid=$!
  for _ in $(seq 200); do
    policy=$(tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | sed -n 's/^OMP_WAIT_POLICY=//p')
    [[ -n $policy && -e "$out/particles_000000.vtu" ]] && break
    sleep 0.02
  done
  kill -INT "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  echo "${policy:-unset}"
}
policy=$(policy_of_run "$tmp/a" -u OMP_WAIT_POLICY)
[[ $policy == passive ]] || fail "without a user setting the run's OMP_WAIT_POLICY is '$policy', expected passive"
policy=$(policy_of_run "$tmp/b" OMP_WAIT_POLICY=active)
[[ $policy == active ]] || fail "the user's OMP_WAIT_POLICY=active became '$policy'"
echo "PASS: passive OpenMP wait policy unless the user sets one"
