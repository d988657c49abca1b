#!/usr/bin/env bash
# Installs what is missing, builds Release, runs the headline example (two colliding elastic disks)
# and tells where its results are.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh

out=out/two-disks
root=$(pwd)
echo "quickstart: running examples/two-disks"
status=0
build/matpoint run examples/two-disks/input.json --out "$out" --overwrite || status=$?
if ((status != 0)); then
  echo "quickstart: the run failed with exit code $status" >&2
  exit "$status"
fi

python=python3
[[ -x /usr/bin/python3 ]] && python=/usr/bin/python3
echo
echo "ParaView:  open $root/$out/results.pvd"
echo "plot:      $root/$out/plots/energy.png (also momentum.png, final_state.png)"
echo "summary:   $root/$out/summary.json"
"$python" - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"checks ({'all pass' if s.get('checks_pass') else 'SOME FAIL'}):")
for c in s.get("checks", []):
    print(f"  {'PASS' if c['pass'] else 'FAIL'}  {c['name']}: measured {c['measured']}, "
          f"expected {c['expected']} +/- {c['tolerance']}  [{c['source']}]")
PY
