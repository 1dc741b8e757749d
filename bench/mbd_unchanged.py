#!/usr/bin/env python3
"""Does a change of mbd_stage change its results? Not a test: a check for refactorings.

Runs two mbd_stage executables (before and after a change) on the same scenes and compares
their outputs: timeseries.csv byte for byte, else column by column to a relative tolerance, and
summary.json value by value (wall_time left out: it is the one field that differs between runs
of the same code).

    bench/mbd_unchanged.py --before OLD/mbd_stage --after build/mbd_stage/mbd_stage
                           [--work DIR] [--rtol 1e-12] [SCENE.yaml ...]

Without SCENE arguments: every scene in mbd_stage/scenes/, and four variants that reach the
integrator's other paths — the damped FE-law scene with BDF (CVODE; 20 ms), Verner 6(5) and
Fehlberg 8(7) (which fails at 2.1 ms there: the failure path), and the frictionless FE-law
scene with a maximum step of 1e-5 s. Exit status 0 when every output agrees, 1 otherwise.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "mbd_stage", "scenes")

# (name, base scene, {scene text to replace: replacement})
VARIANTS = [
    ("bdf", "slider_crank_fe_law_damped.yaml",
     {"method: dopri5": "method: bdf", "duration: 0.1 ": "duration: 0.02"}),
    ("verner6", "slider_crank_fe_law_damped.yaml", {"method: dopri5": "method: verner6"}),
    ("fehlberg8", "slider_crank_fe_law_damped.yaml",
     {"method: dopri5": "method: fehlberg8"}),
    ("max_step", "slider_crank_fe_law_frictionless.yaml",
     {"max_step: 0.0 ": "max_step: 1.0e-5"}),
]


def make_variants(work):
    """Writes the variant scenes into work/variants/ (law files by absolute path)."""
    folder = os.path.join(work, "variants")
    os.makedirs(folder, exist_ok=True)
    paths = []
    for name, base, replacements in VARIANTS:
        with open(os.path.join(SCENES, base), encoding="utf-8") as f:
            text = f.read()
        for old, new in replacements.items():
            if old not in text:
                sys.exit(f"variant {name}: '{old}' not in {base}")
            text = text.replace(old, new)
        text = re.sub(r"law_file: (\S+)", lambda m: "law_file: " + os.path.normpath(
            os.path.join(os.path.abspath(SCENES), m.group(1))), text)
        text = text.replace("name: " + base[:-5], "name: " + base[:-5] + "_" + name, 1)
        path = os.path.join(folder, base[:-5] + "_" + name + ".yaml")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        paths.append(path)
    return paths


def run(exe, scene, out):
    r = subprocess.run([exe, scene, "--output", out, "--no-plots", "-q"],
                       capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


def read_csv(path):
    header, rows = None, []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                continue
            fields = line.rstrip("\n").split(",")
            if header is None:
                header = fields
            else:
                rows.append([float(x) for x in fields])
    return header, rows


def compare_csv(a, b, rtol):
    """'' if the two files agree to rtol (relative to each column's largest magnitude)."""
    with open(a, "rb") as fa, open(b, "rb") as fb:
        if fa.read() == fb.read():
            return ""
    ha, ra = read_csv(a)
    hb, rb = read_csv(b)
    if ha != hb:
        return "different columns"
    if len(ra) != len(rb):
        return f"{len(ra)} rows before, {len(rb)} after"
    worst = []
    for c, name in enumerate(ha):
        scale = max((abs(r[c]) for r in ra), default=0.0) or 1.0
        d = max((abs(x[c] - y[c]) for x, y in zip(ra, rb)), default=0.0) / scale
        if d > rtol or math.isnan(d):
            worst.append(f"{name}: {d:.3g}")
    return "" if not worst else "columns beyond rtol: " + ", ".join(worst)


def compare_json(a, b, path=""):
    """The key paths whose values differ (wall_time left out)."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            if k == "wall_time":
                continue
            if k not in a or k not in b:
                out.append(path + k)
            else:
                out += compare_json(a[k], b[k], path + k + ".")
        return out
    return [] if a == b else [path.rstrip(".")]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", required=True)
    ap.add_argument("--work", default="/tmp/mbd_unchanged")
    ap.add_argument("--rtol", type=float, default=1e-12)
    ap.add_argument("scenes", nargs="*")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    scenes = args.scenes or (
        sorted(os.path.join(SCENES, s) for s in os.listdir(SCENES) if s.endswith(".yaml")) +
        make_variants(args.work))
    bad = 0
    for scene in scenes:
        name = os.path.basename(scene)[:-5]
        outs = {}
        for which, exe in (("before", args.before), ("after", args.after)):
            out = os.path.join(args.work, which, name)
            code, err = run(exe, scene, out)
            outs[which] = (out, code, err)
        (a, ca, ea), (b, cb, eb) = outs["before"], outs["after"]
        problems = []
        if ca != cb:
            problems.append(f"exit {ca} before, {cb} after ({ea} | {eb})")
        else:
            problems.append(compare_csv(os.path.join(a, "timeseries.csv"),
                                        os.path.join(b, "timeseries.csv"), args.rtol))
            with open(os.path.join(a, "summary.json"), encoding="utf-8") as fa, \
                    open(os.path.join(b, "summary.json"), encoding="utf-8") as fb:
                diff = compare_json(json.load(fa), json.load(fb))
            if diff:
                problems.append("summary.json differs at " + ", ".join(diff))
        problems = [p for p in problems if p]
        with open(os.path.join(a, "timeseries.csv"), "rb") as fa, \
                open(os.path.join(b, "timeseries.csv"), "rb") as fb:
            same_bytes = fa.read() == fb.read()
        verdict = "FAIL " + "; ".join(problems) if problems else (
            "identical bytes" if same_bytes else f"within rtol {args.rtol:g}")
        print(f"{name}: exit {ca}, {verdict}")
        bad += bool(problems)
    print(f"{len(scenes) - bad} of {len(scenes)} scenes unchanged")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
