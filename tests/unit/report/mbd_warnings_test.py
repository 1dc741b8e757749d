#!/usr/bin/python3
"""The report's MBD warnings (issue 15 item 1: "every warning of the run — range counters, laws
used outside their fit range"), from summary.json files shaped as mbd_stage writes them
(clearjoint.mbd_summary/1: normal_model.valid_range, normal_model.out_of_range with the counts of
accepted steps above and below the fitted range, law_out_of_range_accepted_steps, peaks):
a clean run has none; a law used beyond its range, each kind of counter and a failed run each
give one; the summary's warning list names them.

    mbd_warnings_test.py
"""
import copy
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))

from plotting._report_common import Warnings  # noqa: E402
from plotting._report_mbd import Run, mbd_section, run_problems  # noqa: E402

CLEAN = {
    "schema": "clearjoint.mbd_summary/1", "status": "complete", "scene": "s",
    "duration": {"unit": "s", "value": 0.1},
    "peaks": {"contact_force_max": 3264.3, "first_impact_peak_force": 3264.3,
              "penetration_max": 1.0169e-05, "units": {"penetration_max": "m"}},
    "energy": {"E0": 2.523, "E_total_final": 2.514, "W_friction": -0.0092, "W_damping": 0.0},
    "clearance_joints": [{
        "name": "rod_slider",
        "law_out_of_range_accepted_steps": 0,
        "n_impacts": {"axial_neg": 0, "axial_pos": 0, "radial": 23},
        "friction": {"mu": 0.1},
        "impact_velocity_floor": {"n_onsets_floored": {"radial": 0}},
        "normal_model": {
            "name": "fe_law", "damping": "none",
            "law": {"K": 3.6595e8, "n": 1.0114, "form": "F = K*delta^n (law file)"},
            "valid_range": {"delta_min": 0.0, "delta_max": 5e-05, "unit": "m"},
            "out_of_range": {"max_delta_accepted": 1.0169e-05, "n_accepted_steps_above": 0,
                             "n_accepted_steps_below": 0, "policy": "extend", "unit": "m"}}}],
}


def run_of(d, name, summary):
    folder = os.path.join(d, name)
    os.makedirs(folder)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump(summary, f)
    return {"name": name, "dir": folder}


def main():
    bad = []

    def expect(ok, what):
        if not ok:
            bad.append(what)

    with tempfile.TemporaryDirectory() as d:
        clean = run_of(d, "clean", CLEAN)
        expect(run_problems(Run(clean)) == [], f"a clean run has no problems: {run_problems(Run(clean))}")

        beyond = copy.deepcopy(CLEAN)
        beyond["peaks"]["penetration_max"] = 6.2e-05
        beyond["clearance_joints"][0]["law_out_of_range_accepted_steps"] = 12
        beyond["clearance_joints"][0]["normal_model"]["out_of_range"]["n_accepted_steps_above"] = 12
        p = run_problems(Run(run_of(d, "beyond", beyond)))
        text = " ".join(p)
        expect(any("beyond its fitted range" in t and "62" in t and "50" in t for t in p),
               f"law used beyond its range (62 µm against 50 µm) named: {p}")
        expect("law_out_of_range_accepted_steps = 12" in text, f"the joint's counter named: {p}")
        expect("n_accepted_steps_above = 12" in text,
               f"the count inside the out_of_range block named: {p}")
        expect("max_delta_accepted" not in text, f"a length is not a counter: {p}")

        below = copy.deepcopy(CLEAN)
        below["clearance_joints"][0]["normal_model"]["out_of_range"]["n_accepted_steps_below"] = 3
        p = run_problems(Run(run_of(d, "below", below)))
        expect(len(p) == 1 and "n_accepted_steps_below = 3" in p[0],
               f"steps below the fitted range counted: {p}")

        family = copy.deepcopy(CLEAN)
        family["clearance_joints"][0]["normal_model"]["out_of_range"]["n_parameter_out_of_range"] = 5
        family["clearance_joints"][0]["axial_model"] = {"n_accepted_steps_beyond_peak": 2}
        p = " ".join(run_problems(Run(run_of(d, "family", family))))
        expect("n_parameter_out_of_range = 5" in p and "n_accepted_steps_beyond_peak = 2" in p,
               f"a family's parameter and Johnson's beyond-peak counters named: {p}")

        failed = copy.deepcopy(CLEAN)
        failed["status"] = "failed"
        failed["failure"] = "step size below h_min at t = 0.031 s"
        p = run_problems(Run(run_of(d, "failed", failed)))
        expect(any("status failed" in t and "h_min" in t for t in p), f"a failed run named: {p}")

        # the summary's warning list: one entry per problem, under the run's name
        w = Warnings()
        mbd_section([clean, {"name": "beyond", "dir": os.path.join(d, "beyond")}], d, w)
        listed = w.html()
        expect(len(w.items) == 2 and all(where == "MBD beyond" for where, _, _ in w.items),
               f"two warnings, both for the run 'beyond': {w.items}")
        expect("href=\"#mbd\"" in listed, "each warning links to the multibody section")

    for b in bad:
        print("FAIL:", b)
    if not bad:
        print("ok")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
