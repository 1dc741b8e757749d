#!/usr/bin/python3
"""bench/measure_presets.py with a recorded reference (issue 32 item 2: the largest error over
a sweep, not one value's, and no figure typed by hand), on the tests' stand-in FE stage
(tests/data/fake_stages, scene key fake_discretisation: F(δ_max) = F_0 (1 + 0.1 h), F_0 the
stand-in's exact force of the case): a plan whose thickness and misalignment studies compare
the preset's own run at every sweep value with that value's interval in a file of adaptive
sequences (written here, about F_0) writes `percent` = the largest of the per-value errors
computed here by hand, a `where` that lists each value's range and names the value with no
sequence; a bad plan (an unknown sequence name, a missing file, a value the sweep does not
have, `values` without a recorded reference, a sequence of another journal) is an error naming
its key before any run, and a run whose journal is not the plan's fails the study.

    measure_presets_recorded_test.py RUN_PIPELINE FIT_STAGE MSH_CHECK
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import measure_presets  # noqa: E402
from fake_build import make_fake_build, write_scenes  # noqa: E402

PIPELINE = """schema: clearjoint.pipeline/1
run: r
output_root: out
preset: fast
presets:
  fast:
    fe: {mesh.global_refinements: 0}
    mbd: null
  standard:
    fe: {mesh.global_refinements: 1}
    mbd: null
  accurate:
    fe: {mesh.global_refinements: 2}
    mbd: null
fe_sweeps:
  - name: thickness
    scene: thickness.yaml
    parameter: {name: t_B, unit: m, key: geometry.t_B}
    values: [0.002, 0.004, 0.006]
  - name: misalignment
    scene: misalignment.yaml
    parameter: {name: theta, unit: deg, key: misalignment.theta_deg}
    values: [1.0, theta_max]
fit: {weighting: absolute}
mbd_runs: []
report: false
"""

SCENES = {
    "thickness.yaml": {"study": "radial", "geometry": {"t_B": 0.004}, "fake_discretisation": True},
    "misalignment.yaml": {"study": "misalignment", "misalignment": {"theta_deg": 1.0},
                          "loading": {"journal": "core"}, "fake_discretisation": True},
}

# The stand-in's exact F(δ_max) (tests/data/fake_stages/fake_fe_stage.py): K δ^n with
# K = 3.65952708e8 N/m^n · t_B / 4 mm, n = 1.0114, δ_max = 50 µm; the core-loaded tilted
# journal 0.7 (1 - 0.2 θ/θ_max) of it, so at θ_max 0.56 of the t_B = 4 mm force.
def exact_force(t_B=0.004, factor=1.0):
    return 3.65952708e8 * t_B / 0.004 * factor * 5e-5 ** 1.0114


# Each value's interval about F_0, chosen so that the largest error is NOT at the study's
# `value` (4 mm: the case whose time is written), and that a preset's force lies inside one
# interval (standard at 4 mm: its lower figure is 0).
INTERVALS = {"t_B = 2 mm": (exact_force(0.002), 0.95, 0.965),
             "t_B = 4 mm": (exact_force(0.004), 1.04, 1.06),
             "theta_max": (exact_force(0.004, 0.56), 0.98, 1.00)}
H = {"fast": 1.0, "standard": 0.5}  # the plan's presets: contact refinements 0 and 1

SEQUENCES = "".join(
    f"sequence test {name}\njournal deformable\nsource made up about the stand-in's exact force\n"
    f"reference {F0 * lo!r} {F0 * hi!r}\nchecked 0\nmesh 1000 {F0 * 1.1!r}\nend\n\n"
    for name, (F0, lo, hi) in INTERVALS.items()) + (
    "sequence test rigid\njournal rigid\nsource another journal\nreference 1.0 2.0\nend\n")

PLAN = {
    "smoke": True,
    "presets": {p: {"mesh.n_circumferential": 8, "mesh.n_axial": 2, "mesh.n_radial": 1,
                    "mesh.global_refinements": 0, "mesh.contact_refinements": i}
                for i, p in enumerate(measure_presets.PRESETS)},
    "studies": {
        "thickness": {"kind": "fe_sweep", "value": 0.004, "values": "all",
                      "quantity": "force_at_delta_max", "time_key": "fe_case_time",
                      "dofs_key": "fe_dofs", "set": {"loading.n_increments": 3},
                      "reference": {"recorded": {
                          "file": "SEQUENCES", "journal": "end_faces", "mu": 0.1,
                          "sequences": {0.002: "test t_B = 2 mm", 0.004: "test t_B = 4 mm"}}}},
        "misalignment": {"kind": "fe_sweep", "value": 1.0, "values": [1.0, "theta_max"],
                         "quantity": "force_at_delta_max", "time_key": "case_times.misalignment",
                         "dofs_key": "dofs.misalignment", "set": {"loading.n_increments": 3},
                         "reference": {"recorded": {
                             "file": "SEQUENCES", "journal": "core", "mu": 0.1,
                             "sequences": {"theta_max": "test theta_max"}}}},
    }}


def by_hand(q, F0, lo, hi):
    """(lower, upper) [%] of force q against [lo F0, hi F0]: the far end gives the upper, the
    near end the lower, 0 inside."""
    a, b = 100 * abs(q - lo * F0) / (lo * F0), 100 * abs(q - hi * F0) / (hi * F0)
    return (0.0 if lo * F0 <= q <= hi * F0 else min(a, b)), max(a, b)


def main():
    run_pipeline, fit_stage, msh_check = sys.argv[1:4]
    bad = []

    def expect(ok, what):
        if not ok:
            bad.append(what)

    def close(a, b, what, rel=5e-3):  # figures have 3 significant digits
        expect(isinstance(a, (int, float)) and abs(a - b) <= rel * abs(b), f"{what}: {a} against {b}")

    d = tempfile.mkdtemp(prefix="measure_presets_recorded_")
    try:
        # 0. the file of sequences is read strictly: a malformed line names the file and line
        broken = os.path.join(d, "broken.txt")
        with open(broken, "w") as f:
            f.write("sequence x\njournal deformable\nreference 1.0\nend\n")
        try:
            measure_presets.read_sequences(broken)
            expect(False, "a reference line with one number read without an error")
        except measure_presets.MeasureError as e:
            expect(f"{broken}:3" in str(e) and "F_low F_high" in str(e), f"the bad line named: {e}")

        build = make_fake_build(d, fit_stage, msh_check)
        write_scenes(d, SCENES)
        sequences = os.path.join(d, "sequences.txt")
        with open(sequences, "w") as f:
            f.write(SEQUENCES)
        p = os.path.join(d, "p.yaml")
        with open(p, "w") as f:
            f.write(PIPELINE)

        def plan_file(name, edit=None):
            plan = json.loads(json.dumps(PLAN))
            plan["studies"]["thickness"]["reference"]["recorded"]["file"] = sequences
            plan["studies"]["misalignment"]["reference"]["recorded"]["file"] = sequences
            # float keys back (JSON made them strings): the plan as YAML writes 0.002
            for s in plan["studies"].values():
                rec = s["reference"]["recorded"]
                rec["sequences"] = {(float(k) if k[0].isdigit() else k): v
                                    for k, v in rec["sequences"].items()}
            if edit:
                edit(plan["studies"])
            path = os.path.join(d, name)
            with open(path, "w") as f:
                yaml.safe_dump(plan, f, allow_unicode=True)
            return path

        def command(plan, *extra):
            return [sys.executable, os.path.join(ROOT, "bench", "measure_presets.py"),
                    "--plan", plan, "--pipeline", p, "--build-dir", build, "--run-pipeline",
                    run_pipeline, "--work", os.path.join(d, "work"), "--no-plots",
                    "--set", "contact.mu=0.1", "--presets", "fast", "standard", *extra]

        # 1. the largest error over each sweep's values with a sequence
        done = subprocess.run(command(plan_file("plan.yaml")), capture_output=True, text=True, cwd=d)
        expect(done.returncode == 0, f"measure_presets with recorded references: exit "
                                     f"{done.returncode}:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
        measured = {k: (v or {}).get("measured") or {}
                    for k, v in yaml.safe_load(open(p))["presets"].items()}
        for preset, h in H.items():
            b = measured.get(preset, {})
            errors = b.get("error_F_max", {})
            q2 = exact_force(0.002) * (1 + 0.1 * h)
            q4 = exact_force(0.004) * (1 + 0.1 * h)
            qm = exact_force(0.004, 0.56) * (1 + 0.1 * h)
            e2 = by_hand(q2, *INTERVALS["t_B = 2 mm"])
            e4 = by_hand(q4, *INTERVALS["t_B = 4 mm"])
            em = by_hand(qm, *INTERVALS["theta_max"])
            expect(e2[1] > e4[1], "the test's intervals put the largest error off the study's value")
            th = errors.get("thickness") or {}
            close(th.get("percent"), max(e2[1], e4[1]), f"{preset} thickness: the largest over t_B")
            where = th.get("where", "")
            # each value's range, to the command's 3 significant digits (0 for a force inside)
            sig = lambda x: measure_presets.significant(x) or 0  # noqa: E731
            for text in (f"{sig(e2[0])}-{sig(e2[1])} % at 2 mm", f"{sig(e4[0])}-{sig(e4[1])} % at 4 mm",
                         "the largest over t_B (at 2 mm)", "t_B = 6 mm: no reference",
                         '"test t_B = 2 mm"', sequences, "loading.journal end_faces",
                         "bench/measure_presets.py --plan", "UTC"):
                expect(text in where, f"{preset} thickness where has '{text}': {where}")
            expect("6 mm (" not in where, f"{preset}: t_B = 6 mm not measured: {where}")
            mis = errors.get("misalignment") or {}
            close(mis.get("percent"), em[1], f"{preset} misalignment at theta_max")
            where = mis.get("where", "")
            for text in (f"% at theta_max (3.28", "theta = 1 deg: no reference",
                         "loading.journal core"):
                expect(text in where, f"{preset} misalignment where has '{text}': {where}")
            # the study's `value` is still the case whose time and DoFs are written
            expect(isinstance(b.get("fe_case_time"), (int, float)) and b.get("fe_dofs") == int(1000 / h),
                   f"{preset} the 4 mm case's time and DoFs: {b.get('fe_case_time')}, {b.get('fe_dofs')}")
        expect(by_hand(exact_force(0.004) * 1.05, *INTERVALS["t_B = 4 mm"])[0] == 0.0
               and " 0-" in measured["standard"]["error_F_max"]["thickness"]["where"],
               "a force inside its interval: the lower figure 0")
        log = done.stdout
        expect(log.count("thickness, fast at 0.002") == 1 and "fast at 0.006" not in log,
               f"2 mm run once per preset, 6 mm (no sequence) not at all:\n{log[-2000:]}")

        # 2. a bad plan: an error naming its key, before any run, the pipeline file untouched
        before = open(p).read()

        def set_in(study, *path_value):
            def edit(studies):
                node = studies[study]
                for k in path_value[:-2]:
                    node = node[k]
                if path_value[-1] is None:
                    del node[path_value[-2]]
                else:
                    node[path_value[-2]] = path_value[-1]
            return edit

        def seq(key, name):
            return lambda s: s["thickness"]["reference"]["recorded"]["sequences"].update({key: name})

        cases = [
            ("a sequence name not in the file", seq(0.002, "no such sequence"),
             ["studies.thickness.reference.recorded.sequences.0.002", "'no such sequence'",
              "'test t_B = 4 mm'"]),
            ("a missing file", set_in("thickness", "reference", "recorded", "file", os.path.join(d, "none.txt")),
             ["studies.thickness.reference.recorded.file", "none.txt"]),
            ("no sequences", set_in("thickness", "reference", "recorded", "sequences", None),
             ["studies.thickness.reference.recorded.sequences: missing"]),
            ("a sequence for a value the sweep does not have", seq(0.008, "test t_B = 4 mm"),
             ["studies.thickness.reference.recorded.sequences.0.008", "0.002, 0.004, 0.006"]),
            ("a value the sweep does not have", set_in("thickness", "values", [0.002, 0.003]),
             ["studies.thickness.values", "0.003"]),
            ("values without a recorded reference",
             set_in("thickness", "reference", {"run": {"preset": "accurate"}}),
             ["studies.thickness.values", "only with reference.recorded"]),
            ("a sequence of another journal", seq(0.004, "test rigid"),
             ["studies.thickness.reference.recorded.sequences.0.004", "rigid journal"]),
            ("an unknown journal", set_in("thickness", "reference", "recorded", "journal", "ends"),
             ["studies.thickness.reference.recorded.journal", "end_faces, axis_line, core"]),
        ]
        for i, (what, edit, names) in enumerate(cases):
            r = subprocess.run(command(plan_file(f"bad{i}.yaml", edit)), capture_output=True,
                               text=True, cwd=d)
            expect(r.returncode != 0 and all(n in r.stderr for n in names),
                   f"{what}: exit {r.returncode}, naming {names}: {r.stderr[-800:]}")
            expect(" run " not in r.stdout and " ref " not in r.stdout, f"{what}: no run made: {r.stdout[-500:]}")
        expect(open(p).read() == before, "a bad plan writes nothing")

        # 3. a run whose journal is not the plan's: the study fails, its error is not written
        r = subprocess.run(command(plan_file("core.yaml", set_in(
            "thickness", "reference", "recorded", "journal", "core")), "--studies", "thickness"),
            capture_output=True, text=True, cwd=d)
        expect(r.returncode != 0 and "studies.thickness.reference.recorded.journal is core" in r.stderr
               and "'end_faces'" in r.stderr,
               f"another journal's run: exit {r.returncode}: {r.stderr[-800:]}")
        after = yaml.safe_load(open(p))["presets"]
        expect(after["fast"]["measured"]["error_F_max"]["thickness"] == measured["fast"]["error_F_max"]["thickness"],
               "the failed study's error is not written")
    finally:
        if not bad:
            shutil.rmtree(d, ignore_errors=True)
        else:
            print(f"(scratch kept: {d})")

    if bad:
        print("FAILED:\n  " + "\n  ".join(bad))
        return 1
    print("measure_presets with recorded references: the largest over the sweep, each value "
          "in the where, values without a sequence named, bad plans refused: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
