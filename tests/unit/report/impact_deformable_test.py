#!/usr/bin/python3
"""The report's impact sections with both journals (issue 31 item 2): the deformable journal's
section has its own anchor and words (both bodies deformable, no journal-mass sweep), names the
time integrator as the FE stage wrote it (issue 31: the Abaqus application by name, with α, β,
γ), its warnings name the deformable variant and link to its section; where both variants ran,
a table sets them side by side at the velocities and the journal mass they share — the rigid
journal's ρπR_J²L_J against the deformable one's FE mass, 4e-5 apart as measured — and leaves
the rigid journal's heavier masses out; a summary written before the variant existed (no
`journal` key, no application in the manifest) still reads as the rigid journal's.

    impact_deformable_test.py
"""
import json
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "scripts"))
sys.path.insert(0, HERE)

from impact_sweep_test import check, write_sweep_folder  # noqa: E402
from plotting._report_impact import (both_journals_html, impact_headline,  # noqa: E402
                                     impact_section)
from plotting._report_common import Warnings  # noqa: E402

# the integrator line fe_stage writes first in impact_history.csv (results/impact_output.cc)
SCHEME = ("moderate_dissipation: HHT alpha = -0.414214, beta = 0.5, gamma = 0.914214")


def as_fe_stage_wrote_it(sweep_csv, journal, application="moderate_dissipation"):
    """Adds to each stand-in case what fe_stage writes: the integrator in the history's first
    comment, the resolved scene (journal, application) and α in the manifest."""
    top = os.path.dirname(sweep_csv)
    for c in sorted(os.listdir(top)):
        f = os.path.join(top, c)
        if not os.path.isdir(f):
            continue
        h = os.path.join(f, "impact_history.csv")
        with open(h) as x:
            text = x.read()
        with open(h, "w") as x:
            x.write("# clearjoint fe_stage: impact study (paper 3.2), deformable journal launched "
                    "at first touch toward the bearing (-y) at 0.1 m/s; Abaqus application "
                    + SCHEME + "\n" + text)
        m = os.path.join(f, "manifest.json")
        with open(m) as x:
            man = json.load(x)
        man["extra"]["scene"] = {"loading": {"journal": journal},
                                 "impact": {"application": application}}
        man["extra"]["impact"]["alpha"] = -0.41421356237309503
        with open(m, "w") as x:
            json.dump(man, x)


def main():
    own_rigid, own_fe = 0.0398074, 0.0398059  # [kg] rho pi R_J^2 L_J; the FE mass matrix's
    with tempfile.TemporaryDirectory() as d:
        rigid_dir, def_dir = os.path.join(d, "rigid"), os.path.join(d, "deformable")
        os.makedirs(rigid_dir)
        os.makedirs(def_dir)
        rigid_csv = write_sweep_folder(rigid_dir, [(v, m, g) for m, g in
                                                   [(own_rigid, 0.25), (1.0, 0.0066)]
                                                   for v in (0.05, 0.1, 0.2)], 0.9617)
        def_csv = write_sweep_folder(def_dir, [(v, own_fe, 0.15) for v in (0.05, 0.1, 0.2)],
                                     [0.9766, 0.9766, 1.02])
        as_fe_stage_wrote_it(def_csv, "end_faces")
        rigid = {"fe_dir": rigid_dir, "sweep": rigid_csv}  # an old summary: no journal key
        deformable = {"fe_dir": def_dir, "sweep": def_csv}  # the journal from the manifests

        w = Warnings()
        html = impact_section(deformable, d, w, "impact_deformable")
        check("id='impact_deformable'" in html and "id='impact'" not in html,
              "its own anchor, not the rigid section's")
        check("both bodies deformable" in html and "loading.journal: end_faces" in html,
              "says what was modelled")
        check("no journal-mass sweep" in html, "says why there is one mass")
        check("Time integration" in html and SCHEME in html,
              f"the integrator as fe_stage wrote it: {re.findall(r'Time integration.*?</p>', html)}")
        # the case beyond the restitution's resolution: a warning naming the variant and
        # linking to its section
        check(len(w.items) == 1, f"one warning: {w.items}")
        where, _, anchor = w.items[0]
        check("deformable" in where and anchor == "impact_deformable", f"{w.items[0]}")
        head = impact_headline(deformable, "impact_deformable")
        check("href='#impact_deformable'" in head and "both bodies deformable" in head, head)

        # the rigid section of a summary without `journal` and without the application: as
        # before, plus "rigid journal" in its title; no integrator line it cannot back
        w = Warnings()
        html = impact_section(rigid, d, w)
        check("id='impact'" in html and "rigid journal" in html, "the rigid section")
        check("Time integration" not in html, "no integrator line without its source")
        check("href='#impact'" in impact_headline(rigid), "the rigid headline links to #impact")
        # the manifest names the application but the history has no comment: the name alone
        as_fe_stage_wrote_it(rigid_csv, "rigid", "transient_fidelity")
        for c in os.listdir(rigid_dir):
            h = os.path.join(rigid_dir, c, "impact_history.csv")
            if os.path.exists(h):
                with open(h) as x:
                    lines = x.readlines()[1:]
                with open(h, "w") as x:
                    x.writelines(lines)
        html = impact_section(rigid, d, Warnings())
        check("transient_fidelity (HHT α = -0.41421)" in html,
              f"the name and α from the manifest: {re.findall(r'Time integration.*?</p>', html)}")

        # side by side: the three velocities at the own mass, not the rigid 1 kg cases
        both = both_journals_html(rigid, deformable)
        rows = re.findall(r"<tr><td>(.*?)</tr>", both)
        check(len(rows) == 3, f"three shared cases: {rows}")
        check(all("0.039807 / 0.039806" in r for r in rows), f"the two own masses: {rows}")
        check(not any("1 /" in r.split("</td>")[1] for r in rows), "the 1 kg journal left out")
        # ratios of the deformable to the rigid journal (the stand-ins: peak force ∝ (1 + gap)
        # at the same δ ∝ √m: 1.15/1.25 × √(own_fe/own_rigid))
        ratio = 1.15 / 1.25 * (own_fe / own_rigid) ** 0.5
        check(f"({ratio:.3f}×)" in rows[0], f"the peak force's ratio {ratio:.3f}: {rows[0]}")
        # no shared case (another mass): nothing
        other = os.path.join(d, "other")
        os.makedirs(other)
        other_csv = write_sweep_folder(other, [(0.1, 0.5, 0.1)])
        check(both_journals_html(rigid, {"fe_dir": other, "sweep": other_csv}) == "",
              "no table without a shared case")
        check(both_journals_html(rigid, {"fe_dir": other, "sweep": other + "/missing.csv"}) == "",
              "no table without the deformable table")
    # the paper's "gap → 0 as v → 0" with the deformable journal's measured gaps (fast preset):
    # it falls a little as v falls, which is neither the linear response nor the paper's claim
    from plotting._impact_sweep import paper_claims
    from impact_sweep_test import sweep
    _, numbers, finding, ok = paper_claims(sweep([(0.05, own_fe, 0.14693), (0.1, own_fe, 0.15194),
                                                  (0.2, own_fe, 0.15464)]))[1]
    check(ok is False and "falls only a little" in finding and "scales with v" not in finding,
          f"the deformable journal's v claim: {finding}")
    check("0.77 points over 4× in v" in finding, f"how much: {finding}")
    check("+14.69 % at 0.05 m/s" in numbers, numbers)
    print("impact_deformable_test: ok")


if __name__ == "__main__":
    main()
