#!/usr/bin/env python3
"""Coulomb friction's cost on the default mesh (issue 11 item 3; docs/benchmarks.md). Not a test.

Runs fe_stage on fe_stage/scenes/radial.yaml (t_B = 4 mm, end_faces, the default mesh) with
contact.mu and contact.active_set_scale replaced, on one or two ranks, and prints one line per
case: wall and CPU time, peak RSS of one rank, active-set iterations summed over the increments
(and their range per increment) and F(delta_max).

    bench/fe_friction_bench.py --fe-stage build/fe_stage/fe_stage [--work DIR] [CASE ...]

CASE names (default all): mu0 mu01 mu01_c10 mu01_c01 mu03 mu05 mu0_np2 mu01_np2.
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import time

CASES = [("mu0", 0, 1, 1), ("mu01", 0.1, 1, 1), ("mu01_c10", 0.1, 10, 1),
         ("mu01_c01", 0.1, 0.1, 1), ("mu03", 0.3, 1, 1), ("mu05", 0.5, 1, 1),
         ("mu0_np2", 0, 1, 2), ("mu01_np2", 0.1, 1, 2)]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fe-stage", required=True)
    ap.add_argument("--work", default="bench_friction_work")
    ap.add_argument("cases", nargs="*")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    base = open(os.path.join(root, "fe_stage", "scenes", "radial.yaml")).read()
    if not re.search(r"^contact:\s*$", base, flags=re.M):
        raise SystemExit("radial.yaml has no 'contact:' block to edit")
    os.makedirs(args.work, exist_ok=True)
    for name, mu, c_scale, ranks in CASES:
        if args.cases and name not in args.cases:
            continue
        # the scene's own contact keys are replaced by ours (a duplicate key is an input error)
        scene = re.sub(r"^contact:\s*\n(?:[ \t]+.*\n|\s*\n)*", "", base, flags=re.M)
        scene += f"contact: {{mu: {mu}, active_set_scale: {c_scale}}}\n"
        path = os.path.join(args.work, name + ".yaml")
        with open(path, "w") as f:
            f.write(scene)
        out = os.path.join(args.work, "out_" + name)
        shutil.rmtree(out, ignore_errors=True)
        cmd = [args.fe_stage, path, "--output", out, "--no-fields", "--no-plots", "-q"]
        if ranks > 1:
            cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
        t0 = time.time()
        p = subprocess.run(["/usr/bin/time", "-f", "%U %S %M"] + cmd, capture_output=True, text=True)
        wall = time.time() - t0
        if p.returncode != 0:
            print(f"{name}: fe_stage failed ({p.returncode}): {p.stderr[-1500:]}", flush=True)
            continue
        user, system, rss = p.stderr.strip().split("\n")[-1].split()
        rows = list(csv.DictReader(l for l in open(os.path.join(out, "force_penetration.csv"))
                                   if not l.startswith("#")))[1:]  # row 0 is the origin
        its = [int(float(r["contact_iterations"])) for r in rows]
        print(f"{name}: mu {mu:g}, c x{c_scale:g}, {ranks} rank(s): wall {wall:.1f} s, CPU "
              f"{float(user) + float(system):.1f} s, RSS {int(rss) // 1024} MB, {sum(its)} "
              f"active-set iterations ({min(its)}-{max(its)}), F(delta_max) = {rows[-1]['force']} N",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
