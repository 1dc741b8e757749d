#!/usr/bin/python3
"""The report's numbers from the FE fields (scripts/plotting/fields.py field_stats): volume above
the yield stress, largest von Mises stress, and the contact-field checks, on a VTU written here
with known values: two unit-size hexahedra (1 mm cubes) side by side, von Mises 300 MPa at
every point of the first and 100 MPa at the second; a quarter model (symmetry factor 4).

    field_stats_test.py
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))

import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util.numpy_support import numpy_to_vtk  # noqa: E402

from plotting import fields  # noqa: E402


def write_case(d):
    h = 1e-3  # [m]
    pts = vtk.vtkPoints()
    ug = vtk.vtkUnstructuredGrid()
    cells_vm, cells_p, cells_active, cells_shear, cells_status, cells_slip = [], [], [], [], [], []
    # contact_status in fe_stage's (Abaqus's) codes: 0 open, 1 slip, 2 stick; a frictionless
    # run's contact points slip (1)
    for c, (vm, p, active, shear, status, slip) in enumerate([(300e6, 50e6, 1, 0.0, 1, 1e-7),
                                                              (100e6, 0.0, 0, 0.0, 0, 0.0)]):
        ids = []
        for (x, y, z) in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                          (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]:
            ids.append(pts.InsertNextPoint((x + c) * h, y * h, z * h))  # patches: own points
            cells_vm.append(vm)
            cells_p.append(p)
            cells_active.append(active)
            cells_shear.append(shear)
            cells_status.append(status)
            cells_slip.append(slip)
        hexa = vtk.vtkHexahedron()
        for i, pid in enumerate(ids):
            hexa.GetPointIds().SetId(i, pid)
        ug.InsertNextCell(hexa.GetCellType(), hexa.GetPointIds())
    ug.SetPoints(pts)
    for name, vals in [("von_mises_stress", cells_vm), ("contact_pressure", cells_p),
                       ("contact_active", cells_active), ("contact_shear", cells_shear),
                       ("contact_status", cells_status), ("contact_slip", cells_slip)]:
        a = numpy_to_vtk(np.array(vals, dtype=float), deep=True)
        a.SetName(name)
        ug.GetPointData().AddArray(a)
    os.makedirs(os.path.join(d, "fields"))
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(os.path.join(d, "fields", "solution_0001.vtu"))
    w.SetInputData(ug)
    w.Write()
    with open(os.path.join(d, "fields", "solution.pvd"), "w") as f:
        f.write('<?xml version="1.0"?><VTKFile type="Collection" version="0.1"><Collection>'
                '<DataSet timestep="0" group="" part="0" file="missing_0000.vtu"/>'
                '<DataSet timestep="5e-05" group="" part="0" file="solution_0001.vtu"/>'
                '</Collection></VTKFile>')


def main():
    bad = 0
    with tempfile.TemporaryDirectory() as d:
        write_case(d)
        s = fields.field_stats(d, yield_stress=168.2e6, symmetry_factor=4.0, mu=0.0)

        # 1e-6: the points are single precision (VTK's default, as deal.II writes them): a 1 mm
        # edge carries ~1e-7 relative error, a volume three times that
        def near(a, b, what, rel=1e-6):
            nonlocal bad
            if not abs(a - b) <= rel * abs(b):
                print(f"FAIL: {what}: {a} != {b}")
                bad += 1
        near(s["max_von_mises"], 300e6, "max von Mises")
        near(s["volume_above_yield"], 4 * 1e-9, "volume above yield (one 1 mm³ cell × 4)")
        near(s["volume_total"], 8 * 1e-9, "total volume × 4")
        near(s["max_contact_pressure"], 50e6, "max pressure")
        for key, expected in [("n_cells_above_yield", 1), ("n_active_points", 8),
                              ("n_stick_points", 0),
                              ("n_slip_points_not_in_contact", 0)]:
            if s[key] != expected:
                print(f"FAIL: {key} = {s[key]}, expected {expected}")
                bad += 1
        # the body split by the cell centre's distance from the z axis: the hot cell's centre
        # is at r = 0.71 mm, the cold one's at 1.58 mm
        inside = fields.field_stats(d, 168.2e6, 4.0, 0.0, R_B=1e-3)["volume_above_yield_bearing"]
        outside = fields.field_stats(d, 168.2e6, 4.0, 0.0, R_B=0.5e-3)["volume_above_yield_bearing"]
        if inside != 0.0:
            print("FAIL: the hot cell lies in the bore (journal), bearing volume", inside)
            bad += 1
        near(outside, 4e-9, "bearing volume above yield with the hot cell outside the bore")
        # a manifest that names code 1 'stick' makes the same 8 contact points count as stuck
        relabelled = fields.field_stats(d, 168.2e6, 4.0, 0.0, stick_code=1)["n_stick_points"]
        if relabelled != 8:
            print("FAIL: with stick_code 1 the 8 contact points should count as stuck:", relabelled)
            bad += 1
        if not s["file"].endswith("solution_0001.vtu"):
            print("FAIL: the last increment of the .pvd was not the one read:", s["file"])
            bad += 1
    print("ok" if not bad else f"{bad} failures")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
