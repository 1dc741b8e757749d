"""The rolling study's principal strains at the end, in the bore and the journal (the paper's
§3.4, Fig. 11), from the fe_stage rolling run's last VTU fields.

    scripts/plot.py rolling_strains CASE_DIR --output OUT.png

CASE_DIR is an fe_stage rolling case folder (fields/solution.pvd, rolling_history.csv,
manifest.json). Its last increment is cut at the axial mid-plane — the model's z = 0 symmetry
plane (the rolling study models the whole ring and half the length, z ≥ 0) — and both bodies are
drawn where they are in the fixed frame at that time: fe_stage computes the bearing in its
co-rotating frame and the deformable journal in its own turning frame (docs/fe.md, "Rolling
study"), so a bearing point X with displacement u is drawn at R(φ)(X + u) and a journal point
at c + R(γ)(X − a + u) — φ and γ from rolling_history.csv at the field's time, c = (0, −c_r − δ)
the journal's axis in the fixed frame, a = (0, −c_r) its axis as meshed, rotations about +z
(the displacement at true scale: micrometres on millimetres). Three panels: (a) the whole
mid-plane section with the plastic zone (cells with equivalent_plastic_strain > 0, outlined),
the contact (bore points with contact_active), the material points that touched at t = 0 and
the zoom window; (b) the largest principal strain (tension) and (c) the smallest (compression)
in that window, red tension, blue compression, white zero, the colour bar in 10⁻³ (mm/m), the
plastic zone outlined in black and the contact marked. The largest and smallest principal
strain per body come from the three principal strains (or, without them, from the strain
tensor). With a rigid journal only the bearing has fields; the journal's outline is drawn.

Bodies: by the cells' material id where the fields carry one (0 bearing, 1 journal), otherwise
by the cell centre's distance from the bearing's axis (≥ R_B: the bearing; the journal is
meshed inside the bore). Matplotlib draws the cut (no display needed); VTK (Debian's
python3-vtk9) reads and cuts the fields, with scripts/plotting/fields.py's readers.

Exit 0 with the picture written; 1 when the case has no fields, no principal strains, or VTK
is missing (one line on stderr saying which: the report shows the same as a note).
"""
import argparse
import math
import os
import sys

import numpy as np

from plotting import fields
from plotting._common import read_table

BODY_NAMES = {0: "bearing", 1: "journal"}


# --- geometry (pure numpy: tests/unit/report/rolling_strains_test.py) -------------------------

def rotate_z(xy, angle):
    """Points (N, 2) [m] turned by `angle` [rad] counter-clockwise about +z (the rolling study's
    sense of φ and γ, fe_stage/solve/rolling_kinematics.h rotate_z)."""
    xy = np.asarray(xy, dtype=float)
    c, s = math.cos(angle), math.sin(angle)
    return np.stack([c * xy[..., 0] - s * xy[..., 1], s * xy[..., 0] + c * xy[..., 1]], axis=-1)


def to_fixed_frame(xy, body, phi, gamma, c_r, delta):
    """In-plane positions (N, 2) [m] of points given in their body's frame (X + u) moved to the
    fixed frame: the bearing (body 0) by R(φ) about the bearing's axis, the journal (body 1) by
    R(γ) about its own axis, meshed at a = (0, −c_r) and now at c = (0, −c_r − δ). The journal's
    frame is turned by ψ = γ − φ relative to the bearing's, whose frame is turned by φ: R(φ)R(ψ)
    = R(γ) (docs/fe.md, "The deformable elastoplastic journal"). [rad, m]"""
    xy = np.asarray(xy, dtype=float)
    body = np.broadcast_to(np.asarray(body), xy.shape[:-1])
    out = rotate_z(xy, phi)
    journal = body == 1
    if np.any(journal):
        a = np.array([0.0, -c_r])
        c = np.array([0.0, -c_r - delta])
        out[journal] = c + rotate_z(xy[journal] - a, gamma)
    return out


def mid_plane(z_lo, z_hi):
    """The axial mid-plane z = 0 of the model whose z extent is [z_lo, z_hi] [m], and where to
    cut it: (z, side) with side +1 when the model lies on z ≥ 0 (the half model's symmetry plane
    is its face z_lo = 0: cut just above it), −1 for a model on z ≤ 0, 0 when z = 0 lies inside
    (the full length: cut there). A model that does not reach z = 0 is cut at its middle, side 0.
    Tolerance: 1e-6 of the length."""
    tol = 1e-6 * max(abs(z_hi - z_lo), 1e-300)
    if abs(z_lo) <= tol:
        return 0.0, 1
    if abs(z_hi) <= tol:
        return 0.0, -1
    if z_lo < 0.0 < z_hi:
        return 0.0, 0
    return 0.5 * (z_lo + z_hi), 0


def contact_centre(xy):
    """The middle of the arc the points (N, 2) [m] span about the bearing's axis: at their mean
    radius, halfway between their smallest and largest angle (angles taken about the first
    point's, so a patch across ±π is one arc; the cut gives some points twice, which a mean of
    the points would count twice)."""
    xy = np.asarray(xy, dtype=float)
    theta = np.arctan2(xy[:, 0], -xy[:, 1])  # from −y toward +x, as fe_stage's rays
    theta = theta[0] + np.angle(np.exp(1j * (theta - theta[0])))
    mid = 0.5 * (theta.min() + theta.max())
    r = float(np.mean(np.hypot(xy[:, 0], xy[:, 1])))
    return [r * math.sin(mid), -r * math.cos(mid)]


def boundary_edges(xy, triangles, tol):
    """The edges of the triangles (M, 3) that belong to one triangle only, as segments
    (K, 2, 2) [m]: the outline of their union. Points are compared after rounding to `tol` [m]
    (fe_stage's patches give each cell its own copies of shared points)."""
    if len(triangles) == 0:
        return np.zeros((0, 2, 2))
    key = np.round(np.asarray(xy) / tol).astype(np.int64)
    t = np.asarray(triangles)
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    ka, kb = key[e[:, 0]], key[e[:, 1]]
    swap = (ka[:, 0] > kb[:, 0]) | ((ka[:, 0] == kb[:, 0]) & (ka[:, 1] > kb[:, 1]))
    lo = np.where(swap[:, None], kb, ka)
    hi = np.where(swap[:, None], ka, kb)
    both = np.concatenate([lo, hi], axis=1)
    degenerate = np.all(lo == hi, axis=1)
    _, inverse, counts = np.unique(both, axis=0, return_inverse=True, return_counts=True)
    once = (counts[inverse.ravel()] == 1) & ~degenerate
    return np.stack([np.asarray(xy)[e[once, 0]], np.asarray(xy)[e[once, 1]]], axis=1)


# --- reading ----------------------------------------------------------------------------------

def _manifest(fe_dir):
    import json
    try:
        with open(os.path.join(fe_dir, "manifest.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def _geometry(manifest):
    """(R_B, c_r, t_B or None) [m] from the manifest's scene, or None."""
    try:
        g = manifest["extra"]["scene"]["geometry"]
        t_B = g.get("t_B")
        return float(g["R_B"]), float(g["c_r"]), (float(t_B) if t_B is not None else None)
    except (KeyError, TypeError, ValueError, AttributeError):
        return None


def frame_angles(fe_dir, t):
    """φ, γ [rad] and δ [m] from rolling_history.csv in the row nearest the time t [s], with that
    row's time; None without the file or its columns."""
    path = os.path.join(fe_dir, "rolling_history.csv")
    try:
        _, _, h = read_table(path)
    except (OSError, ValueError):
        return None
    if not all(h.get(c) for c in ("time", "phi", "gamma", "delta")):
        return None
    i = int(np.argmin(np.abs(np.asarray(h["time"]) - t)))
    return {"time": h["time"][i], "phi": h["phi"][i], "gamma": h["gamma"][i], "delta": h["delta"][i]}


def _cell_bodies(grid, R_B):
    """Per cell: 0 bearing, 1 journal (material id when written, else the centre's radius)."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    arr = grid.GetCellData().GetArray("material_id")
    if arr is not None:
        return np.rint(vtk_to_numpy(arr)).astype(int).clip(0, 1), "material_id"
    centres = vtk.vtkCellCenters()
    centres.SetInputData(grid)
    centres.Update()
    c = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())
    return np.where(np.hypot(c[:, 0], c[:, 1]) >= R_B, 0, 1), "radius"


def _principal(a):
    """Largest and smallest principal strain per point [1], or None."""
    names = [f"principal_strain_{i}" for i in (1, 2, 3)]
    if all(n in a for n in names):
        p = np.stack([a[n] for n in names], axis=1).astype(float)
        return p.max(axis=1), p.min(axis=1)
    if "strain" in a and a["strain"].ndim == 2 and a["strain"].shape[1] == 9:
        e = a["strain"].astype(float).reshape(-1, 3, 3)
        w = np.linalg.eigvalsh(0.5 * (e + np.transpose(e, (0, 2, 1))))
        return w[:, -1], w[:, 0]
    return None


def _cut(grid, z_cut):
    """The section at z = z_cut as triangles: (points (N, 3), triangles (M, 3), point arrays,
    each triangle's body from the cell array clearjoint_body)."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.0, 0.0, z_cut)
    plane.SetNormal(0.0, 0.0, 1.0)
    cutter = vtk.vtkCutter()
    cutter.SetInputData(grid)
    cutter.SetCutFunction(plane)
    # keep each cell's own points: the fields jump between cells (and the two bodies' points
    # coincide where they touch), merging would mix them
    cutter.SetLocator(vtk.vtkNonMergingPointLocator())
    tri = vtk.vtkTriangleFilter()
    tri.SetInputConnection(cutter.GetOutputPort())
    tri.Update()
    poly = tri.GetOutput()
    if poly.GetNumberOfPoints() == 0:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=int), {}, np.zeros(0, dtype=int)
    # copies: vtk_to_numpy's arrays are views into `poly`, freed when this function returns
    pts = np.array(vtk_to_numpy(poly.GetPoints().GetData()), dtype=float)
    conn = np.array(vtk_to_numpy(poly.GetPolys().GetData()).reshape(-1, 4)[:, 1:])
    body = np.rint(vtk_to_numpy(poly.GetCellData().GetArray("clearjoint_body"))).astype(int)
    return pts, conn, {k: np.array(v) for k, v in fields._arrays(poly).items()}, body


def read_strain_map(fe_dir):
    """Everything the picture and the report need, or {"note": why not} when there is nothing to
    draw (no fields; no principal strains; no geometry in the manifest)."""
    entry = fields.last_field_entry(fe_dir)
    if entry is None:
        return {"note": "the run wrote no fields (fields/solution.pvd; fe_stage --no-fields, or "
                        "it stopped before its first field output)"}
    t_field, path = entry
    manifest = _manifest(fe_dir)
    geo = _geometry(manifest)
    if geo is None:
        return {"note": f"{os.path.join(fe_dir, 'manifest.json')} gives no "
                        "extra.scene.geometry R_B and c_r"}
    R_B, c_r, t_B = geo
    grid = fields.read_grid(path)
    if grid is None or grid.GetNumberOfPoints() == 0:
        return {"note": f"{os.path.basename(path)} could not be read (no points; VTK's message "
                        "is on stderr)"}
    a = fields._arrays(grid)
    if _principal(a) is None:
        return {"note": f"{os.path.basename(path)} has no principal_strain_1/2/3 (nor a strain "
                        "tensor) to draw"}
    angles = frame_angles(fe_dir, t_field)
    out = {"file": path, "field_time": t_field, "R_B": R_B, "c_r": c_r, "R_J": R_B - c_r,
           "angles": angles, "bodies": {}}
    if angles is None:
        out["angles_note"] = ("no rolling_history.csv with time, phi, gamma, delta: each body is "
                              "drawn in its own frame")
        angles = {"time": t_field, "phi": 0.0, "gamma": 0.0, "delta": 0.0}
    b = grid.GetBounds()
    z, side = mid_plane(b[4], b[5])
    out["mid_plane_z"], out["mid_plane_side"] = z, side
    z_cut = z + side * 1e-4 * (b[5] - b[4])
    body_of, out["bodies_from"] = _cell_bodies(grid, R_B)
    tol = 1e-7 * max(b[1] - b[0], b[3] - b[2])
    from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    # each point's body, from its cell (fe_stage's patches: every cell has its own points)
    cells = grid.GetCells()
    offsets = np.array(vtk_to_numpy(cells.GetOffsetsArray()))
    conn = np.array(vtk_to_numpy(cells.GetConnectivityArray()))
    point_body = np.full(grid.GetNumberOfPoints(), -1)
    point_body[conn] = np.repeat(body_of, np.diff(offsets))
    p3 = np.array(vtk_to_numpy(grid.GetPoints().GetData()), dtype=float)
    e_max, e_min = _principal(a)
    # the cut, both bodies at once, the body carried as cell data through the cutter
    tag = numpy_to_vtk(body_of.astype(np.float64), deep=True)
    tag.SetName("clearjoint_body")
    grid.GetCellData().AddArray(tag)
    pts, tris, ca, cut_body = _cut(grid, z_cut)
    for body in (0, 1):
        on = point_body == body
        if not np.any(on):
            continue
        info = {"n_cells": int(np.sum(body_of == body))}
        i = int(np.argmax(np.where(on, e_max, -np.inf)))
        j = int(np.argmin(np.where(on, e_min, np.inf)))
        info["max_tension"] = float(e_max[i])
        info["max_tension_at"] = _where(p3[i], body, c_r)
        info["max_compression"] = float(e_min[j])
        info["max_compression_at"] = _where(p3[j], body, c_r)
        if "equivalent_plastic_strain" in a:
            info["max_plastic_strain"] = float(np.max(a["equivalent_plastic_strain"][on]))
        mine = tris[cut_body == body]
        if len(mine):
            # the body's own points, renumbered
            used = np.unique(mine)
            renum = np.full(len(pts), -1)
            renum[used] = np.arange(len(used))
            bt = renum[mine]
            bp = pts[used]
            bca = {k: v[used] for k, v in ca.items()}
            u = bca.get("displacement")
            X = bp[:, :2] + (u[:, :2] if u is not None else 0.0)
            xy = to_fixed_frame(X, body, angles["phi"], angles["gamma"], c_r, angles["delta"])
            cmax, cmin = _principal(bca)
            info["cut"] = {"xy": xy, "tri": bt, "e_max": cmax, "e_min": cmin}
            ep = bca.get("equivalent_plastic_strain")
            if ep is not None:
                plastic = np.min(ep[bt], axis=1) > 0.0
                info["cut"]["plastic_outline"] = _move_segments(
                    boundary_edges(bp[:, :2], bt[plastic], tol), bp, xy, tol)
                info["cut"]["plastic"] = plastic
                info["mid_plane_plastic_cells"] = int(np.sum(plastic))
            active = bca.get("contact_active")
            if active is not None and body == 0:
                info["cut"]["contact"] = xy[active > 0.5]
            info["mid_plane_max_tension"] = float(np.max(cmax))
            info["mid_plane_max_compression"] = float(np.min(cmin))
        out["bodies"][BODY_NAMES[body]] = info
    contact = out["bodies"].get("bearing", {}).get("cut", {}).get("contact")
    if contact is not None and len(contact):
        out["contact_centre"] = contact_centre(contact)
        out["contact_from"] = "contact_active"
    else:
        # no active points on the cut: the deepest point of the bore under the push (−y)
        out["contact_centre"] = [0.0, -R_B]
        out["contact_from"] = "nominal"
    # the ring's outer radius: R_B + t_B, or from the fields' extent (the whole ring)
    out["R_o"] = R_B + t_B if t_B else max(0.5 * (b[1] - b[0]), R_B)
    # the extremes near the contact: on the mid-plane, in the zoom window of the picture
    w = window(out)
    for info in out["bodies"].values():
        c = info.get("cut")
        if c is not None:
            inside = np.zeros(len(c["xy"]), dtype=bool)
            inside[np.unique(c["tri"][np.all(_in_window(c["xy"], w)[c["tri"]], axis=1)])] = True
            if np.any(inside):
                info["near_contact_max_tension"] = float(np.max(c["e_max"][inside]))
                info["near_contact_max_compression"] = float(np.min(c["e_min"][inside]))
    # the material points that touched at t = 0 (the bottom of the bore, (0, −R_B), in both
    # bodies' meshes), now: the bearing's turned by φ, the journal's by γ about its axis
    out["start_points"] = {
        "bearing": to_fixed_frame([[0.0, -R_B]], 0, angles["phi"], angles["gamma"], c_r, angles["delta"])[0].tolist(),
        "journal": to_fixed_frame([[0.0, -R_B]], 1, angles["phi"], angles["gamma"], c_r, angles["delta"])[0].tolist()}
    return out


def _where(p, body, c_r):
    """A point of a body's mesh [m] as (distance from the body's own axis, z) [m]."""
    return [math.hypot(p[0], p[1] + (c_r if body == 1 else 0.0)), float(p[2])]


def _move_segments(segments, ref_pts, xy, tol):
    """Segments found on reference points moved as the points: each end's fixed-frame position
    is that of the cut point with the same rounded reference coordinates."""
    key = {tuple(k): i for i, k in enumerate(np.round(ref_pts[:, :2] / tol).astype(np.int64))}
    if len(segments) == 0:
        return np.zeros((0, 2, 2))
    ends = np.round(segments.reshape(-1, 2) / tol).astype(np.int64)
    idx = np.array([key[tuple(k)] for k in ends])
    return xy[idx].reshape(-1, 2, 2)


# --- drawing ----------------------------------------------------------------------------------

def window(m):
    """The zoom window around the contact [m]: (x0, x1, y0, y1), the wall thickness each way."""
    cx, cy = m["contact_centre"]
    t = max(m["R_o"] - m["R_B"], 0.1 * m["R_B"])
    h = 1.1 * t
    return cx - h, cx + h, cy - h, cy + h


def _in_window(xy, w):
    return (xy[:, 0] >= w[0]) & (xy[:, 0] <= w[1]) & (xy[:, 1] >= w[2]) & (xy[:, 1] <= w[3])


def draw(m, out_png, title=""):
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.colors import Normalize
    from matplotlib.patches import Circle, Rectangle

    mm = 1e3
    fig, axes = plt.subplots(1, 3, figsize=(17, 6.2), gridspec_kw={"width_ratios": [1, 1, 1]})
    ang = m["angles"] or {"phi": 0.0, "gamma": 0.0, "delta": 0.0, "time": m["field_time"]}
    w = window(m)
    cuts = {name: info["cut"] for name, info in m["bodies"].items() if "cut" in info}

    def outlines(ax, lw_body=0.6, lw_plastic=1.6):
        # the bodies' outlines as circles (the generated ring and journal; the displacements,
        # micrometres, would not show), the plastic zone as the outline of its cells
        cj = (0.0, (-m["c_r"] - ang["delta"]) * mm)
        for centre, radius, ls in (((0.0, 0.0), m["R_B"], "-"), ((0.0, 0.0), m["R_o"], "-"),
                                   (cj, m["R_J"], "-" if "journal" in cuts else "--")):
            ax.add_patch(Circle(centre, radius * mm, fill=False, ls=ls, color="0.35", lw=lw_body))
        for name, c in cuts.items():
            if len(c.get("plastic_outline", [])):
                ax.add_collection(LineCollection(c["plastic_outline"] * mm, colors="k",
                                                 linewidths=lw_plastic))

    def contact(ax, size=10):
        c = cuts.get("bearing", {}).get("contact")
        if c is not None and len(c):
            ax.plot(c[:, 0] * mm, c[:, 1] * mm, "o", ms=3, mfc="none", mec="m", mew=0.8,
                    label="bore points in contact (contact_active)")
        cx, cy = m["contact_centre"]
        ax.plot([cx * mm], [(cy - 0.03 * m["R_B"]) * mm], marker="^", ms=size, color="m",
                ls="none", label="contact" + (" (nominal: no active point on the cut)"
                                              if m["contact_from"] == "nominal" else ""))

    # (a) the whole section
    ax = axes[0]
    for name, colour in (("bearing", "0.8"), ("journal", "0.9")):
        c = cuts.get(name)
        if c is not None:
            # edges in the face colour: no seams between the triangles
            ax.add_collection(PolyCollection(c["xy"][c["tri"]] * mm, facecolors=colour,
                                             edgecolors=colour, linewidths=0.3))
            if c.get("plastic") is not None and np.any(c["plastic"]):
                ax.add_collection(PolyCollection(c["xy"][c["tri"][c["plastic"]]] * mm,
                                                 facecolors="#f5b971", edgecolors="#f5b971",
                                                 linewidths=0.3))
    outlines(ax)
    contact(ax)
    sp = m["start_points"]
    ax.plot(sp["bearing"][0] * mm, sp["bearing"][1] * mm, "s", mfc="none", mec="C0", mew=1.5, ms=11,
            label=f"bore point at the contact at t = 0, turned by φ = {math.degrees(ang['phi']):.1f}°")
    ax.plot(sp["journal"][0] * mm, sp["journal"][1] * mm, "D", color="C1", ms=7,
            label=f"journal point at the contact at t = 0, turned by γ = {math.degrees(ang['gamma']):.1f}°")
    ax.plot([0], [0], "+", color="k", ms=10)
    ax.plot([0], [(-m["c_r"] - ang["delta"]) * mm], "x", color="k", ms=7)
    ax.add_patch(Rectangle((w[0] * mm, w[2] * mm), (w[1] - w[0]) * mm, (w[3] - w[2]) * mm,
                           fill=False, ls=":", color="k", lw=1))
    R = m["R_o"] * 1.05 * mm
    ax.set_xlim(-R, R)
    ax.set_ylim(-R, R)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm] (fixed frame)")
    ax.set_ylabel("y [mm] (push along −y)")
    ax.set_title(f"(a) mid-plane z = {m['mid_plane_z'] * mm:g} mm at t = {ang['time']:.4g} s:\n"
                 "both bodies where they are; orange, outlined: plastic zone (ε_p > 0)", fontsize=10)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2)

    # (b), (c) the principal strains in the window
    for ax, key, what in ((axes[1], "e_max", "largest principal strain (tension)"),
                          (axes[2], "e_min", "smallest principal strain (compression)")):
        shown = [c[key][_in_window(c["xy"], w)] for c in cuts.values()]
        shown = np.concatenate([s for s in shown if s.size]) if any(s.size for s in shown) else np.zeros(1)
        lim = max(float(np.max(np.abs(shown))), 1e-12) * 1e3
        norm = Normalize(-lim, lim)
        mappable = None
        for c in cuts.values():
            mappable = ax.tripcolor(c["xy"][:, 0] * mm, c["xy"][:, 1] * mm, c["tri"], c[key] * 1e3,
                                    cmap="RdBu_r", norm=norm, shading="gouraud")
        outlines(ax)
        contact(ax)
        ax.set_xlim(w[0] * mm, w[1] * mm)
        ax.set_ylim(w[2] * mm, w[3] * mm)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm] (fixed frame)")
        ax.set_ylabel("y [mm]")
        ax.set_title(f"({'b' if key == 'e_max' else 'c'}) {what}\nnear the contact; black: plastic zone",
                     fontsize=10)
        if mappable is not None:
            cb = fig.colorbar(mappable, ax=ax, shrink=0.85)
            cb.set_label(f"{'ε_max' if key == 'e_max' else 'ε_min'} [10⁻³ = mm/m]")
        # the body names at their side of the contact
        cx, cy = m["contact_centre"]
        ax.text(w[0] * mm + 0.03 * (w[1] - w[0]) * mm, (cy - 0.5 * (cy - w[2])) * mm, "bearing",
                fontsize=9, bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
        ax.text(w[0] * mm + 0.03 * (w[1] - w[0]) * mm, (cy + 0.5 * (w[3] - cy)) * mm,
                "journal" + ("" if "journal" in cuts else " (rigid)"), fontsize=9,
                bbox=dict(facecolor="white", alpha=0.7, edgecolor="none"))
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    tmp = out_png + ".tmp.png"
    fig.savefig(tmp, dpi=100)
    plt.close(fig)
    os.replace(tmp, out_png)


def summary_rows(m):
    """[(body, max tension, max compression, on the mid-plane: tension, compression, max ε_p)]."""
    rows = []
    for name in ("bearing", "journal"):
        info = m["bodies"].get(name)
        if info:
            rows.append((name, info["max_tension"], info["max_compression"],
                         info.get("mid_plane_max_tension"), info.get("mid_plane_max_compression"),
                         info.get("max_plastic_strain")))
    return rows


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py rolling_strains", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fe_dir")
    p.add_argument("--output", required=True)
    p.add_argument("--title", default="")
    a = p.parse_args(argv)
    try:
        import vtk  # noqa: F401
    except ImportError:
        print("rolling_strains: VTK's Python bindings are missing (Debian package python3-vtk9)",
              file=sys.stderr)
        return 1
    m = read_strain_map(a.fe_dir)
    if "note" in m:
        print(f"rolling_strains: {a.fe_dir}: {m['note']}", file=sys.stderr)
        return 1
    draw(m, a.output, a.title)
    for row in summary_rows(m):
        print(f"{row[0]}: largest principal strain {row[1]:.4g}, smallest {row[2]:.4g} (whole body); "
              f"on the mid-plane {row[3]:.4g} / {row[4]:.4g}")
    return 0
