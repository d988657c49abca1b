#!/usr/bin/env bash
# The return map's cost: particle-steps per second of examples/soil-column-collapse (Mohr-Coulomb)
# next to the same run with a neo-Hookean soil (same E, nu, density), on 1 and 2 threads.
# Both runs: the fine grid (h = 0.025 m, 12 800 particles), a fixed dt = 4e-4 s and 500 steps (to
# t = 0.2 s: the column has started to fail), no particle output. Best of REPEAT runs each (the
# machine may be shared). Usage: bench/column_plasticity.sh [BUILD_DIR] [REPEAT]
set -euo pipefail
build=${1:-build}
repeat=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work" <<'PY'
import json, re, sys
work = sys.argv[1]
text = open("examples/soil-column-collapse/input.json").read()
spec = json.loads(re.sub(r"^\s*//.*$", "", text, flags=re.M))
spec["grid"]["cell_size"] = 0.025
spec["solver"].pop("courant", None)
spec["solver"].update({"dt": 4e-4, "end_time": 0.2})
spec["output"] = {"every_time": 0.2, "particles": False, "plots": False}
spec["checks"] = []
json.dump(spec, open(f"{work}/mohr_coulomb.json", "w"))
m = spec["materials"][0]
for key in ("cohesion", "friction_angle", "dilation_angle"):
    m.pop(key)
m["model"] = "neo_hookean"
json.dump(spec, open(f"{work}/neo_hookean.json", "w"))
PY
for threads in 1 2; do
  for model in mohr_coulomb neo_hookean; do
    best=0
    for ((i = 0; i < repeat; ++i)); do
      "$build/matpoint" run "$work/$model.json" --out "$work/out" --overwrite --quiet --threads "$threads" > /dev/null 2>&1
      rate=$(python3 -c "import json; print(json.load(open('$work/out/summary.json'))['particle_steps_per_second'])")
      best=$(python3 -c "print(max($best, $rate))")
    done
    printf "%-13s threads %d: %.3g particle-steps/s (best of %d)\n" "$model" "$threads" "$best" "$repeat"
  done
done
