#!/usr/bin/env bash
# `matpoint dispersion` exits 0, prints the tight Courant bounds of Gong 2015 (7.29) with the square kept
# (extraction T16: 1.0000, 1.29904, 1.34479, 1.36035 for N_p^e = 1..4, +-1e-4) and the sufficient bound 1
# of (7.31)-(7.32), writes dispersion.csv and the plots/dispersion_*.png images; a bad option exits 2.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

status=0
"$matpoint" dispersion --out "$tmp/out" >"$tmp/stdout" 2>"$tmp/stderr" || status=$?
[[ $status -eq 0 ]] || fail "matpoint dispersion exited $status:"$'\n'"$(cat "$tmp/stderr")"

# The bounds table: the rows after the "Courant bounds" line whose first field is N_p^e.
bounds=$(awk '/^Courant bounds/ {b = 1; next} b && $1 ~ /^[0-9]+$/ {print $1, $2, $4}' "$tmp/stdout")
[[ $(wc -l <<<"$bounds") -eq 4 ]] || fail "expected 4 bound rows, got:"$'\n'"$bounds"$'\n'"$(cat "$tmp/stdout")"
awk 'BEGIN {e[1] = 1.0000; e[2] = 1.29904; e[3] = 1.34479; e[4] = 1.36035}
     { d = $2 - e[$1]; if (d < 0) d = -d
       if (d > 1e-4) { printf "N_p^e = %d: tight bound %s, expected %s +- 1e-4\n", $1, $2, e[$1]; bad = 1 }
       s = $3 - 1; if (s < 0) s = -s
       if (s > 1e-6) { printf "N_p^e = %d: sufficient bound %s, expected 1\n", $1, $3; bad = 1 } }
     END { exit bad }' <<<"$bounds" || fail "wrong bounds:"$'\n'"$bounds"

[[ -s "$tmp/out/dispersion.csv" ]] || fail "no dispersion.csv"
[[ -s "$tmp/out/dispersion_bounds.csv" ]] || fail "no dispersion_bounds.csv"
header=$(head -1 "$tmp/out/dispersion.csv")
[[ $header == relation,particles_per_cell,courant,theta,m,* ]] || fail "dispersion.csv header: $header"
leftovers=$(find "$tmp/out" -name '*.partial*')
[[ -z "$leftovers" ]] || fail "temporary files left behind: $leftovers"

if "$python" -c 'import matplotlib' 2>/dev/null; then
  for name in amplitude phase_speed growth; do
    png="$tmp/out/plots/dispersion_$name.png"
    [[ -f "$png" ]] || fail "no $png; stderr:"$'\n'"$(cat "$tmp/stderr")"
    [[ $(head -c 4 "$png" | tail -c 3) == PNG ]] || fail "$png is not a PNG"
  done
else
  echo "SKIP: $python has no matplotlib, plots/dispersion_*.png not checked"
fi

status=0
"$matpoint" dispersion --particles-per-cell 0 --out "$tmp/bad" >/dev/null 2>&1 || status=$?
[[ $status -eq 2 ]] || fail "--particles-per-cell 0 exited $status, expected 2"
[[ ! -e "$tmp/bad" ]] || fail "a rejected command line wrote $tmp/bad"

"$matpoint" dispersion --json --no-plots -n 2 --courant 1.2 --out "$tmp/json" >"$tmp/json.out" ||
  fail "--json exited non-zero"
grep -q '"tight": 1.2990' "$tmp/json.out" || fail "--json does not report the N_p^e = 2 bound:"$'\n'"$(cat "$tmp/json.out")"
echo "PASS: dispersion table, bounds $(awk '{printf "%s ", $2}' <<<"$bounds")and outputs"
