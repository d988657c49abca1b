#!/usr/bin/env bash
# Plots of a 3-D run with probes and an input `units` block: final_state.png is drawn (x-y and x-z
# projections), the axes carry the input's units, and each probe keeps one colour for all its
# components (one line style per component), so 3-D probes do not share colours.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
source_dir=$2

cat >"$tmp/input.json" <<'JSON'
{ "title": "a long title that used to be clipped at the top of final_state.png because it did not fit",
  "units": {"length": "m", "time": "s", "mass": "kg", "stress": "Pa", "energy": "J"},
  "grid": {"dim": 3, "min": [0, 0, 0], "max": [1, 1, 1], "cell_size": 0.125},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.25, 0.25, 0.25], "max": [0.75, 0.75, 0.75]},
              "velocity": [0.1, 0, 0]}],
  "solver": {"dt": 0.001, "end_time": 0.01},
  "output": {"every_steps": 5, "probes": [{"name": "a", "position": [0.3, 0.3, 0.3]},
                                          {"name": "b", "position": [0.7, 0.7, 0.7]}]} }
JSON
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/out" >/dev/null 2>"$tmp/err" || fail "run failed: $(cat "$tmp/err")"
grep -q "could not draw" "$tmp/err" && fail "plot warning: $(cat "$tmp/err")"
[[ -s "$tmp/out/plots/final_state.png" ]] || fail "no final_state.png for a 3-D run"

MPLBACKEND=Agg "$python" - "$source_dir/scripts" "$tmp/out" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import matplotlib.pyplot as plt
import plot_history as ph

units = {"length": "m", "time": "s", "mass": "kg", "stress": "Pa", "energy": "J"}
for quantity, label in [("energy", "energy [J]"), ("time", "time [s]"), ("velocity", "velocity [m/s]"),
                        ("linear momentum", "linear momentum [kg·m/s]"), ("Cauchy stress", "Cauchy stress [Pa]"),
                        ("displacement", "displacement [m]")]:
    got = ph.axis_label(quantity, units)
    assert got == label, (quantity, got, label)
assert ph.axis_label("energy", {}) == "energy"

# Probe lines: one colour per probe, distinct line styles within a probe.
h = ph.read_history(sys.argv[2] + "/history.csv")
figures = []
ph.save = lambda fig, plots, name: figures.append(fig)
ph.plot_probes(h, "t", "unused", units)
stress_axis = figures[0].axes[2]
colours = {}
for line in stress_axis.get_lines():
    probe = line.get_label().split(":")[0]
    colours.setdefault(probe, set()).add(line.get_color())
assert set(colours) == {"a", "b"}, colours
assert all(len(c) == 1 for c in colours.values()), f"a probe's components have several colours: {colours}"
assert colours["a"] != colours["b"], "two probes share a colour"
styles = [str(line._dash_pattern) for line in stress_axis.get_lines() if line.get_label().startswith("a:")]
assert len(styles) == 6 and len(set(styles)) == 6, f"probe a's 6 stress components: styles {styles}"
print("units, probe colours and styles as expected")
PY
echo "PASS: 3-D final state drawn; units on the axes; one colour per probe"
