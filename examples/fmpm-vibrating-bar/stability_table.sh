#!/usr/bin/env bash
# Courant limits of the Nairn 2026 §3.3 vibrating bar for each method, by bisection to +/-0.005
# (matpoint stability-scan), next to the paper's values (Nairn 2026 §3.3, Fig. 12A and text).
# Usage: examples/fmpm-vibrating-bar/stability_table.sh [MATPOINT] [SHAPE]
# Stable = 5 periods complete with no guard tripping and the kinetic energy never above 10^2 times
# its initial value (--growth 10); the paper's criterion is completing 5 periods.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
matpoint="${1:-$here/../../build/matpoint}"
shape="${2:-linear}"
input="$here/input.json"

fmpm() { echo "--set solver.fmpm.order=$1"; }
variants=(
  "FLIP (alpha 1/2)|0.84|--set solver.transfer=\"flip\" --set solver.fmpm=null"
  "FMPM(1)|0.86|$(fmpm 1)"
  "FMPM(4)|0.539|$(fmpm 4)"
  "FMPM(40)|0.25|$(fmpm 40)"
  "FMPM(80)|0.24|$(fmpm 80)"
  "FMPM(40) blended with FMPM(1), alpha_b = 0.8|0.51|$(fmpm 40) --set solver.fmpm.blend={\"with\":1,\"factor\":0.8}"
  "FMPM(40) blended with FMPM(1), alpha_b = 0.9|0.40|$(fmpm 40) --set solver.fmpm.blend={\"with\":1,\"factor\":0.9}"
  "FMPM(40) blended with FMPM(2), alpha_b = 0.8|0.40|$(fmpm 40) --set solver.fmpm.blend={\"with\":2,\"factor\":0.8}"
  "periodic FMPM(40), C_X = 2|0.40|$(fmpm 40) --set solver.fmpm.periodic={\"courant\":2}"
)
echo "| method | paper | matpoint ($shape) | difference |"
echo "|---|---|---|---|"
for v in "${variants[@]}"; do
  IFS='|' read -r name paper args <<<"$v"
  # shellcheck disable=SC2086  # args are intentionally split into options
  line=$("$matpoint" stability-scan "$input" --lo 0.05 --hi 1.0 --growth 10 --set "solver.basis=\"$shape\"" $args | tail -1 || true)
  if [[ $line =~ limit:\ ([0-9.]+) ]]; then
    limit=${BASH_REMATCH[1]}
    printf '| %s | %s | %s | %+.3f |\n' "$name" "$paper" "$limit" "$(echo "$limit - $paper" | bc -l)"
  else
    printf '| %s | %s | >= 1 (stable at 1.0) | |\n' "$name" "$paper"
  fi
done
