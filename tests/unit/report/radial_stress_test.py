#!/usr/bin/python3
"""The radial normal stress of the paper's Fig. 7 (scripts/plotting/fields.py, issue 31 item 5):
σ_rr = n·σ·n with n radial from the bearing's axis, on tensors with known answers; the array
added to a grid from its 9-component `stress`; and `plot.py fields --cut` drawing it beside von
Mises from the stand-in FE stage's fields (whose stress is −vm·n⊗n: σ_rr = −vm), or refusing
fields without the stress tensor with exit 1 and the reason.

    radial_stress_test.py
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import vtk_to_numpy  # noqa: E402

from plotting import _report_fe, fields  # noqa: E402


def check(cond, what):
    if not cond:
        raise SystemExit("FAIL: " + what)


def tensors():
    rng = np.random.default_rng(7)
    # A hydrostatic stress −p·I: σ_rr = −p in every direction, on the axis too.
    pts = np.array([[0.0, -0.01, 0.003], [0.007, 0.007, -0.002], [0.0, 0.0, 0.0]])
    sig = np.tile((-5e7 * np.eye(3)).reshape(9), (3, 1))
    check(np.allclose(fields.radial_normal_stress(pts, sig), -5e7, rtol=1e-14), "hydrostatic")
    # Uniaxial σ_yy = s: s at the bottom of the bore (x = 0), 0 at (x, 0), s·cos²φ between; the
    # axial stress σ_zz never enters (n has no z part).
    s = -3e8
    sig = np.zeros(9)
    sig[4], sig[8] = s, 1e9
    phis = np.linspace(0.0, np.pi, 13)
    pts = np.stack([0.01 * np.sin(phis), -0.01 * np.cos(phis), np.full_like(phis, 0.004)], axis=1)
    got = fields.radial_normal_stress(pts, np.tile(sig, (len(phis), 1)))
    check(np.allclose(got, s * np.cos(phis) ** 2, rtol=1e-12, atol=1e-6), f"uniaxial: {got}")
    # Invariance: rotating the tensor with the point about z keeps σ_rr; a random symmetric
    # tensor against the formula written out, n = (x, y)/r.
    A = rng.normal(size=(3, 3))
    S = A + A.T
    x, y = 0.003, -0.004
    r = np.hypot(x, y)
    n = np.array([x / r, y / r, 0.0])
    want = n @ S @ n
    for t in np.linspace(0.0, 2 * np.pi, 7):
        R = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
        p = R @ np.array([x, y, 0.02])
        got = fields.radial_normal_stress(p[None, :], (R @ S @ R.T).reshape(1, 9))[0]
        check(abs(got - want) <= 1e-12 * np.abs(S).max(), f"rotated by {t}: {got} != {want}")
    # Row by row: σ_xy and σ_yx may differ in a file; n·σ·n uses both halves.
    sig = np.zeros(9)
    sig[1], sig[3] = 2.0, 0.0
    got = fields.radial_normal_stress(np.array([[1.0, 1.0, 0.0]]), sig[None, :])[0]
    check(abs(got - 1.0) < 1e-14, f"xy only: {got}")  # n = (1, 1)/√2: 2·(1/2)


def grid_array():
    g = vtk.vtkUnstructuredGrid()
    p = vtk.vtkPoints()
    for xyz in ([0.0, -0.01, 0.0], [0.01, 0.0, 0.0]):
        p.InsertNextPoint(*xyz)
    g.SetPoints(p)
    check(not fields.add_radial_normal_stress(g), "no stress array: False")
    a = vtk.vtkDoubleArray()
    a.SetName("stress")
    a.SetNumberOfComponents(9)
    a.InsertNextTuple([0, 0, 0, 0, -7e7, 0, 0, 0, 0])
    a.InsertNextTuple([0, 0, 0, 0, -7e7, 0, 0, 0, 0])
    g.GetPointData().AddArray(a)
    check(fields.add_radial_normal_stress(g), "with stress: True")
    got = vtk_to_numpy(g.GetPointData().GetArray("radial_normal_stress"))
    check(np.allclose(got, [-7e7, 0.0], atol=1e-6), f"grid array: {got}")


def cut_picture(tmp):
    """The stand-in FE stage's fields, drawn with --cut; then without the stress array."""
    fake = os.path.join(ROOT, "tests", "data", "fake_stages", "fake_fe_stage.py")
    scene = os.path.join(tmp, "mis.yaml")
    with open(scene, "w") as f:
        json.dump({"study": "misalignment", "misalignment": {"theta_deg": 1.0},
                   "loading": {"journal": "core"}}, f)
    case = os.path.join(tmp, "case")
    os.makedirs(case)
    env = dict(os.environ, CLEARJOINT_FAKE_FIELDS="1")
    r = subprocess.run([sys.executable, fake, scene, "--output", case], env=env,
                       capture_output=True, text=True)
    check(r.returncode == 0, "stand-in FE stage: " + r.stderr)
    srr = fields.read_grid(fields.last_field_file(case))
    check(fields.add_radial_normal_stress(srr), "stand-in fields have the stress tensor")
    vm = vtk_to_numpy(srr.GetPointData().GetArray("von_mises_stress"))
    rr = vtk_to_numpy(srr.GetPointData().GetArray("radial_normal_stress"))
    # float32 in the file: 1e-6 relative of the largest stress
    check(np.allclose(rr, -vm, atol=1e-6 * vm.max()), "the stand-in's σ_rr = −von Mises")
    plot = os.path.join(ROOT, "scripts", "plot.py")
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run") is None:
        print("SKIP the picture: no $DISPLAY and no xvfb-run")
        return
    png = os.path.join(tmp, "fig7.png")
    r = subprocess.run([sys.executable, plot, "fields", case, "--cut", "--output", png],
                       capture_output=True, text=True)
    check(r.returncode == 0 and os.path.getsize(png) > 10000, f"--cut: {r.returncode} {r.stderr}")
    reader = vtk.vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    dims = reader.GetOutput().GetDimensions()
    check(dims[0] == 1400 and dims[1] == 560, f"two panels, 1400 x 560: {dims}")
    started_pictures(tmp, case, png)
    # Without the stress tensor: exit 1 naming the array, no picture.
    grid = fields.read_grid(fields.last_field_file(case))
    grid.GetPointData().RemoveArray("stress")
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(fields.last_field_file(case))
    w.SetInputData(grid)
    w.Write()
    png2 = os.path.join(tmp, "none.png")
    r = subprocess.run([sys.executable, plot, "fields", case, "--cut", "--output", png2],
                       capture_output=True, text=True)
    check(r.returncode == 1 and "'stress'" in r.stderr and not os.path.exists(png2),
          f"no stress tensor: {r.returncode} {r.stderr}")


def started_pictures(tmp, case, png_alone):
    """The report starts its pictures when it begins (_report_fe.start_pictures) and each
    section waits for its own (render_picture): the same file as `plot.py fields --cut` alone,
    and a failed picture's reason from the renderer's stderr."""
    law = os.path.join(tmp, "law.json")
    with open(law, "w") as f:
        json.dump({}, f)
    sweep = {"name": "misalignment", "parameter": "theta", "unit": "deg",
             "cases": [{"value": 1.0, "fe_dir": case, "law": law}]}
    run_dir = os.path.join(tmp, "run")
    _report_fe.start_pictures([sweep], run_dir)
    fig7a = os.path.join(run_dir, "pictures", "misalignment_fig7a.png")
    check(fig7a in _report_fe._STARTED_PICTURES, f"Fig. 7a started: {_report_fe._STARTED_PICTURES}")
    fs = _report_fe.FeSweep(sweep)
    png, args = _report_fe.fig7_picture(fs, run_dir, fs.cases[0][0], fs.cases[0][2], 1.0, "a")
    check(png == fig7a and args is not None, f"the section asks for the started one: {png}")
    ok, err = _report_fe.render_picture(png, args)
    check(ok and fig7a not in _report_fe._STARTED_PICTURES, f"rendered and collected: {err}")
    with open(png_alone, "rb") as a, open(fig7a, "rb") as b:
        # The title differs (the report names the sweep), so compare the size only.
        check(len(b.read()) > 10000 and len(a.read()) > 10000, "both pictures written")
    # A case without fields: not started ahead, rendered on demand, fails with the reason.
    bad = os.path.join(run_dir, "pictures", "none.png")
    ok, err = _report_fe.render_picture(bad, [os.path.join(tmp, "no_such_case"), "--cut",
                                              "--output", bad])
    check(not ok and err.strip() and not os.path.exists(bad), f"a failed picture: {ok} {err}")


def main():
    tensors()
    grid_array()
    with tempfile.TemporaryDirectory() as tmp:
        cut_picture(tmp)
    print("radial_stress_test: ok")


if __name__ == "__main__":
    main()
