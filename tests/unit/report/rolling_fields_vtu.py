"""Tiny rolling-study fields for the tests of the principal-strain map (Fig. 11): one bearing
hexahedron and one journal hexahedron at the bottom of the bore, each in its own frame as
fe_stage writes them (the journal as meshed, its axis at (0, −c_r)), z from the mid-plane 0 to
L/2 (the rolling study's half model), with constant fields per body, written with VTK as
fields/solution.pvd + one .vtu. Used by rolling_strains_test.py and rolling_section_test.py.
"""
import math
import os

import numpy as np

R_B, C_R, T_B, HALF_L = 0.01, 0.0005, 0.004, 0.01  # [m]
R_J = R_B - C_R
HALF_ANGLE = math.radians(10.0)  # each cell spans ±10° about the bottom of its body's axis
# (principal strains 1, 2, 3, equivalent plastic strain) per body [1]
BEARING = (1.0e-3, 0.0, -2.0e-3, 1.5e-3)
JOURNAL = (3.0e-3, 1.0e-4, -4.0e-3, 0.0)


def ring_cell_points(centre_y, r_in, r_out):
    """The 8 corners (VTK hexahedron order) of a ring sector about (0, centre_y), ±HALF_ANGLE
    about −y, z from 0 to HALF_L [m]."""
    def at(r, a, z):
        return (r * math.sin(a), centre_y - r * math.cos(a), z)
    return [at(r_in, -HALF_ANGLE, 0), at(r_out, -HALF_ANGLE, 0), at(r_out, HALF_ANGLE, 0),
            at(r_in, HALF_ANGLE, 0), at(r_in, -HALF_ANGLE, HALF_L), at(r_out, -HALF_ANGLE, HALF_L),
            at(r_out, HALF_ANGLE, HALF_L), at(r_in, HALF_ANGLE, HALF_L)]


def write_fields(folder, t, material_id=False, journal=True, principal=True):
    """fields/ in `folder` with the last increment at time t [s]. material_id: write the cells'
    material id (0 bearing, 1 journal) as fe_stage may; journal False: a rigid journal (the
    bearing only); principal False: no principal strains (nor strain tensor)."""
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk
    pts = vtk.vtkPoints()
    grid = vtk.vtkUnstructuredGrid()
    values = {"principal_strain_1": [], "principal_strain_2": [], "principal_strain_3": [],
              "equivalent_plastic_strain": [], "contact_active": []}
    cells = [(ring_cell_points(0.0, R_B, R_B + T_B), BEARING, 0)]
    if journal:
        cells.append((ring_cell_points(-C_R, 0.8 * R_J, R_J), JOURNAL, 1))
    ids_material = []
    for corners, vals, mat in cells:
        hexa = vtk.vtkHexahedron()
        for i, p in enumerate(corners):
            hexa.GetPointIds().SetId(i, pts.InsertNextPoint(*p))  # each cell its own points
            for name, v in zip(("principal_strain_1", "principal_strain_2", "principal_strain_3",
                                "equivalent_plastic_strain"), vals):
                values[name].append(v)
            # the bore's points (the mortar slaves) in contact: the bearing's inner face
            inner = mat == 0 and abs(math.hypot(p[0], p[1]) - R_B) < 1e-9
            values["contact_active"].append(1.0 if inner else 0.0)
        grid.InsertNextCell(hexa.GetCellType(), hexa.GetPointIds())
        ids_material.append(mat)
    grid.SetPoints(pts)
    for name, vals in values.items():
        if name.startswith("principal") and not principal:
            continue
        a = numpy_to_vtk(np.array(vals, dtype=np.float32), deep=True)
        a.SetName(name)
        grid.GetPointData().AddArray(a)
    disp = numpy_to_vtk(np.zeros((pts.GetNumberOfPoints(), 3), dtype=np.float32), deep=True)
    disp.SetName("displacement")
    grid.GetPointData().AddArray(disp)
    if material_id:
        a = numpy_to_vtk(np.array(ids_material, dtype=np.float32), deep=True)
        a.SetName("material_id")
        grid.GetCellData().AddArray(a)
    os.makedirs(os.path.join(folder, "fields"), exist_ok=True)
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(os.path.join(folder, "fields", "solution_0001.vtu"))
    w.SetInputData(grid)
    w.Write()
    with open(os.path.join(folder, "fields", "solution.pvd"), "w") as f:
        f.write('<?xml version="1.0"?><VTKFile type="Collection" version="0.1"><Collection>'
                '<DataSet timestep="0" group="" part="0" file="solution_0000.vtu"/>'
                f'<DataSet timestep="{t!r}" group="" part="0" file="solution_0001.vtu"/>'
                '</Collection></VTKFile>')


def write_history(folder, rows):
    """A minimal rolling_history.csv: rows of (time [s], delta [m], phi [rad], gamma [rad])."""
    with open(os.path.join(folder, "rolling_history.csv"), "w") as f:
        f.write("# units: s,m,rad,rad\ntime,delta,phi,gamma\n")
        for r in rows:
            f.write(",".join(repr(float(x)) for x in r) + "\n")
        f.write("# status: complete\n")


def write_manifest(folder):
    import json
    with open(os.path.join(folder, "manifest.json"), "w") as f:
        json.dump({"extra": {"scene": {"geometry": {"R_B": R_B, "c_r": C_R, "t_B": T_B,
                                                    "L_B": 2 * HALF_L}}}}, f)
