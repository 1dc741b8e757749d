#!/usr/bin/env python3
"""FE stage speed against accuracy (issue 3 item 9; SPEC §5). Not a test.

Runs fe_stage on the t_B = 4 mm radial study for nested mesh levels (level L = L global
refinements of the base mesh n_circumferential 8, n_axial 2, n_radial 1, one extra refinement in
the contact window, Q2), for each journal loading and rank count asked for, and prints a
markdown table: DoFs, wall time, peak memory (max RSS of one rank, from /usr/bin/time -v),
F(delta_max), and the error of F(delta_max) estimated by Richardson extrapolation from the three
finest levels (observed order p = log2((F0 - F1)/(F1 - F2))).

    bench/fe_bench.py --fe-stage build/fe_stage/fe_stage [--levels 0 1 2] [--ranks 1 2]
                      [--journals end_faces rigid] [--increments 10] [--work DIR]
                      [--study radial|misalignment] [--theta DEG] [--mu MU] [--pairing node_to_node|mortar]
                      [--plot FILE.png]

--pairing chooses how the deformable journal meets the bore (contact.pairing; default
automatic = mortar; node_to_node pairs the generated meshes' nodes on common rays). --mu is
Coulomb's coefficient (default 0, frictionless; 0.1 the paper's). The table gives the
active-set iterations summed over the increments beside the wall time.

--study misalignment runs the tilted journal (rigid, or deformable with --journals core) at
--theta degrees on the same mesh levels (half model). --plot draws DoFs and wall time against the estimated error (matplotlib; run
with /usr/bin/python3 where the default python3 lacks it).

Every loading runs on any number of ranks (the forces agree with one rank to 1e-6).

--adaptive N also runs the base mesh (level 0) with N adaptive cycles (mesh.adaptive_cycles) per
journal and rank count: a row per marking mesh and one for the recorded curve's mesh, whose
error is taken against the uniform levels' Richardson value, beside the run's own estimate.
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys


def run_case(args, journal, level, ranks, adaptive=0):
    """One fe_stage run on mesh level `level`, or (adaptive > 0) on the base mesh with that many
    adaptive cycles before the recorded curve."""
    name = f"{args.study}_{journal}_mu{args.mu:g}_{args.pairing}_" + \
        (f"A{adaptive}" if adaptive else f"L{level}") + f"_np{ranks}"
    out = os.path.join(args.work, name)
    scene = os.path.join(args.work, name + ".yaml")
    with open(scene, "w") as f:
        if args.study == "misalignment":
            f.write(f"study: misalignment\nmisalignment: {{theta_deg: {args.theta}}}\n")
        f.write(f"schema: clearjoint.fe/1\ncontact: {{mu: {args.mu}, pairing: {args.pairing}}}\noutput: {{fields: false}}\n"
                "solver: {linear: cg_amg}\n"
                f"mesh: {{n_circumferential: 8, n_axial: 2, n_radial: 1, contact_refinements: 1, "
                f"global_refinements: {level}, adaptive_cycles: {adaptive}}}\n"
                f"loading: {{journal: {journal}, n_increments: {args.increments}}}\n")
    cmd = ["/usr/bin/time", "-v"]
    if ranks > 1:
        cmd += ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)]
    cmd += [args.fe_stage, scene, "--output", out, "-q"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print(f"{name}: fe_stage failed ({p.returncode}):\n{p.stderr[-2000:]}", file=sys.stderr)
        return None
    rss = max(int(m) for m in re.findall(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr))
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", p.stderr).group(1)
    parts = [float(x) for x in wall.split(":")]
    wall_s = parts[-1] + 60 * parts[-2] + (3600 * parts[-3] if len(parts) > 2 else 0)
    with open(os.path.join(out, "manifest.json")) as f:
        manifest = json.load(f)
    rows = [r for r in csv.reader(l for l in open(os.path.join(out, "force_penetration.csv"))
                                  if not l.startswith("#"))]
    force = float(rows[-1][rows[0].index("force")])
    iterations = sum(int(float(r[rows[0].index("contact_iterations")])) for r in rows[1:])
    result = {"journal": journal, "level": level, "ranks": ranks, "dofs": manifest["extra"]["n_dofs"],
              "wall": wall_s, "rss_mb": rss / 1024.0, "force": force, "iterations": iterations}
    if adaptive:
        a = manifest["extra"]["adaptive"]
        result["level"] = f"adaptive {adaptive}"
        result["cycles"] = [(c["n_dofs"], c["force_at_delta_max"]["value"], c["contact_iterations"],
                             c["wall_time"]["value"]) for c in a["cycles"]]
        est = a.get("estimated_error_F_max")
        result["own_estimate"] = est["value"] if est else None
        # the marking meshes' iterations are not in the curve's CSV
        result["iterations"] = sum(c[2] for c in result["cycles"])
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fe-stage", help="the fe_stage executable (not needed with --from-table)")
    ap.add_argument("--from-table", metavar="FILE",
                    help="redraw --plot from the markdown table this script printed (rows "
                         "'| journal | ranks | level | ... | est. error |' in FILE), run nothing")
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--journals", nargs="+", default=["end_faces", "rigid"])
    ap.add_argument("--increments", type=int, default=10)
    ap.add_argument("--work", default="bench_fe_work")
    ap.add_argument("--study", choices=["radial", "misalignment"], default="radial")
    ap.add_argument("--theta", type=float, default=1.0, help="[deg] misalignment angle")
    ap.add_argument("--mu", type=float, default=0.0, help="Coulomb friction coefficient")
    ap.add_argument("--pairing", choices=["automatic", "node_to_node", "mortar"], default="automatic",
                    help="contact.pairing of a deformable journal")
    ap.add_argument("--plot", help="PNG: DoFs and wall time against the estimated error")
    ap.add_argument("--adaptive", type=int, default=0, metavar="CYCLES",
                    help="also run the base mesh with this many adaptive cycles (mesh.adaptive_cycles) "
                         "per journal and rank count; its error is taken against the uniform levels' "
                         "Richardson value, beside the run's own estimate")
    args = ap.parse_args()
    if args.from_table:
        return replot(args)
    if not args.fe_stage:
        ap.error("--fe-stage is required (or --from-table FILE)")
    if args.study == "misalignment":
        # the tilted journal is rigid or pushed at its core (SPEC §2: no driven rim)
        args.journals = [j for j in args.journals if j in ("rigid", "core")] or ["rigid"]
    os.makedirs(args.work, exist_ok=True)
    results = []
    for journal in args.journals:
        for ranks in args.ranks:
            for level in args.levels + ([None] if args.adaptive else []):
                r = run_case(args, journal, 0 if level is None else level, ranks,
                             adaptive=args.adaptive if level is None else 0)
                if r:
                    results.append(r)
                    print(f"# {journal} {r['level']} np{ranks}: {r['dofs']} DoFs, {r['wall']:.1f} s, "
                          f"F = {r['force']:.1f} N", file=sys.stderr, flush=True)
    print(f"study {args.study}" + (f", theta = {args.theta} deg" if args.study == "misalignment" else "")
          + f", mu = {args.mu:g}, pairing {args.pairing}")
    print("| journal | ranks | level | DoFs | wall time [s] | peak RSS/rank [MB] | F(δ_max) [N] | est. error | active-set iterations |")
    print("|---|---|---|---|---|---|---|---|---|")
    for journal in args.journals:
        for ranks in args.ranks:
            rs = sorted((r for r in results if r["journal"] == journal and r["ranks"] == ranks
                         and "cycles" not in r), key=lambda r: r["level"])
            adaptive = [r for r in results if r["journal"] == journal and r["ranks"] == ranks
                        and "cycles" in r]
            F_inf, p = None, None
            if len(rs) >= 3:
                F0, F1, F2 = (r["force"] for r in rs[-3:])
                if (F0 - F1) * (F1 - F2) > 0:
                    p = math.log2((F0 - F1) / (F1 - F2))
                    F_inf = F2 + (F2 - F1) / (2 ** p - 1)
            for r in rs:
                r["error"] = abs(r["force"] - F_inf) / abs(F_inf) if F_inf else None
                err = f"{r['error'] * 100:.2f} %" if F_inf else "n/a"
                print(f"| {journal} | {ranks} | {r['level']} | {r['dofs']} | {r['wall']:.1f} | "
                      f"{r['rss_mb']:.0f} | {r['force']:.1f} | {err} | {r['iterations']} |")
            if F_inf:
                print(f"| {journal} | {ranks} | Richardson | | | | {F_inf:.1f} | p = {p:.2f} |")
            for r in adaptive:
                # each marking mesh, then the recorded curve's mesh (the whole run's time and memory)
                for k, (dofs, force, its, wall) in enumerate(r["cycles"]):
                    err = f"{abs(force - F_inf) / abs(F_inf) * 100:.2f} %" if F_inf else "n/a"
                    last = k + 1 == len(r["cycles"])
                    label = f"{r['level']}: " + ("curve" if last else f"mesh {k}")
                    cost = f"{r['wall']:.1f} (run)" if last else f"{wall:.1f}"
                    rss = f"{r['rss_mb']:.0f}" if last else ""
                    own = (f" (own estimate {r['own_estimate'] * 100:.2f} %)"
                           if last and r["own_estimate"] is not None else "")
                    print(f"| {journal} | {ranks} | {label} | {dofs} | {cost} | {rss} | {force:.1f} | "
                          f"{err}{own} | {its} |")
                r["error"] = abs(r["force"] - F_inf) / abs(F_inf) if F_inf else None
    if args.plot:
        plot(args, results)
    return 0


def replot(args):
    """--plot from a table printed earlier: the measured rows are not re-run."""
    row = re.compile(r"^\|\s*(\w+)\s*\|\s*(\d+)\s*\|\s*(\d+)\s*\|\s*(\d+)\s*\|\s*([\d.]+)\s*\|"
                     r"\s*([\d.]+)\s*\|\s*([\d.]+)\s*\|\s*([\d.]+)\s*%\s*\|")
    # an adaptive run's curve row: '| end_faces | 2 | adaptive 3: curve | 41115 | 33.9 (run) | ...'
    adaptive_row = re.compile(r"^\|\s*(\w+)\s*\|\s*(\d+)\s*\|\s*(adaptive \d+): curve\s*\|\s*(\d+)\s*\|"
                              r"\s*([\d.]+) \(run\)\s*\|\s*([\d.]+)\s*\|\s*([\d.]+)\s*\|\s*([\d.]+)\s*%")
    results = []
    with open(args.from_table) as f:
        for line in f:
            a = adaptive_row.match(line.strip())
            if a:
                results.append({"journal": a.group(1), "ranks": int(a.group(2)), "level": a.group(3),
                                "cycles": [], "dofs": int(a.group(4)), "wall": float(a.group(5)),
                                "force": float(a.group(7)), "error": float(a.group(8)) / 100})
            m = row.match(line.strip())
            if m:
                results.append({"journal": m.group(1), "ranks": int(m.group(2)),
                                "level": int(m.group(3)), "dofs": int(m.group(4)),
                                "wall": float(m.group(5)), "force": float(m.group(7)),
                                "error": float(m.group(8)) / 100})
    if not results or not args.plot:
        print("--from-table needs a table with measured rows and --plot", file=sys.stderr)
        return 1
    args.journals = sorted({r["journal"] for r in results}, key=lambda j: j != "end_faces")
    args.ranks = sorted({r["ranks"] for r in results})
    plot(args, results)
    return 0


def plot(args, results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for journal in args.journals:
        for ranks in args.ranks:
            for adaptive in (False, True):
                rs = [r for r in results if r["journal"] == journal and r["ranks"] == ranks
                      and r.get("error") and ("cycles" in r) == adaptive]
                if not rs:
                    continue
                label = f"{journal}, {ranks} rank{'s' if ranks > 1 else ''}"
                label += f", {rs[0]['level']} cycles" if adaptive else ", uniform levels"
                e = [r["error"] * 100 for r in rs]
                style = "s" if adaptive else "o-"
                # cost on x, error on y, both growing away from the origin: no reversed axis
                ax1.loglog([r["dofs"] for r in rs], e, style, label=label)
                ax2.loglog([r["wall"] for r in rs], e, style, label=label)
    title = args.study + (f", θ = {args.theta}°" if args.study == "misalignment" else ", t_B = 4 mm")
    title += f", μ = {args.mu:g}" if args.mu else ", frictionless"
    for ax, x in ((ax1, "DoFs [1]"), (ax2, "wall time [s]")):
        ax.set_xlabel(x)
        ax.set_ylabel("estimated error of F(δ_max) [%] (Richardson)")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
            axis.set_minor_formatter(NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        ax.set_title(title)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=120)
    print(f"# wrote {args.plot}", file=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
