#!/usr/bin/env bash
# particles_NNNNNN.vtu is zlib-compressed appended binary with UInt64 headers, read identically by
# VTK's own XML reader (python3-vtk9) and by meshio; `state` has named components (Mie-Grueneisen:
# e, eta); displacement is x - X (X: the particle's position in the first file, by id) and
# pressure is -tr(stress)/3; compressed, a file is smaller than its raw arrays.
# shellcheck source-path=SCRIPTDIR source=common.bash
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"

cat >"$tmp/input.json" <<'JSON'
{ "grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.05},
  "materials": [{"name": "nickel", "model": "mie_gruneisen", "density": 8870, "bulk_sound_speed": 4600,
                 "hugoniot_slope": 1.44, "gruneisen": 1.93, "shear_modulus": 7.6e10}],
  "bodies": [{"material": "nickel", "shape": {"type": "disk", "center": [0.5, 0.5], "radius": 0.2},
              "velocity": [50, 20]}],
  "solver": {"end_time": 2e-5}, "output": {"every_steps": 10, "plots": false} }
JSON
"$matpoint" run "$tmp/input.json" --quiet --out "$tmp/out" >/dev/null 2>"$tmp/err" || fail "run failed: $(cat "$tmp/err")"

"$python" - "$tmp/out" <<'PY'
import glob, os, sys
import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

def fail(message):
    sys.exit(f"FAIL: {message}")

files = sorted(glob.glob(os.path.join(sys.argv[1], "particles_*.vtu")))
if len(files) < 2:
    fail(f"{len(files)} .vtu files")
head = open(files[-1], "rb").read(400).decode("latin-1")
for attribute in ('header_type="UInt64"', 'compressor="vtkZLibDataCompressor"'):
    if attribute not in head:
        fail(f"no {attribute} in the VTKFile element: {head[:300]}")

def read_vtk(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    data = grid.GetPointData()
    arrays = {data.GetArrayName(i): data.GetArray(i) for i in range(data.GetNumberOfArrays())}
    return vtk_to_numpy(grid.GetPoints().GetData()), arrays

X = {}
for path in (files[0], files[-1]):
    points, arrays = read_vtk(path)
    mesh = meshio.read(path)
    n = len(mesh.points)
    if points.shape != (n, 3) or not np.array_equal(points, mesh.points):
        fail(f"{path}: VTK and meshio read different points")
    for name, array in arrays.items():
        ours = vtk_to_numpy(array).reshape(n, -1)
        theirs = np.asarray(mesh.point_data[name]).reshape(n, -1)
        if not np.array_equal(ours, theirs):
            fail(f"{path}: VTK and meshio read different {name!r}")
    if mesh.cells[0].type != "vertex" or len(mesh.cells[0].data) != n:
        fail(f"{path}: cells are not one vertex per particle")
    ids = vtk_to_numpy(arrays["id"])
    if path == files[0]:
        X = dict(zip(ids, points))
    state = arrays["state"]
    names = [state.GetComponentName(c) for c in range(state.GetNumberOfComponents())]
    if names != ["e", "eta"]:
        fail(f"state components are named {names}, expected ['e', 'eta']")
    u = vtk_to_numpy(arrays["displacement"])
    expected_u = points - np.array([X[i] for i in ids])
    if np.max(np.abs(u - expected_u)) > 1e-12:
        fail(f"{path}: displacement is not x - X (max error {np.max(np.abs(u - expected_u))})")
    sigma = vtk_to_numpy(arrays["stress"]).reshape(n, 3, 3)
    p = vtk_to_numpy(arrays["pressure"])
    if np.max(np.abs(p + np.trace(sigma, axis1=1, axis2=2) / 3)) > 1e-9 * max(1.0, np.max(np.abs(sigma))):
        fail(f"{path}: pressure is not -tr(stress)/3")

# Compressed: smaller than the raw bytes of its arrays.
raw = sum(vtk_to_numpy(a).nbytes for a in arrays.values()) + points.nbytes
size = os.path.getsize(files[-1])
if size >= raw:
    fail(f"{files[-1]} has {size} bytes, its raw arrays {raw}: not compressed")
print(f"{os.path.basename(files[-1])}: {size} bytes for {raw} raw bytes of point data")
PY
echo "PASS: compressed .vtu read identically by VTK and meshio; named state, displacement and pressure"
