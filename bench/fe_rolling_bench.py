#!/usr/bin/env python3
"""Time-step and mesh convergence of the FE rolling study (issue 13 item 4). Not a test.

Runs fe_stage's rolling study for a sequence of time steps (rolling.n_steps, each level twice
the last) on one mesh, and for a sequence of nested meshes (mesh.contact_refinements: the cells
along the contact's path halved at each level) at one time step, and prints markdown tables of
the quantities at the run's end — the contact force on the journal (normal), the journal's spin
rate, the plastic dissipation — with each level's error against the Richardson value of the
three finest levels (observed order p = log2((Q0 - Q1)/(Q1 - Q2)), Q = Q2 + (Q2 - Q1)/(2^p - 1)).
The force and the spin at the end are read off a straight line fitted over the run's last
--window seconds (they move from step to step as the contact patch passes the cells; the table
gives the raw force and that noise's RMS beside it). Where the three finest levels do not
converge monotonically (the differences change sign, or shrink by less than a factor 2^0.5)
there is no usable order: the table says so and gives their spread instead. An order below 0.8
is flagged: both the time step (backward
Euler) and the mesh should give at least 1, so the levels are not yet asymptotic and the
estimate is rough.

    bench/fe_rolling_bench.py --fe-stage build/fe_stage/fe_stage [--work DIR]
        [--steps 25 50 100 200] [--steps-refinement 1]
        [--refinements 0 1 2] [--refinements-steps 50]
        [--journal core|rigid] [--delta 1e-5] [--ramp-time 0.25] [--end-time 0.25] [--ranks 1]
        [--reuse]
    bench/fe_rolling_bench.py --histories L0.csv L1.csv L2.csv [--refinements 0 1 2]

--histories tabulates finished runs as the mesh levels instead of running them: their
rolling_history.csv files, coarsest first, each level's cells along the contact's path halved
(the paper's case at 1 mm, whose finest level runs for hours on two ranks with restart files:
docs/benchmarks.md "The paper's rolling case at 1 mm"). The runs' scenes are theirs; the table
says only which files it read.

The default scene is the paper's time line (the push ramped over 0.25 s, the bearing half a
turn at 12.56 rad/s, mu = 0.3, the SPEC hardening table) with a push of 10 um instead of 1 mm
(small strain is accurate there: the largest strain stays near 0.003), on the coarse ring of the
pipeline's rolling scene (8 x 2 x 1 cells) with the deformable journal. --reuse takes a case's
output again when WORK/<case>/rolling_history.csv is complete and WORK/<case>.json is the scene
this run would write (so an interrupted sweep goes on where it stopped).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys


def scene(args, n_steps, refinements):
    return {
        "schema": "clearjoint.fe/1",
        "study": "rolling",
        "mesh": {"n_circumferential": 8, "n_radial": 1, "n_axial": 2,
                 "contact_refinements": refinements},
        "loading": {"delta_max": args.delta, "journal": args.journal},
        "rolling": {"ramp_time": args.ramp_time, "end_time": args.end_time, "n_steps": n_steps},
    }


def read_history(path):
    """The rolling history's rows and its status line, or (None, status)."""
    status = "missing"
    if not os.path.exists(path):
        return None, status
    with open(path) as f:
        lines = f.readlines()
    for line in lines:
        if line.startswith("# status:"):
            status = line.split(":", 1)[1].strip()
    rows = list(csv.DictReader(l for l in lines if not l.startswith("#")))
    return rows, status


_done = {}  # the cases run in this sweep (the time and mesh sequences share one)


def run_case(args, name, n_steps, refinements):
    """Runs (or reuses) one case; returns its rows and its wall time [s] (fe_stage's own
    clock from the start of the run to the last step: the setup and the steps, no output)."""
    if name not in _done:
        _done[name] = run_new_case(args, name, n_steps, refinements)
    return _done[name]


def run_new_case(args, name, n_steps, refinements):
    os.makedirs(args.work, exist_ok=True)
    scene_file = os.path.join(args.work, name + ".json")
    out = os.path.join(args.work, name)
    text = json.dumps(scene(args, n_steps, refinements), indent=1, sort_keys=True)
    history = os.path.join(out, "rolling_history.csv")
    if args.reuse and os.path.exists(scene_file) and open(scene_file).read() == text:
        rows, status = read_history(history)
        if rows and status.startswith("complete"):
            print(f"{name}: reused {history}", file=sys.stderr)
            return rows, float(rows[-1]["wall_time"])
    with open(scene_file, "w") as f:
        f.write(text)
    cmd = [args.fe_stage, scene_file, "-o", out, "--no-plots", "--no-fields", "-q"]
    if args.ranks > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.ranks)] + cmd
    print(f"{name}: {' '.join(cmd)}", file=sys.stderr)
    proc = subprocess.run(cmd)
    rows, status = read_history(history)
    if proc.returncode != 0 or not rows or not status.startswith("complete"):
        sys.exit(f"fe_rolling_bench: {name} failed (exit {proc.returncode}, status {status}); "
                 f"its log: {out}")
    return rows, float(rows[-1]["wall_time"])


# The force and the spin move from step to step as the contact patch passes the cells (the
# active contact points change; the force's RMS about its trend is 4 % on the default scene at
# contact refinement 1, 0.8 % at refinement 2), so their value at
# the end is also taken from a straight line fitted over the run's last `--window` seconds
# (default 0.03 s, the bearing's turn over one coarse 22.5° cell): the noise averages out, the
# trend stays. The plastic dissipation is a sum over the run and needs no fit.
QUANTITIES = [("force_normal", "F at the end, fitted [N]", "{:.1f}", True),
              ("gamma_rate", "spin at the end, fitted [rad/s]", "{:.6f}", True),
              ("plastic_dissipation", "plastic dissipation [J]", "{:.5g}", False),
              ("max_plastic_strain", "largest plastic strain", "{:.4g}", False)]


def fitted_end(rows, key, window):
    """The least-squares line through (t, key) over the last `window` seconds, at the end;
    and the residuals' RMS."""
    t_end = float(rows[-1]["time"])
    pts = [(float(r["time"]), float(r[key])) for r in rows if float(r["time"]) >= t_end - window]
    if len(pts) < 3:
        return float(rows[-1][key]), 0.0
    n = len(pts)
    mt = sum(t for t, _ in pts) / n
    mq = sum(q for _, q in pts) / n
    stt = sum((t - mt) ** 2 for t, _ in pts)
    slope = sum((t - mt) * (q - mq) for t, q in pts) / stt
    rms = math.sqrt(sum((q - mq - slope * (t - mt)) ** 2 for t, q in pts) / n)
    return mq + slope * (t_end - mt), rms


def value(case, key, fit, window):
    rows = case[0]
    return fitted_end(rows, key, window)[0] if fit else float(rows[-1][key])


def richardson(values):
    """(value, order) from the three finest levels, or (None, None) if they do not converge
    monotonically at a positive order."""
    q0, q1, q2 = values[-3:]
    d1, d2 = q1 - q0, q2 - q1
    if d1 == 0.0 or d2 == 0.0 or d1 * d2 < 0.0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log2(d1 / d2)
    if p < 0.5:  # the levels differ by about as much at each halving: no usable order
        return None, None
    return q2 + d2 / (2.0 ** p - 1.0), p


def table(title, label, levels, results, window):
    print(f"\n### {title}\n")
    print("| " + label + " | wall to the last step [s] | F at the end, raw [N] | " +
          " | ".join(q[1] + " | error" for q in QUANTITIES) + " | F noise (RMS) |")
    print("|" + "---|" * (4 + 2 * len(QUANTITIES)))
    estimates = []
    for key, _, _, fit in QUANTITIES:
        vals = [value(c, key, fit, window) for c in results]
        estimates.append((vals,) + (richardson(vals) if len(vals) >= 3 else (None, None)))
    for i, level in enumerate(levels):
        rows, wall = results[i]
        cells = [str(level), f"{wall:.1f}", f"{float(rows[-1]['force_normal']):.1f}"]
        for (key, _, fmt, _), (vals, ref, p) in zip(QUANTITIES, estimates):
            cells.append(fmt.format(vals[i]))
            cells.append(f"{100.0 * abs(vals[i] - ref) / abs(ref):.2g} %" if ref is not None else "—")
        rms = fitted_end(rows, "force_normal", window)[1]
        force = abs(float(rows[-1]["force_normal"]))
        cells.append(f"{rms:.0f} N" + (f" ({100.0 * rms / force:.2g} %)" if force > 0.0 else ""))
        print("| " + " | ".join(cells) + " |")
    print()
    for (key, name, fmt, _), (vals, ref, p) in zip(QUANTITIES, estimates):
        if len(vals) < 3:
            print(f"- {name}: fewer than three levels, no estimate")
        elif ref is not None:
            rough = " — below 0.8: not yet asymptotic, a rough estimate" if p < 0.8 else ""
            print(f"- {name}: Richardson {fmt.format(ref)} (p = {p:.2f}{rough})")
        else:
            spread = max(vals[-3:]) - min(vals[-3:])
            print(f"- {name}: the three finest levels show no order (p < 0.5 or not monotone); their spread "
                  f"{fmt.format(spread)} ({100.0 * spread / abs(vals[-1]):.2g} % of the finest)")


def histories_table(args):
    """The mesh table of finished runs (--histories), labelled by --refinements."""
    levels = args.refinements[:len(args.histories)]
    if len(levels) != len(args.histories):
        sys.exit(f"fe_rolling_bench: {len(args.histories)} histories but --refinements names "
                 f"{len(args.refinements)} levels")
    results = []
    for path in args.histories:
        rows, status = read_history(path)
        if not rows or not status.startswith("complete"):
            sys.exit(f"fe_rolling_bench: {path}: not a finished rolling history (status {status})")
        results.append((rows, float(rows[-1]["wall_time"])))
    ends = {f"{float(r[-1]['time']):.9g}" for r, _ in results}
    if len(ends) != 1:
        sys.exit(f"fe_rolling_bench: the histories end at different times ({', '.join(sorted(ends))} s)")
    table("Mesh, finished runs: " + ", ".join(args.histories), "contact_refinements", levels,
          results, args.window)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fe-stage", help="the fe_stage executable (needed unless --histories)")
    ap.add_argument("--histories", nargs="*", default=[],
                    help="rolling_history.csv of finished runs, coarsest first: tabulated as the "
                         "mesh levels (--refinements labels them), nothing is run")
    ap.add_argument("--work", default="bench_rolling_work")
    ap.add_argument("--steps", type=int, nargs="*", default=[25, 50, 100, 200],
                    help="rolling.n_steps of the time-step levels (each twice the last)")
    ap.add_argument("--steps-refinement", type=int, default=1,
                    help="mesh.contact_refinements of the time-step levels")
    ap.add_argument("--refinements", type=int, nargs="*", default=[0, 1, 2],
                    help="mesh.contact_refinements of the mesh levels")
    ap.add_argument("--refinements-steps", type=int, default=50,
                    help="rolling.n_steps of the mesh levels")
    ap.add_argument("--journal", choices=["core", "rigid"], default="core")
    ap.add_argument("--delta", type=float, default=1.0e-5, help="[m] loading.delta_max")
    ap.add_argument("--ramp-time", type=float, default=0.25, help="[s] rolling.ramp_time")
    ap.add_argument("--end-time", type=float, default=0.25, help="[s] rolling.end_time")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--window", type=float, default=0.03,
                    help="[s] the end's fit of the force and the spin spans this much of the run")
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    if args.histories:
        histories_table(args)
        return
    if not args.fe_stage:
        sys.exit("fe_rolling_bench: give --fe-stage (or --histories to tabulate finished runs)")
    if any(b != 2 * a for a, b in zip(args.steps, args.steps[1:])):
        sys.exit("fe_rolling_bench: --steps must double from level to level (Richardson)")
    if any(b != a + 1 for a, b in zip(args.refinements, args.refinements[1:])):
        sys.exit("fe_rolling_bench: --refinements must be consecutive levels (Richardson)")
    if args.steps:
        res = [run_case(args, f"steps{n}_ref{args.steps_refinement}", n, args.steps_refinement)
               for n in args.steps]
        table(f"Time steps (contact_refinements {args.steps_refinement}, {args.journal} journal, "
              f"delta {args.delta:g} m over {args.ramp_time:g} s, {args.ranks} rank(s))",
              "n_steps", args.steps, res, args.window)
    if args.refinements:
        res = [run_case(args, f"steps{args.refinements_steps}_ref{r}", args.refinements_steps, r)
               for r in args.refinements]
        table(f"Mesh (n_steps {args.refinements_steps}, {args.journal} journal, "
              f"delta {args.delta:g} m over {args.ramp_time:g} s, {args.ranks} rank(s))",
              "contact_refinements", args.refinements, res, args.window)


if __name__ == "__main__":
    main()
