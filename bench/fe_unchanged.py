#!/usr/bin/env python3
"""Checks that a change to fe_stage's code left its results unchanged (issue 29 item 3).

Runs a set of small scenes — radial (rigid journal with friction, deformable journal by mortar,
finite sliding, adaptive cycles), misalignment, Hertz and patch blocks, impact (rigid and
deformable journal) and rolling (rigid and deformable journal, elastoplastic; and the paper's
1 mm push in finite strain) — and keeps every CSV they write. `record` stores them as the reference (run it with the binary from before the
change); `compare` runs them again and compares every numeric column of every CSV with the
reference, to 1e-12 of the column's largest magnitude (round-off of sums in another order
stays far below; any change of the numerical path shows above). Wall-time columns are skipped.

    bench/fe_unchanged.py --fe-stage OLD/fe_stage record /tmp/fe_ref
    bench/fe_unchanged.py --fe-stage build/fe_stage/fe_stage compare /tmp/fe_ref
    bench/fe_unchanged.py ... --only impact_rigid rolling_rigid   (a subset)

Exit 0 when every column matches, 1 when one differs (each listed), 2 on bad use or a run
that failed. Takes about 3 minutes on 2 cores (--np 2 runs each scene on two MPI ranks).
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

COARSE = "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 1}\n"
SCENES = {
    "radial_rigid_friction":
        "study: radial\ncontact: {mu: 0.1}\n" + COARSE +
        "loading: {journal: rigid, n_increments: 4}\n",
    "radial_mortar_friction":
        "study: radial\ncontact: {mu: 0.1}\n" + COARSE +
        "loading: {journal: end_faces, n_increments: 3}\n",
    "radial_finite_sliding":
        "study: radial\ncontact: {mu: 0.1, sliding: finite}\n" + COARSE +
        "loading: {journal: core, n_increments: 3, axial_slide: 2.0e-5}\n",
    "radial_adaptive":
        "study: radial\ncontact: {mu: 0}\n"
        "mesh: {n_circumferential: 16, n_axial: 3, contact_refinements: 0, adaptive_cycles: 2}\n"
        "loading: {journal: rigid, n_increments: 2}\n",
    "misalignment_rigid":
        "study: misalignment\ncontact: {mu: 0.1}\n" + COARSE +
        "loading: {journal: rigid, n_increments: 3}\nmisalignment: {theta_deg: 1.0}\n",
    "hertz":
        "study: hertz\ncontact: {mu: 0}\nloading: {n_increments: 3}\n"
        "verification: {contact_refinements: 2}\n",
    "patch_friction":
        "study: patch\ncontact: {mu: 0.1}\nloading: {n_increments: 2}\n"
        "verification: {n_cells: 2, contact_refinements: 1, indenter: deformable}\n",
    "impact_rigid":
        "study: impact\ncontact: {mu: 0.1}\n" + COARSE +
        "loading: {journal: rigid}\nimpact: {velocity: 0.1, steps_per_period: 20}\n",
    "impact_deformable":
        "study: impact\ncontact: {mu: 0}\n" + COARSE +
        "loading: {journal: end_faces}\nimpact: {velocity: 0.1, steps_per_period: 20}\n",
    # (small strain stated: the references before the rolling study's default became finite
    # were recorded with it)
    "rolling_rigid":
        "study: rolling\n"
        "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
        "material: {kinematics: small}\n"
        "loading: {delta_max: 1.0e-5, journal: rigid}\n"
        "rolling: {n_steps: 8, ramp_time: 0.02, end_time: 0.04}\n",
    "rolling_deformable":
        "study: rolling\n"
        "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 1}\n"
        "material: {kinematics: small}\n"
        "loading: {delta_max: 1.0e-5, journal: core}\n"
        "rolling: {n_steps: 8, ramp_time: 0.02, end_time: 0.04}\n",
    # the paper's push (1 mm over 0.25 s) in finite strain on the coarsest ring, 32 steps
    "rolling_finite_paper":
        "study: rolling\n"
        "mesh: {n_circumferential: 8, n_radial: 1, n_axial: 2, contact_refinements: 0}\n"
        "material: {kinematics: finite}\n"
        "rolling: {n_steps: 32}\n",
}
RELATIVE = 1e-12
SKIPPED = ("wall_time", "setup_time", "time_assembly", "time_solve")
# The BLAS must not be a variable of the comparison: OpenBLAS (the machine's BLAS since
# 2026-11-29, for MUMPS's dense fronts) rounds differently from ATLAS (results ~1e-7 apart
# where a Krylov iteration count changes), and a helper saw two runs of one binary differ at
# ~1e-11 on it (four scenes run twice on it later were identical). So the scenes run on ATLAS,
# installed beside it by deal.II's dependencies, whenever it is there — the reference and the
# comparison alike — and 1e-12 still tells a change of the code.
ATLAS = "/usr/lib/x86_64-linux-gnu/atlas"


def run_env():
    env = dict(os.environ)
    if os.path.isfile(os.path.join(ATLAS, "libblas.so.3")):
        env["LD_LIBRARY_PATH"] = ATLAS + (":" + env["LD_LIBRARY_PATH"]
                                          if env.get("LD_LIBRARY_PATH") else "")
    return env


def run_scene(fe_stage, name, body, out, np):
    os.makedirs(out, exist_ok=True)
    scene = os.path.join(out, "scene.yaml")
    with open(scene, "w") as f:
        f.write("schema: clearjoint.fe/1\n" + body)
    cmd = [fe_stage, scene, "--output", os.path.join(out, "run"), "--no-fields", "--no-plots"]
    if np > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np)] + cmd
    t0 = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env=run_env())
    with open(os.path.join(out, "log.txt"), "w") as f:
        f.write(p.stdout)
    if p.returncode != 0:
        sys.exit(f"fe_unchanged: scene {name} failed (exit {p.returncode}); log: "
                 f"{os.path.join(out, 'log.txt')}\n" + p.stdout[-2000:])
    print(f"  {name}: {time.time() - t0:.1f} s", flush=True)


def csv_files(folder):
    found = []
    for root, _, files in os.walk(os.path.join(folder, "run")):
        for f in files:
            if f.endswith(".csv"):
                found.append(os.path.relpath(os.path.join(root, f), folder))
    return sorted(found)


def read_table(path):
    with open(path) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], rows[1:]


def as_number(text):
    try:
        return float(text)
    except ValueError:
        return None


def compare_table(ref_path, new_path, label):
    head_ref, rows_ref = read_table(ref_path)
    head_new, rows_new = read_table(new_path)
    problems = []
    if head_ref != head_new:
        return [f"{label}: columns differ: {head_ref} vs {head_new}"]
    if len(rows_ref) != len(rows_new):
        return [f"{label}: {len(rows_ref)} rows in the reference, {len(rows_new)} now"]
    for j, name in enumerate(head_ref):
        if any(name.startswith(s) for s in SKIPPED):
            continue
        ref = [r[j] if j < len(r) else "" for r in rows_ref]
        new = [r[j] if j < len(r) else "" for r in rows_new]
        num_ref = [as_number(v) for v in ref]
        num_new = [as_number(v) for v in new]
        if any(v is None for v in num_ref) or any(v is None for v in num_new):
            if ref != new:
                problems.append(f"{label}: column {name} (text) differs")
            continue
        scale = max([abs(v) for v in num_ref if math.isfinite(v)] + [0.0])
        worst, where = 0.0, -1
        for i, (a, b) in enumerate(zip(num_ref, num_new)):
            if math.isnan(a) and math.isnan(b):
                continue
            d = abs(a - b) if math.isfinite(a) and math.isfinite(b) else (0.0 if a == b else math.inf)
            if d > worst:
                worst, where = d, i
        if worst > RELATIVE * scale:
            problems.append(f"{label}: column {name}: largest difference {worst:.3g} "
                            f"({worst / scale if scale > 0 else math.inf:.3g} of the column's "
                            f"largest |value| {scale:.6g}) at row {where + 1}: "
                            f"{ref[where]} -> {new[where]}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fe-stage", required=True, help="the fe_stage executable to run")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per scene (default 1)")
    ap.add_argument("--only", nargs="*", help="run only these scenes (names: --list)")
    ap.add_argument("--list", action="store_true", help="list the scenes and exit")
    ap.add_argument("mode", nargs="?", choices=["record", "compare"])
    ap.add_argument("reference", nargs="?", help="the reference folder")
    a = ap.parse_args()
    if a.list:
        print("\n".join(SCENES))
        return 0
    if not a.mode or not a.reference:
        ap.error("give the mode (record or compare) and the reference folder")
    if not os.access(a.fe_stage, os.X_OK):
        ap.error(f"--fe-stage {a.fe_stage}: not an executable file")
    names = a.only or list(SCENES)
    unknown = [n for n in names if n not in SCENES]
    if unknown:
        ap.error(f"unknown scene(s) {unknown}; valid: {list(SCENES)}")
    if a.mode == "record":
        for n in names:  # (only the named scenes' folders are replaced)
            if os.path.exists(os.path.join(a.reference, n)):
                shutil.rmtree(os.path.join(a.reference, n))
            run_scene(a.fe_stage, n, SCENES[n], os.path.join(a.reference, n), a.np)
        print(f"fe_unchanged: recorded {len(names)} scenes in {a.reference}")
        return 0
    problems, n_tables = [], 0
    with tempfile.TemporaryDirectory(prefix="fe_unchanged.") as tmp:
        for n in names:
            ref_dir = os.path.join(a.reference, n)
            if not os.path.isdir(ref_dir):
                sys.exit(f"fe_unchanged: no reference for scene {n} in {a.reference} (record it)")
            new_dir = os.path.join(tmp, n)
            run_scene(a.fe_stage, n, SCENES[n], new_dir, a.np)
            ref_files, new_files = csv_files(ref_dir), csv_files(new_dir)
            if ref_files != new_files:
                problems.append(f"{n}: CSV files differ: {ref_files} vs {new_files}")
            for f in sorted(set(ref_files) & set(new_files)):
                n_tables += 1
                problems += compare_table(os.path.join(ref_dir, f), os.path.join(new_dir, f),
                                          f"{n}/{f}")
    for p in problems:
        print("DIFFERS " + p)
    print(f"fe_unchanged: {len(names)} scenes, {n_tables} CSV files, "
          f"{len(problems)} differences (tolerance {RELATIVE:g} of each column's scale)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
