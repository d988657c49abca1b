#!/usr/bin/env bash
# Plots are drawn without a shell: an output folder whose name holds quotes, spaces, `$` and `;`
# gets its plots and runs nothing, a failing script's own error is reported, and an installed
# binary (cmake --install) uses the scripts installed beside it.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
source_dir=$2

cat >"$tmp/input.json" <<'JSON'
{ "title": "plot launch test",
  "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1000, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3, 0.3], "max": [0.7, 0.7]},
              "velocity": [0.1, 0]}],
  "solver": {"dt": 0.001, "end_time": 0.01}, "output": {"every_steps": 5} }
JSON

# A folder name a shell would split, expand or execute: it must be taken literally.
out="$tmp/it's a \"dir\" \$HOME \`touch $tmp/pwned-backtick\`; touch $tmp/pwned"
status=0
"$matpoint" run "$tmp/input.json" --quiet --out "$out" >"$tmp/run.out" 2>"$tmp/run.err" || status=$?
[[ $status -eq 0 ]] || fail "matpoint run exited $status:"$'\n'"$(cat "$tmp/run.err")"
[[ ! -e "$tmp/pwned" && ! -e "$tmp/pwned-backtick" ]] || fail "the output path was run as shell code"
[[ -s "$out/plots/energy.png" ]] || fail "no plots/energy.png in the quoted folder:"$'\n'"$(cat "$tmp/run.err")"
grep -q "could not draw" "$tmp/run.err" && fail "plot warning for the quoted folder:"$'\n'"$(cat "$tmp/run.err")"

# `matpoint plot` on the same folder redraws; on a folder without history.csv it reports the
# script's own message (not a guess about matplotlib) and exits 1.
rm -r "$out/plots"
"$matpoint" plot "$out" 2>"$tmp/plot.err" || fail "matpoint plot on the quoted folder failed: $(cat "$tmp/plot.err")"
[[ -s "$out/plots/energy.png" ]] || fail "matpoint plot drew no energy.png in the quoted folder"
mkdir "$tmp/empty \$dir"
status=0
"$matpoint" plot "$tmp/empty \$dir" 2>"$tmp/plot.err" || status=$?
[[ $status -eq 1 ]] || fail "matpoint plot on an empty folder exited $status, expected 1"
grep -qF "empty \$dir/history.csv not found" "$tmp/plot.err" ||
  fail "the script's own error is not reported:"$'\n'"$(cat "$tmp/plot.err")"
grep -q "matplotlib" "$tmp/plot.err" && fail "blames matplotlib:"$'\n'"$(cat "$tmp/plot.err")"

# Installed: the binary finds share/matpoint/scripts relative to itself. The installed copy of
# plot_history.py is marked so that its use (and not the source tree's) shows.
build_dir=$(dirname "$matpoint")
if [[ -f "$build_dir/cmake_install.cmake" ]]; then
  cmake --install "$build_dir" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 ||
    fail "cmake --install failed:"$'\n'"$(cat "$tmp/install.log")"
  installed="$tmp/prefix/share/matpoint/scripts/plot_history.py"
  [[ -x "$tmp/prefix/bin/matpoint" && -f "$installed" ]] || fail "cmake --install did not install bin/matpoint and $installed"
  sed -i '/^import sys$/a open(os.path.join(sys.argv[1], "installed-script-ran"), "w").close()' "$installed"
  env -u MATPOINT_SCRIPTS_DIR "$tmp/prefix/bin/matpoint" plot "$out" 2>"$tmp/plot.err" ||
    fail "installed matpoint plot failed: $(cat "$tmp/plot.err")"
  [[ -e "$out/installed-script-ran" ]] || fail "the installed binary did not use the installed scripts"
fi
echo "PASS: plots drawn without a shell; script errors reported; installed scripts found"
