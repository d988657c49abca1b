#!/usr/bin/env bash
# Measured Courant limits of FLIP and FMPM(k) for every basis, on the Nairn 2026 §3.3 vibrating bar
# (1-D, examples/fmpm-vibrating-bar/input.json), by bisection to +/-0.005 with `matpoint
# stability-scan` (stable = 5 periods with no guard tripping and K never above 10^2 K(0)).
# The table feeds src/matpoint/explicit/courant_limits.hpp and docs/theory/courant_limits.md.
# Usage: scripts/courant_limits_by_basis.sh [MATPOINT] > table.md   (about 10 minutes on 2 cores)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
matpoint="${1:-$here/../build/matpoint}"
input="$here/../examples/fmpm-vibrating-bar/input.json"
bases=(linear ugimp cpgimp bspline2 bspline3 b2gimp cpdi1 cpdi2 b2cpdi)
orders=(1 2 3 4 8 16 40 80)

limit() {  # prints the bisected limit, or 1.0 when stable at C = 1
  local line
  # shellcheck disable=SC2086  # the options are meant to split
  line=$("$matpoint" stability-scan "$input" --lo 0.02 --hi 1.0 --growth 10 $1 | tail -1 || true)
  if [[ $line =~ limit:\ ([0-9.]+) ]]; then echo "${BASH_REMATCH[1]}"; else echo "1.0"; fi
}

printf '| basis | FLIP |'
for k in "${orders[@]}"; do printf ' FMPM(%s) |' "$k"; done
printf '\n|---|---|'
for _ in "${orders[@]}"; do printf -- '---|'; done
printf '\n'
for basis in "${bases[@]}"; do
  shape="--set solver.basis=\"$basis\""
  printf '| %s | %s |' "$basis" "$(limit "$shape --set solver.transfer=\"flip\" --set solver.fmpm=null")"
  for k in "${orders[@]}"; do printf ' %s |' "$(limit "$shape --set solver.fmpm.order=$k")"; done
  printf '\n'
done
