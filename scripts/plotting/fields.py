"""Pictures of an FE case's fields, rendered off-screen from its VTU files with VTK (Debian's
python3-vtk9) — the counterpart of the paper's Fig. 7 — and the numbers the report needs from
the fields (largest von Mises stress, volume above a yield stress, contact-field checks).

    plot.py fields FE_DIR --output OUT.png [--yield-stress PA] [--title TEXT] [--cut]

FE_DIR is an fe_stage case folder (fields/solution.pvd and manifest.json); the last increment
is drawn. Three panels: the mesh (output patches: each Q2 cell is written as 2×2×2 sub-cells),
von Mises stress on the x = 0 symmetry plane near the contact (the paper's side cut, Fig. 7;
black line: the yield stress), and the contact pressure on the bearing's bore seen from the
axis (the journal removed). With --cut: the paper's Fig. 7 itself, the radial normal stress
σ_rr = n·σ·n (n radial from the bearing's axis; from the 9-component `stress` array) beside
von Mises, both on the x = 0 plane near the contact. VTK 9.1 from Debian renders through X: without $DISPLAY the script
runs itself again under xvfb-run (Debian package xvfb).
"""
import argparse
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

# SPEC §2: the first point of the hardening table, the yield stress the paper's steel starts
# yielding at; the FE model stays linear elastic, so stresses above it mean the model is no
# longer what it claims to be there.
DEFAULT_YIELD_STRESS = 168.2e6  # [Pa]


def last_field_entry(fe_dir):
    """(timestep, path) of the last increment named in fields/solution.pvd, or None when there
    is no .pvd or its last file is missing. The timestep is what fe_stage wrote: the push δ [m]
    in the quasi-static studies, the time t [s] in the rolling and impact studies."""
    pvd = os.path.join(fe_dir, "fields", "solution.pvd")
    if not os.path.exists(pvd):
        return None
    sets = ET.parse(pvd).getroot().iter("DataSet")
    best = None
    for s in sets:
        t = float(s.get("timestep", "0"))
        if best is None or t >= best[0]:
            best = (t, s.get("file"))
    if best is None:
        return None
    path = best[1] if os.path.isabs(best[1]) else os.path.join(os.path.dirname(pvd), best[1])
    return (best[0], path) if os.path.exists(path) else None


def last_field_file(fe_dir):
    """The .pvtu/.vtu of the last increment named in fields/solution.pvd, or None."""
    entry = last_field_entry(fe_dir)
    return entry[1] if entry else None


def read_grid(path):
    import vtk
    reader = vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") \
        else vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    # deal.II writes every cell's points separately (discontinuous patches: the stress jumps
    # between cells), so the surface filter also returns the faces between cells; they lie
    # inside the body, hidden by the depth test, and keeping the patches unmerged keeps each
    # cell's own stress (VTK 9.1 from Debian has no unstructured-grid cleaner anyway).
    return reader.GetOutput()


def _arrays(grid):
    from vtk.util.numpy_support import vtk_to_numpy
    pd = grid.GetPointData()
    return {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}


def field_stats(fe_dir, yield_stress=DEFAULT_YIELD_STRESS, symmetry_factor=1.0, mu=None,
                stick_code=2, R_B=None):
    """Numbers from the last increment's fields, for the report's warnings:
    max_von_mises [Pa]; volume_above_yield [m³] of the FULL body (modelled part × symmetry
    factor) with the cell value taken as the mean of its points; contact checks: for a
    frictionless run (mu == 0) the largest contact_shear [Pa] and its ratio to the pressure, the
    number of active points whose status says stick (code `stick_code`: 2 in fe_stage's
    open/slip/stick = 0/1/2, or what the manifest's contact_fields.status_codes says), and the
    number of points with slip where not in contact. With R_B [m], volume_above_yield_bearing
    is the part in cells whose centre lies outside the bore (the bearing; the journal's cells
    lie inside). None if there are no fields."""
    path = last_field_file(fe_dir)
    if path is None:
        return None
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    grid = read_grid(path)
    a = _arrays(grid)
    out = {"file": path, "yield_stress": yield_stress}
    if "von_mises_stress" in a:
        vm = a["von_mises_stress"]
        out["max_von_mises"] = float(np.max(vm))
        cell_vm = vtk.vtkPointDataToCellData()
        cell_vm.SetInputData(grid)
        cell_vm.Update()
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputConnection(cell_vm.GetOutputPort())
        sizes.ComputeVolumeOn()
        sizes.ComputeAreaOff()
        sizes.ComputeLengthOff()
        sizes.ComputeVertexCountOff()
        sizes.Update()
        g = sizes.GetOutput()
        vol = vtk_to_numpy(g.GetCellData().GetArray("Volume"))
        cvm = vtk_to_numpy(g.GetCellData().GetArray("von_mises_stress"))
        above = cvm > yield_stress
        out["volume_above_yield"] = float(np.sum(vol[above])) * symmetry_factor
        out["volume_total"] = float(np.sum(vol)) * symmetry_factor
        out["n_cells_above_yield"] = int(np.sum(above))
        centres = vtk.vtkCellCenters()
        centres.SetInputData(g)
        centres.Update()
        call = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())
        if R_B is not None:
            in_bearing = np.hypot(call[:, 0], call[:, 1]) >= R_B
            out["volume_above_yield_bearing"] = float(np.sum(vol[above & in_bearing])) * symmetry_factor
        if np.any(above):
            c = call[above]
            out["above_yield_box"] = [c.min(axis=0).tolist(), c.max(axis=0).tolist()]
    if "contact_pressure" in a and "contact_active" in a:
        p, active = a["contact_pressure"], a["contact_active"] > 0.5
        out["n_active_points"] = int(np.sum(active))
        out["max_contact_pressure"] = float(np.max(p)) if p.size else 0.0
        if "contact_shear" in a:
            s = a["contact_shear"]
            out["max_contact_shear"] = float(np.max(s)) if s.size else 0.0
            ratio = s[active] / np.maximum(p[active], 1e-30) if np.any(active) else np.zeros(0)
            out["max_shear_over_pressure"] = float(np.max(ratio)) if ratio.size else 0.0
        if "contact_status" in a:
            st = a["contact_status"]
            out["n_stick_points"] = int(np.sum(active & (np.rint(st) == stick_code)))
        if "contact_slip" in a:
            slip = a["contact_slip"] > 0
            out["n_slip_points"] = int(np.sum(slip))
            out["n_slip_points_not_in_contact"] = int(np.sum(slip & ~active))
    out["mu"] = mu
    return out


def _bearing_only(grid, R_B):
    """Cells whose centre lies outside the bore (r ≥ R_B from the z axis): the bearing. The
    journal's cells lie inside; with a rigid journal there are none."""
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    centres = vtk.vtkCellCenters()
    centres.SetInputData(grid)
    centres.Update()
    c = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())
    r = np.hypot(c[:, 0], c[:, 1])
    ids = vtk.vtkIdList()
    for i in np.nonzero(r >= R_B)[0]:
        ids.InsertNextId(int(i))
    ex = vtk.vtkExtractCells()
    ex.SetInputData(grid)
    ex.SetCellList(ids)
    ex.Update()
    return ex.GetOutput()


def _surface(data):
    import vtk
    s = vtk.vtkDataSetSurfaceFilter()
    s.SetInputData(data)
    s.Update()
    return s.GetOutput()


def _lut(lo, hi, title_unit_scale):
    import vtk
    lut = vtk.vtkLookupTable()
    lut.SetHueRange(0.667, 0.0)  # blue (low) → red (high), as ParaView/Abaqus users expect
    lut.SetTableRange(lo, hi)
    lut.SetBelowRangeColor(0.85, 0.85, 0.85, 1.0)
    lut.UseBelowRangeColorOn()
    lut.Build()
    return lut


def _scaled_copy(poly, name, scale):
    """A copy of poly with point array `name` × scale set active (MPa for the colour bar)."""
    import vtk
    from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    out = vtk.vtkPolyData()
    out.DeepCopy(poly)
    arr = out.GetPointData().GetArray(name)
    if arr is None:
        return None
    v = numpy_to_vtk(vtk_to_numpy(arr) * scale, deep=True)
    v.SetName(name + "_shown")
    out.GetPointData().AddArray(v)
    out.GetPointData().SetActiveScalars(name + "_shown")
    return out


def _text(ren, text, size=14, top=False):
    import vtk
    t = vtk.vtkTextActor()
    t.SetInput(text)
    t.GetTextProperty().SetFontSize(size)
    t.GetTextProperty().SetColor(0, 0, 0)
    t.GetTextProperty().SetBackgroundColor(1, 1, 1)
    t.GetTextProperty().SetBackgroundOpacity(0.85)
    if top:
        t.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
        t.GetPositionCoordinate().SetValue(0.02, 0.90)
    else:
        t.SetPosition(8, 8)
    ren.AddActor2D(t)


def _title(ren, title, height):
    """The picture's title in the top left corner of `ren` (nothing when empty)."""
    import vtk
    if not title:
        return
    t = vtk.vtkTextActor()
    t.SetInput(title)
    t.GetTextProperty().SetFontSize(16)
    t.GetTextProperty().SetColor(0, 0, 0)
    t.SetPosition(8, height - 26)
    ren.AddActor2D(t)


def _bar(ren, lut, title):
    import vtk
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(5)
    bar.SetLabelFormat("%.0f")
    bar.SetOrientationToHorizontal()
    bar.SetWidth(0.8)
    bar.SetHeight(0.11)
    bar.SetPosition(0.1, 0.01)
    for p in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        p.SetColor(0, 0, 0)
        p.SetFontSize(12)
        p.ItalicOff()
        p.BoldOff()
    bar.UnconstrainedFontSizeOn()
    ren.AddActor2D(bar)


def radial_normal_stress(points, stress):
    """σ_rr = n·σ·n [Pa] at each point, n the unit vector from the bearing's axis (the z axis)
    to the point in its cross-section, n = (x, y, 0)/√(x² + y²): the paper's Fig. 7 "normal
    stress along the radial direction". points: (N, 3) [m]; stress: (N, 9), the tensor row by
    row as fe_stage writes it (σ_xx, σ_xy, σ_xz, σ_yx, …). On the axis itself (r < 1e-12 m, the
    journal's centre line, far from the contact) n is undefined and −y, the push direction,
    is taken."""
    import numpy as np
    p = np.asarray(points, dtype=float)
    sig = np.asarray(stress, dtype=float).reshape(-1, 3, 3)
    r = np.hypot(p[:, 0], p[:, 1])
    n = np.zeros((len(p), 3))
    on_axis = r < 1e-12
    n[~on_axis, 0] = p[~on_axis, 0] / r[~on_axis]
    n[~on_axis, 1] = p[~on_axis, 1] / r[~on_axis]
    n[on_axis, 1] = -1.0
    return np.einsum("ni,nij,nj->n", n, sig, n)


def add_radial_normal_stress(grid):
    """Adds the point array `radial_normal_stress` [Pa] (radial_normal_stress() of the grid's
    9-component `stress`); False when the grid has no such stress array."""
    import vtk  # noqa: F401
    from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    arr = grid.GetPointData().GetArray("stress")
    if arr is None or arr.GetNumberOfComponents() != 9:
        return False
    srr = radial_normal_stress(vtk_to_numpy(grid.GetPoints().GetData()), vtk_to_numpy(arr))
    v = numpy_to_vtk(srr.astype(float), deep=True)
    v.SetName("radial_normal_stress")
    grid.GetPointData().AddArray(v)
    return True


def _diverging_lut(limit):
    """Blue (compression) – white (0) – red (tension) over [−limit, limit]."""
    import vtk
    ctf = vtk.vtkColorTransferFunction()
    ctf.SetColorSpaceToDiverging()
    ctf.AddRGBPoint(-limit, 0.230, 0.299, 0.754)
    ctf.AddRGBPoint(0.0, 0.865, 0.865, 0.865)
    ctf.AddRGBPoint(limit, 0.706, 0.016, 0.150)
    lut = vtk.vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    lut.SetTableRange(-limit, limit)
    lut.Build()
    for i in range(256):
        c = ctf.GetColor(-limit + 2 * limit * i / 255)
        lut.SetTableValue(i, c[0], c[1], c[2], 1.0)
    return lut


# The cut panels: (array, colour-bar title, words for the panel's caption)
CUT_KINDS = {
    "von_mises": ("von_mises_stress", "von Mises [MPa]", "von Mises"),
    "radial": ("radial_normal_stress", "radial normal stress [MPa]",
               "radial normal stress (blue: compression)"),
}


def _cut_panel(grid, surf, b, R_B, kind, viewport, panel_width, height, yield_stress=None):
    """A renderer with `kind` (CUT_KINDS) on the x = 0 plane near the contact (bottom of the
    bore), seen from −x: horizontal z (the axial direction), vertical y; the whole axial extent
    and the wall below the bore with a little of the journal above it. von Mises on a rainbow
    scale from 0 with the yield stress as a black line; the radial normal stress on a diverging
    scale symmetric about 0."""
    import vtk
    array, bar_title, words = CUT_KINDS[kind]
    r2 = vtk.vtkRenderer()
    r2.SetViewport(viewport[0], 0.0, viewport[1], 1.0)
    r2.SetBackground(1, 1, 1)
    # keep the wall below the bore and a band above it (the journal's rim, if meshed): above
    # that a half model would show the far side of the bore through the open plane
    t_wall = -b[2] - R_B
    y_cut = -R_B + 0.75 * t_wall
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.0, y_cut, 0.0)
    plane.SetNormal(0.0, -1.0, 0.0)
    clip = vtk.vtkClipPolyData()
    clip.SetInputData(surf)
    clip.SetClipFunction(plane)
    clip.Update()
    vm = _scaled_copy(clip.GetOutput(), array, 1e-6)
    shown = array + "_shown"
    if vm is not None:
        lo, hi = vm.GetPointData().GetArray(shown).GetRange()
        if kind == "radial":
            # symmetric about 0 at the 95th percentile of |σ_rr| over the cut's points (they
            # crowd where the mesh is refined): the deformable rim is a corner whose peak grows
            # with the mesh and would wash the rest out; the bar states the peak
            import numpy as np
            from vtk.util.numpy_support import vtk_to_numpy
            vals = np.abs(vtk_to_numpy(vm.GetPointData().GetArray(shown)))
            limit = max(float(np.percentile(vals, 95.0)) if vals.size else 0.0, 1e-9)
            peak = float(vals.max()) if vals.size else 0.0
            if peak > limit * (1 + 1e-9):
                bar_title = f"{bar_title}, saturated beyond +-{limit:.0f} (peak {peak:.0f})"
            lut, lo, hi = _diverging_lut(limit), -limit, limit
        else:
            lo, hi = 0.0, max(hi, 1e-9)
            lut = _lut(lo, hi, 1e-6)
        mv = vtk.vtkPolyDataMapper()
        mv.SetInputData(vm)
        mv.SetLookupTable(lut)
        mv.SetScalarRange(lo, hi)
        mv.SetScalarModeToUsePointData()
        mv.InterpolateScalarsBeforeMappingOn()
        av = vtk.vtkActor()
        av.SetMapper(mv)
        r2.AddActor(av)
        if kind == "von_mises" and yield_stress is not None and hi > yield_stress * 1e-6:
            cont = vtk.vtkContourFilter()
            cont.SetInputData(vm)
            cont.SetInputArrayToProcess(0, 0, 0, 0, shown)
            cont.SetValue(0, yield_stress * 1e-6)
            cm = vtk.vtkPolyDataMapper()
            cm.SetInputConnection(cont.GetOutputPort())
            cm.ScalarVisibilityOff()
            ca = vtk.vtkActor()
            ca.SetMapper(cm)
            ca.GetProperty().SetColor(0, 0, 0)
            ca.GetProperty().SetLineWidth(1.5)
            r2.AddActor(ca)
        _bar(r2, lut, bar_title)
    cam = r2.GetActiveCamera()
    cam.ParallelProjectionOn()
    z_ext = b[5] - b[4]
    zc = 0.5 * (b[4] + b[5])
    aspect = panel_width / height
    # parallel scale = half the visible height; the strip is wider than tall
    half = max(0.5 * 1.08 * z_ext / aspect, 0.5 * 1.3 * (y_cut - b[2]))
    yc = 0.5 * (y_cut + b[2]) - 0.12 * half  # a little low: the colour bar sits below
    cam.SetFocalPoint(0.0, yc, zc)
    cam.SetPosition(-1.0, yc, zc)
    cam.SetViewUp(0, 1, 0)
    cam.SetParallelScale(half)
    r2.ResetCameraClippingRange()
    line = (f"; black line: {yield_stress / 1e6:.4g} MPa"
            if kind == "von_mises" and yield_stress is not None else "")
    _text(r2, f"{words} on the plane x = 0 (z across, y up){line}"
          if vm is not None else f"no {array} in the fields", top=True)
    return r2


def render_cut(fe_dir, out_png, R_B, yield_stress=DEFAULT_YIELD_STRESS, title="", width=1400,
               height=560):
    """The paper's Fig. 7 cut: the radial normal stress and von Mises side by side on the x = 0
    plane near the contact. Returns False (and says why) without fields or without the
    9-component `stress` array."""
    path = last_field_file(fe_dir)
    if path is None:
        print(f"fields: {fe_dir}: no fields/solution.pvd with an existing last increment",
              file=sys.stderr)
        return False
    import vtk
    grid = read_grid(path)
    if not add_radial_normal_stress(grid):
        print(f"fields: {path}: no 9-component 'stress' array: cannot compute the radial "
              "normal stress", file=sys.stderr)
        return False
    surf = _surface(grid)
    b = grid.GetBounds()
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(width, height)
    win.SetMultiSamples(0)
    left = _cut_panel(grid, surf, b, R_B, "radial", (0.0, 0.5), width / 2, height)
    win.AddRenderer(left)
    win.AddRenderer(_cut_panel(grid, surf, b, R_B, "von_mises", (0.5, 1.0), width / 2, height,
                               yield_stress))
    _title(left, title, height)
    _write_png(win, out_png)
    return True


def _write_png(win, out_png):
    import vtk
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtk.vtkPNGWriter()
    tmp = out_png + ".tmp.png"
    writer.SetFileName(tmp)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    os.replace(tmp, out_png)


def render(fe_dir, out_png, R_B, yield_stress=DEFAULT_YIELD_STRESS, title="", width=1650,
           height=560):
    """Writes the three-panel picture; returns False (and says why) if there are no fields."""
    path = last_field_file(fe_dir)
    if path is None:
        print(f"fields: {fe_dir}: no fields/solution.pvd with an existing last increment",
              file=sys.stderr)
        return False
    import vtk
    grid = read_grid(path)
    surf = _surface(grid)
    b = grid.GetBounds()  # x0 x1 y0 y1 z0 z1 [m]
    zc = 0.5 * (b[4] + b[5])

    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(width, height)
    win.SetMultiSamples(0)

    # (a) mesh: the whole modelled part, isometric, patches drawn with their edges
    r1 = vtk.vtkRenderer()
    r1.SetViewport(0.0, 0.0, 1 / 3, 1.0)
    r1.SetBackground(1, 1, 1)
    m = vtk.vtkPolyDataMapper()
    m.SetInputData(surf)
    m.ScalarVisibilityOff()
    act = vtk.vtkActor()
    act.SetMapper(m)
    act.GetProperty().SetColor(0.78, 0.82, 0.88)
    act.GetProperty().EdgeVisibilityOn()
    act.GetProperty().SetEdgeColor(0.2, 0.2, 0.25)
    act.GetProperty().SetLineWidth(0.5)
    r1.AddActor(act)
    cam = r1.GetActiveCamera()
    cx, cy = 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3])
    size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
    cam.SetFocalPoint(cx, cy, zc)
    cam.SetPosition(cx - 1.6 * size, cy + 1.0 * size, zc + 2.2 * size)
    cam.SetViewUp(0, 1, 0)
    r1.ResetCamera()
    cam.Zoom(0.85)
    _text(r1, "mesh (output patches), reference configuration")
    win.AddRenderer(r1)

    # (b) von Mises on the x = 0 plane near the contact (bottom of the bore), seen from −x
    win.AddRenderer(_cut_panel(grid, surf, b, R_B, "von_mises", (1 / 3, 2 / 3), width / 3, height,
                               yield_stress))

    # (c) contact pressure on the bore, journal removed, seen from the axis looking −y, framed
    # on the points in contact (undeformed positions: deal.II writes the reference mesh)
    r3 = vtk.vtkRenderer()
    r3.SetViewport(2 / 3, 0.0, 1.0, 1.0)
    r3.SetBackground(1, 1, 1)
    bearing = _surface(_bearing_only(grid, R_B))
    cp = _scaled_copy(bearing, "contact_pressure", 1e-6)
    frame = None
    if cp is not None:
        import numpy as np
        from vtk.util.numpy_support import vtk_to_numpy
        vals = vtk_to_numpy(cp.GetPointData().GetArray("contact_pressure_shown"))
        pts = vtk_to_numpy(cp.GetPoints().GetData())
        hi = float(vals.max()) if vals.size else 0.0
        if hi > 0:
            on = pts[vals > 0]
            frame = (on[:, 0].min(), on[:, 0].max(), on[:, 2].min(), on[:, 2].max())
        # zero pressure (no contact) in grey: below a tiny positive threshold
        lut = _lut(max(hi, 1e-9) * 1e-6, max(hi, 1e-9), 1e-6)
        mc = vtk.vtkPolyDataMapper()
        mc.SetInputData(cp)
        mc.SetLookupTable(lut)
        mc.SetScalarRange(max(hi, 1e-9) * 1e-6, max(hi, 1e-9))
        mc.UseLookupTableScalarRangeOn()
        mc.InterpolateScalarsBeforeMappingOn()
        ac = vtk.vtkActor()
        ac.SetMapper(mc)
        ac.GetProperty().EdgeVisibilityOn()
        ac.GetProperty().SetEdgeColor(0.45, 0.45, 0.45)
        ac.GetProperty().SetLineWidth(0.5)
        r3.AddActor(ac)
        _bar(r3, lut, "contact pressure [MPa]")
    cam = r3.GetActiveCamera()
    cam.ParallelProjectionOn()
    if frame is None:
        frame = (b[0], min(b[1], 0.3 * R_B), b[4], b[5])
    x0, x1, z0, z1 = frame
    # at least 2 mm (or a fifth of the bore radius) around the patch; the patch may be a line
    pad = max(0.2 * R_B, 0.5 * max(x1 - x0, z1 - z0))
    x0, x1, z0, z1 = max(b[0], x0 - pad), min(b[1], x1 + pad), max(b[4], z0 - pad), min(b[5], z1 + pad)
    fx, fz = 0.5 * (x0 + x1), 0.5 * (z0 + z1)
    half = 0.5 * max(x1 - x0, z1 - z0) * 1.15
    y_at = -math.sqrt(max(R_B ** 2 - fx ** 2, 0.0))
    # horizontal z, vertical x; shifted so the lowest part stays free for the colour bar
    cam.SetFocalPoint(fx - 0.2 * half, y_at, fz)
    cam.SetPosition(fx - 0.2 * half, y_at + R_B, fz)
    cam.SetViewUp(1, 0, 0)
    cam.SetParallelScale(half)
    r3.ResetCameraClippingRange()
    _text(r3, "contact pressure on the bore seen from the axis\n(horizontal z, vertical x; grey: no contact)", top=True)
    win.AddRenderer(r3)

    _title(r1, title, height)

    _write_png(win, out_png)
    return True


def needs_virtual_display():
    return not os.environ.get("DISPLAY")


def run_under_xvfb(argv):
    """Runs `plot.py fields ARGS` under xvfb-run; returns its exit code, or None if xvfb-run is
    missing."""
    xvfb = shutil.which("xvfb-run")
    if xvfb is None:
        return None
    plot_py = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "plot.py")
    cmd = [xvfb, "-a", "-s", "-screen 0 1920x1080x24", sys.executable, plot_py, "fields"] + argv
    return subprocess.run(cmd).returncode


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py fields", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fe_dir")
    p.add_argument("--output", required=True)
    p.add_argument("--yield-stress", type=float, default=DEFAULT_YIELD_STRESS,
                   help="[Pa] drawn as a black line on the von Mises panel (default 168.2e6)")
    p.add_argument("--bore-radius", type=float, default=None,
                   help="[m] R_B; default: from the case's manifest (scene geometry)")
    p.add_argument("--title", default="")
    p.add_argument("--cut", action="store_true",
                   help="instead: the paper's Fig. 7 cut, the radial normal stress and von Mises "
                        "on the plane x = 0 (needs the 9-component 'stress' array)")
    a = p.parse_args(argv)
    if needs_virtual_display():
        rc = run_under_xvfb(argv)
        if rc is None:
            print("fields: no $DISPLAY and no xvfb-run (Debian package xvfb): cannot render",
                  file=sys.stderr)
            return 1
        return rc
    R_B = a.bore_radius
    if R_B is None:
        import json
        try:
            with open(os.path.join(a.fe_dir, "manifest.json")) as f:
                R_B = json.load(f)["extra"]["scene"]["geometry"]["R_B"]
        except (OSError, KeyError, ValueError, TypeError):
            print(f"fields: {a.fe_dir}/manifest.json gives no extra.scene.geometry.R_B; "
                  "pass --bore-radius", file=sys.stderr)
            return 1
    try:
        import vtk  # noqa: F401
    except ImportError:
        print("fields: VTK's Python bindings are missing (Debian package python3-vtk9)",
              file=sys.stderr)
        return 1
    draw = render_cut if a.cut else render
    return 0 if draw(a.fe_dir, a.output, R_B, a.yield_stress, a.title) else 1
