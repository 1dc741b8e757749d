#!/usr/bin/python3
"""The rolling study's principal-strain map (scripts/plotting/rolling_strains.py, the paper's
Fig. 11): the geometry and the reading, on points with known answers and on tiny fields written
here (tests/unit/report/rolling_fields_vtu.py).
- The frame rotation: a bearing point turned by φ about the bearing's axis, a journal point by γ
  about the journal's axis at (0, −c_r − δ); the journal's placement equals the bearing's frame
  carrying the journal's frame (R(φ)·(c_frame + R(γ − φ)(X − a)), docs/fe.md).
- The mid-plane: the half model's face z = 0 (either side), an interior z = 0, the middle of a
  model that does not reach it.
- The outline of a set of triangles with each cell's own copies of shared points.
- The fields: the cut is taken at z = 0, each body is found (by radius, and by material id),
  turned to where it is, its extremes are the known constants, the plastic zone is the plastic
  body's outline, the contact sits at the turned bore; the picture is written; no fields, no
  principal strains and no manifest each give a note instead of a picture.

    rolling_strains_test.py
"""
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "scripts"))
sys.path.insert(0, HERE)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import numpy as np  # noqa: E402

import rolling_fields_vtu as rf  # noqa: E402
from plotting import rolling_strains as rs  # noqa: E402

bad = []


def expect(ok, what):
    if not ok:
        bad.append(what)


def near(a, b, tol, what):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    expect(a.shape == b.shape and np.all(np.abs(a - b) <= tol), f"{what}: {a.tolist()} != {b.tolist()}")


def geometry():
    R_B, c_r, delta = 0.01, 0.0005, 1e-5
    R_J = R_B - c_r
    # the bore's bottom (0, −R_B) after a quarter turn of the bearing (counter-clockwise about
    # +z) is at (R_B, 0); after a half turn at the top
    near(rs.to_fixed_frame([[0.0, -R_B]], 0, math.pi / 2, 0.0, c_r, delta), [[R_B, 0.0]], 1e-15,
         "bearing point after φ = π/2")
    near(rs.to_fixed_frame([[0.0, -R_B]], 0, math.pi, 1.0, c_r, delta), [[0.0, R_B]], 1e-15,
         "bearing point after φ = π")
    # the journal's bottom as meshed, (0, −c_r − R_J) = (0, −R_B), after γ = π/2 about its axis,
    # which the push has moved to (0, −c_r − δ): (R_J, −c_r − δ); γ alone matters, not φ
    near(rs.to_fixed_frame([[0.0, -R_B]], 1, 0.3, math.pi / 2, c_r, delta), [[R_J, -c_r - delta]],
         1e-15, "journal point after γ = π/2")
    # the journal's axis as meshed goes to the pushed axis whatever the angles
    near(rs.to_fixed_frame([[0.0, -c_r]], 1, 1.1, 2.3, c_r, delta), [[0.0, -c_r - delta]], 1e-15,
         "journal axis")
    # the same as the bearing's frame carrying the journal's: x = R(φ)(c_frame + R(γ − φ)(X − a)),
    # c_frame = R(−φ) c (fe_stage/solve/rolling_kinematics.h centre_frame)
    phi, gamma = 0.7, 0.75
    X = np.array([[0.003, -0.008], [-0.002, -0.009]])
    a, c = np.array([0.0, -c_r]), np.array([0.0, -c_r - delta])
    c_frame = rs.rotate_z(c, -phi)
    nested = rs.rotate_z(c_frame + rs.rotate_z(X - a, gamma - phi), phi)
    near(rs.to_fixed_frame(X, 1, phi, gamma, c_r, delta), nested, 1e-15,
         "journal placement = the bearing's frame carrying the journal's")
    # mixed bodies in one call
    both = rs.to_fixed_frame([[0.0, -R_B], [0.0, -R_B]], np.array([0, 1]), math.pi / 2,
                             math.pi / 2, c_r, delta)
    near(both, [[R_B, 0.0], [R_J, -c_r - delta]], 1e-15, "bearing and journal points in one call")

    # the mid-plane
    expect(rs.mid_plane(0.0, 0.01) == (0.0, 1), "half model on z ≥ 0: its face z = 0, cut above")
    expect(rs.mid_plane(-0.01, 0.0) == (0.0, -1), "half model on z ≤ 0: its face z = 0, cut below")
    expect(rs.mid_plane(-0.01, 0.01) == (0.0, 0), "the whole length: z = 0 inside")
    expect(rs.mid_plane(1e-12, 0.01) == (0.0, 1), "z = 0 within round-off of the face")
    expect(rs.mid_plane(0.002, 0.006) == (0.004, 0), "a model away from z = 0: its middle")

    # the outline of two triangles (a unit square), each with its own points
    xy = np.array([[0, 0], [1, 0], [1, 1], [0, 0], [1, 1], [0, 1]], dtype=float) * 1e-3
    seg = rs.boundary_edges(xy, np.array([[0, 1, 2], [3, 4, 5]]), 1e-9)
    expect(len(seg) == 4, f"a square of two triangles has 4 outline edges: {len(seg)}")
    lengths = np.linalg.norm(seg[:, 1] - seg[:, 0], axis=1)
    near(np.sort(lengths), [1e-3] * 4, 1e-12, "the outline is the square's sides (no diagonal)")
    expect(len(rs.boundary_edges(xy, np.zeros((0, 3), dtype=int), 1e-9)) == 0, "no triangles, no outline")

    # the contact's centre: the middle of the arc its points span, points given twice or not,
    # and across ±π (the top of the bore)
    arc = [[R_B * math.sin(a), -R_B * math.cos(a)] for a in np.radians([-5, 0, 15, 15, 15])]
    near(rs.contact_centre(arc), [R_B * math.sin(math.radians(5)), -R_B * math.cos(math.radians(5))],
         1e-15, "the contact's centre: the middle of its arc")
    top = [[R_B * math.sin(a), -R_B * math.cos(a)] for a in np.radians([170, 175, -170])]
    near(rs.contact_centre(top), [R_B * math.sin(math.radians(180)), R_B], 1e-12,
         "a contact across the top: the middle of its arc")


def fields():
    with tempfile.TemporaryDirectory() as d:
        # the last increment at t = 0.04 s; the bearing and the journal turned a quarter turn
        case = os.path.join(d, "case")
        os.makedirs(case)
        delta = 1e-5
        rf.write_fields(case, 0.04)
        rf.write_history(case, [(0.0, 0.0, 0.0, 0.0), (0.02, delta, 0.2, 0.21),
                                (0.04, delta, math.pi / 2, math.pi / 2)])
        rf.write_manifest(case)
        m = rs.read_strain_map(case)
        expect("note" not in m, f"fields are read: {m.get('note')}")
        if "note" in m:
            return
        expect(m["mid_plane_z"] == 0.0 and m["mid_plane_side"] == 1, "the cut is the face z = 0")
        expect(m["bodies_from"] == "radius", "bodies by radius without a material id")
        near([m["angles"]["phi"], m["angles"]["gamma"], m["angles"]["delta"]],
             [math.pi / 2, math.pi / 2, delta], 1e-15, "the angles of the history row at the field's time")
        b, j = m["bodies"]["bearing"], m["bodies"]["journal"]
        # the extremes (single precision in the file)
        near([b["max_tension"], b["max_compression"], j["max_tension"], j["max_compression"]],
             [1e-3, -2e-3, 3e-3, -4e-3], 1e-9, "whole-body extremes")
        near([b["near_contact_max_tension"], b["near_contact_max_compression"],
              j["near_contact_max_tension"], j["near_contact_max_compression"]],
             [1e-3, -2e-3, 3e-3, -4e-3], 1e-9, "near-contact extremes")
        # where they are: the bearing cell's section turned a quarter turn lies right of the
        # axis (x from R_B cos 10° to R_B + t_B, |y| ≤ (R_B + t_B) sin 10°)
        bx = b["cut"]["xy"]
        r_out = rf.R_B + rf.T_B
        expect(np.all(bx[:, 0] >= rf.R_B * math.cos(rf.HALF_ANGLE) - 1e-9) and
               np.all(bx[:, 0] <= r_out + 1e-9) and
               np.all(np.abs(bx[:, 1]) <= r_out * math.sin(rf.HALF_ANGLE) + 1e-9),
               "the bearing's section turned by φ = π/2 lies on +x")
        # the journal cell turned a quarter turn about its axis (0, −c_r − δ): right of the axis
        jx = j["cut"]["xy"]
        cy = -rf.C_R - delta
        expect(np.all(jx[:, 0] >= 0.8 * rf.R_J * math.cos(rf.HALF_ANGLE) - 1e-9) and
               np.all(jx[:, 0] <= rf.R_J + 1e-9) and
               np.all(np.abs(jx[:, 1] - cy) <= rf.R_J * math.sin(rf.HALF_ANGLE) + 1e-9),
               "the journal's section turned by γ = π/2 lies right of its axis")
        # the contact: the bore's points, turned with the bearing: centre near (R_B, 0)
        near(m["contact_centre"], [rf.R_B, 0.0], 1e-9, "the contact sits at the turned bore")
        expect(m["contact_from"] == "contact_active", "contact from contact_active")
        # the plastic zone: the bearing's whole section (4 sides), none in the journal
        expect(len(b["cut"]["plastic_outline"]) == 4 and len(j["cut"]["plastic_outline"]) == 0,
               f"plastic outline: {len(b['cut']['plastic_outline'])} bearing / "
               f"{len(j['cut']['plastic_outline'])} journal edges")
        # the material points that touched at t = 0
        near(m["start_points"]["bearing"], [rf.R_B, 0.0], 1e-12, "the bore's start point")
        near(m["start_points"]["journal"], [rf.R_J, cy], 1e-12, "the journal's start point")
        # the picture
        png = os.path.join(d, "strains.png")
        expect(rs.main([case, "--output", png]) == 0 and os.path.getsize(png) > 10000,
               "plot.py rolling_strains writes the picture")

        # the material id, where the fields carry one, decides the bodies
        mid = os.path.join(d, "material_id")
        os.makedirs(mid)
        rf.write_fields(mid, 0.04, material_id=True)
        rf.write_history(mid, [(0.04, delta, 0.0, 0.0)])
        rf.write_manifest(mid)
        m = rs.read_strain_map(mid)
        expect(m.get("bodies_from") == "material_id" and set(m["bodies"]) == {"bearing", "journal"},
               "bodies from the material id")

        # a rigid journal: the bearing only, the picture still drawn
        rigid = os.path.join(d, "rigid")
        os.makedirs(rigid)
        rf.write_fields(rigid, 0.04, journal=False)
        rf.write_history(rigid, [(0.04, delta, 0.1, 0.1)])
        rf.write_manifest(rigid)
        m = rs.read_strain_map(rigid)
        expect(set(m.get("bodies", {})) == {"bearing"}, "a rigid journal: the bearing only")
        expect(rs.main([rigid, "--output", os.path.join(d, "rigid.png")]) == 0,
               "the picture with a rigid journal")

        # notes instead of pictures
        none = os.path.join(d, "none")
        os.makedirs(none)
        rf.write_history(none, [(0.04, delta, 0.1, 0.1)])
        rf.write_manifest(none)
        m = rs.read_strain_map(none)
        expect("no fields" in m.get("note", ""), f"no fields: a note: {m}")
        expect(rs.main([none, "--output", os.path.join(d, "none.png")]) == 1 and
               not os.path.exists(os.path.join(d, "none.png")), "no fields: exit 1, no picture")
        nop = os.path.join(d, "no_principal")
        os.makedirs(nop)
        rf.write_fields(nop, 0.04, principal=False)
        rf.write_manifest(nop)
        expect("principal" in rs.read_strain_map(nop).get("note", ""), "no principal strains: a note")
        nom = os.path.join(d, "no_manifest")
        os.makedirs(nom)
        rf.write_fields(nom, 0.04)
        expect("manifest" in rs.read_strain_map(nom).get("note", ""), "no manifest: a note")


def main():
    geometry()
    fields()
    if bad:
        print("FAILED:\n  " + "\n  ".join(bad))
        return 1
    print("rolling strains: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
