#!/usr/bin/env bash
# Plane strain keeps sigma_zz: a linear-elastic block stretched by an initial velocity gradient
# writes a 3 x 3 stress whose zz component is Hooke's nu (sigma_xx + sigma_yy) (plane strain,
# eps_zz = 0; St Venant-Kirchhoff differs from it by O(strain) ~ 1e-4 here, so the bound is 1e-3
# of the largest stress), and pressure / von_mises computed from that 3 x 3 stress.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

cat >"$tmp/input.json" <<'JSON'
{ "title": "plane-strain sigma_zz",
  "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
  "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e6, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3, 0.3], "max": [0.7, 0.7]},
              "velocity_gradient": [[0.02, 0.005], [0, -0.004]]}],
  "solver": {"dt": 1e-4, "end_time": 0.01},
  "output": {"every_time": 0.01, "fields": ["stress", "pressure", "von_mises"], "plots": false} }
JSON

status=0
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/out" >"$tmp/run.out" 2>"$tmp/run.err" || status=$?
[[ $status -eq 0 ]] || fail "matpoint run exited $status:"$'\n'"$(cat "$tmp/run.err")"

"$python" - "$tmp/out" <<'PY'
import os, sys
import xml.etree.ElementTree as ET
import meshio
import numpy as np

out = sys.argv[1]
files = [d.get("file") for d in ET.parse(os.path.join(out, "results.pvd")).getroot().iter("DataSet")]
mesh = meshio.read(os.path.join(out, files[-1]))
s = np.asarray(mesh.point_data["stress"]).reshape(-1, 3, 3)
scale = np.abs(s).max()
if not scale > 0:
    sys.exit(f"FAIL: no stress in {files[-1]}")
zz, hooke = s[:, 2, 2], 0.3 * (s[:, 0, 0] + s[:, 1, 1])
error = np.abs(zz - hooke).max() / scale
if not error < 1e-3:
    sys.exit(f"FAIL: sigma_zz differs from nu (sigma_xx + sigma_yy) by {error:.3g} of the stress scale")
mean = np.trace(s, axis1=1, axis2=2) / 3
if not np.allclose(mesh.point_data["pressure"].ravel(), -mean, rtol=0, atol=1e-12 * scale):
    sys.exit("FAIL: pressure is not -tr(sigma)/3 of the 3 x 3 stress")
dev = s - mean[:, None, None] * np.eye(3)
vm = np.sqrt(1.5 * np.einsum("pij,pij->p", dev, dev))
if not np.allclose(mesh.point_data["von_mises"].ravel(), vm, rtol=0, atol=1e-12 * scale):
    sys.exit("FAIL: von_mises is not sqrt(3/2 s:s) of the 3 x 3 stress")
print(f"sigma_zz = nu (sigma_xx + sigma_yy) to {error:.2e} of the stress scale {scale:.3g}")
PY
echo "PASS: plane-strain sigma_zz written"
