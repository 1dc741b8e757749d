"""The pipeline's HTML report: one self-contained file (figures embedded as PNG data, no network
resources) with the fitted laws, their trends, the MBD results, stage wall times and links.

    plot.py report out/<run>/pipeline_summary.json --output out/<run>/report.html
"""
import argparse
import base64
import glob
import html
import io
import json
import math
import os

import matplotlib.pyplot as plt

from plotting._common import read_table


def figure_html(fig, caption):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    data = base64.b64encode(buf.getvalue()).decode()
    return (f'<figure><img src="data:image/png;base64,{data}" alt="{html.escape(caption)}">'
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def image_file_html(path, caption):
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode()
    return (f'<figure><img src="data:image/png;base64,{data}" alt="{html.escape(caption)}">'
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def load(path):
    with open(path) as f:
        return json.load(f)


def shown(value, unit):
    if unit == "rad":
        return value * 180 / math.pi, "°"
    if unit == "deg":
        return value, "°"
    if unit == "m":
        return value * 1e3, "mm"
    return value, unit


def case_label(study, case):
    """'t_B = 4 mm', or 'theta = θ_max = 3.2842 °' for a value given by a keyword."""
    v, u = shown(case["value"], study["unit"])
    keyword = case.get("keyword")
    middle = f"{keyword} = " if keyword else ""
    return f"{study['parameter']} = {middle}{v:.5g} {u}"


def rel(path, base):
    return os.path.relpath(path, base)


def study_section(study, base):
    out = [f"<h2>FE study “{html.escape(study['name'])}”: F–δ and fitted laws over "
           f"{html.escape(study['parameter'])}</h2>"]
    laws = []
    for case in study["cases"]:
        if os.path.exists(case["law"]):
            laws.append((case, load(case["law"])))
    if not laws:
        return "".join(out) + "<p>No fitted laws found.</p>"
    unit = study["unit"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for case, law in laws:
        K, n = law["law"]["K"], law["law"]["n"]
        d = law["diagnostics"]
        top = law["valid_range"]["delta_max"]
        xs = [top * i / 100 for i in range(101)]
        line, = ax.plot([x * 1e3 for x in xs], [K * x ** n for x in xs], "-",
                        label=case_label(study, case))
        if d:
            ax.plot([x * 1e3 for x in d["delta"]], d["force"], "o", ms=3, color=line.get_color())
    ax.set_xlabel("penetration δ [mm]")
    ax.set_ylabel("contact force F [N]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    out.append(figure_html(fig, f"FE force–penetration data (points) and fits F = K·δ^n (lines), "
                                f"study {study['name']}"))

    # Trends with 95 % intervals: n directly; F_ref rather than K (K and n are correlated).
    values = [shown(c["value"], unit)[0] for c, _ in laws]
    u = shown(1.0, unit)[1]
    ns = [l["law"]["n"] for _, l in laws]
    n_lo = [l["diagnostics"]["n_ci95"][0] if l["diagnostics"] else l["law"]["n"] for _, l in laws]
    n_hi = [l["diagnostics"]["n_ci95"][1] if l["diagnostics"] else l["law"]["n"] for _, l in laws]
    Ks = [l["law"]["K"] for _, l in laws]
    K_lo = [l["diagnostics"]["K_ci95"][0] if l["diagnostics"] else l["law"]["K"] for _, l in laws]
    K_hi = [l["diagnostics"]["K_ci95"][1] if l["diagnostics"] else l["law"]["K"] for _, l in laws]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    a1.errorbar(values, [k / 1e8 for k in Ks],
                yerr=[[(k - lo) / 1e8 for k, lo in zip(Ks, K_lo)], [(hi - k) / 1e8 for k, hi in zip(Ks, K_hi)]],
                fmt="o-", capsize=4)
    a1.set_xlabel(f"{study['parameter']} [{u}]")
    a1.set_ylabel("K [1e8 N/m^n] (95 % CI)")
    a1.grid(True, alpha=0.3)
    a2.errorbar(values, ns, yerr=[[n - lo for n, lo in zip(ns, n_lo)], [hi - n for n, hi in zip(ns, n_hi)]],
                fmt="s-", color="C3", capsize=4)
    a2.set_xlabel(f"{study['parameter']} [{u}]")
    a2.set_ylabel("exponent n (95 % CI)")
    a2.grid(True, alpha=0.3)
    fig.tight_layout()
    out.append(figure_html(fig, f"K and n against {study['parameter']} with 95 % confidence intervals"))

    out.append("<table><tr><th>case</th><th>K [N/mm^n] (δ in mm)</th><th>K [N/m^n] (SI)</th>"
               "<th>n</th><th>n 95 % CI</th><th>F_ref [N] at δ_ref</th><th>R²</th><th>files</th></tr>")
    for case, law in laws:
        d = law["diagnostics"] or {}
        n_ci = d.get("n_ci95", [float("nan")] * 2)
        ref = law["reference"]
        links = [f'<a href="{html.escape(rel(case["law"], base))}">law</a>',
                 f'<a href="{html.escape(rel(os.path.join(case["fe_dir"], "force_penetration.csv"), base))}">CSV</a>']
        pvd = sorted(glob.glob(os.path.join(case["fe_dir"], "**", "*.pvd"), recursive=True))
        if pvd:
            links.append(f'<a href="{html.escape(rel(pvd[0], base))}">fields (ParaView)</a>')
        if case.get("mesh"):
            links.append(f'<a href="{html.escape(rel(case["mesh"], base))}">mesh</a>')
        out.append(f"<tr><td>{html.escape(case_label(study, case))}</td>"
                   f"<td>{law['mm_N']['K']:.6g}</td><td>{law['law']['K']:.6g}</td>"
                   f"<td>{law['law']['n']:.5f}</td><td>{n_ci[0]:.5f} … {n_ci[1]:.5f}</td>"
                   f"<td>{ref['F_ref']:.6g} at {ref['delta_ref'] * 1e3:.4g} mm</td>"
                   f"<td>{d.get('r_squared', float('nan')):.6f}</td><td>{' · '.join(links)}</td></tr>")
    out.append("</table>")
    if study.get("family"):
        out.append(f"<p>Law family over {html.escape(study['parameter'])} (parameter stored in "
                   f"{html.escape(study.get('family_unit', unit))}, SI): "
                   f'<a href="{html.escape(rel(study["family"], base))}">'
                   f"{html.escape(os.path.basename(study['family']))}</a>.</p>")
    return "".join(out)


def preset_section(summary):
    """Every preset's measured cost and error of F(δ_max) per FE study; the chosen one marked."""
    presets = summary.get("presets") or []
    if not presets:
        return ""
    studies = [s["name"] for s in summary["studies"]]
    for p in presets:
        for name in ((p.get("measured") or {}).get("error_F_max") or {}):
            if name not in studies:
                studies.append(name)

    def quantity(q, fmt):
        return "not measured" if not q else fmt.format(q["value"])

    rows = ["<h2>Presets: measured cost and error</h2>",
            "<p>Estimated relative error of the force at δ_max per FE study (against a Richardson "
            "extrapolation over the mesh levels) and cost, as measured "
            "(docs/benchmarks.md). “not yet measured” means no number exists yet.</p>",
            "<table><tr><th>preset</th><th>FE scene settings</th><th>FE DoFs</th>"
            "<th>one FE curve [s]</th><th>whole pipeline [s]</th>" +
            "".join(f"<th>error F(δ_max), {html.escape(s)}</th>" for s in studies) +
            "<th>source</th></tr>"]
    for p in presets:
        m = p.get("measured") or {}
        errors = m.get("error_F_max") or {}
        cells = []
        for s in studies:
            e = errors.get(s)
            if e is None:
                cells.append("<td>not stated</td>")
            elif e["percent"] is None:
                cells.append(f"<td title='{html.escape(e['where'])}'><em>not yet measured</em></td>")
            else:
                cells.append(f"<td title='{html.escape(e['where'])}'>{e['percent']:.3g} %</td>")
        settings = ", ".join(f"{k} = {v}" for k, v in sorted((p.get("fe") or {}).items())) or "defaults"
        name = html.escape(p["name"]) + (" <strong>(this run)</strong>" if p.get("chosen") else "")
        style = " style='background:#ffe9b3'" if p.get("chosen") else ""
        rows.append(f"<tr{style}><td>{name}</td><td>{html.escape(settings)}</td>"
                    f"<td>{quantity(m.get('fe_dofs'), '{:.0f}')}</td>"
                    f"<td>{quantity(m.get('fe_case_time'), '{:.3g}')}</td>"
                    f"<td>{quantity(m.get('pipeline_time'), '{:.0f}')}</td>" + "".join(cells) +
                    f"<td>{html.escape(m.get('note', 'no measurements stated'))}</td></tr>")
    rows.append("</table>")
    wheres = sorted({(s, e["where"]) for p in presets
                     for s, e in ((p.get("measured") or {}).get("error_F_max") or {}).items()})
    if wheres:
        rows.append("<p>Where each error was measured: " +
                    "; ".join(f"{html.escape(s)}: {html.escape(w)}" for s, w in wheres) + ".</p>")
    return "".join(rows)


def mbd_section(runs, base):
    out = ["<h2>Multibody simulations</h2>"]
    series = []
    for r in runs:
        csv = os.path.join(r["dir"], "timeseries.csv")
        if os.path.exists(csv):
            _, units, data = read_table(csv)
            series.append((r["name"], data))
    for column, label in (("slider_velocity", "slider velocity [m/s]"),
                          ("slider_acceleration", "slider acceleration [m/s²]")):
        have = [(n, d) for n, d in series if column in d and "t" in d]
        if not have:
            continue
        fig, ax = plt.subplots(figsize=(9, 4))
        for name, d in have:
            ax.plot(d["t"], d[column], lw=1, label=name)
        ax.set_xlabel("time t [s]")
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        out.append(figure_html(fig, f"{label} of every MBD run overlaid (the paper's Figs. 14–17)"))
    for r in runs:
        out.append(band_figure(r))
    out.append("<table><tr><th>run</th><th>summary</th><th>files</th></tr>")
    for r in runs:
        summary = os.path.join(r["dir"], "summary.json")
        text = ""
        if os.path.exists(summary):
            s = load(summary)
            peaks = s.get("peaks", {})
            text = ", ".join(f"{k} = {v:.4g}" for k, v in peaks.items() if isinstance(v, (int, float)))
        links = " · ".join(f'<a href="{html.escape(rel(p, base))}">{html.escape(os.path.basename(p))}</a>'
                           for p in (os.path.join(r["dir"], f) for f in ("timeseries.csv", "summary.json"))
                           if os.path.exists(p))
        out.append(f"<tr><td>{html.escape(r['name'])}</td><td>{html.escape(text)}</td><td>{links}</td></tr>")
    out.append("</table>")
    for r in runs:
        for png in sorted(glob.glob(os.path.join(r["dir"], "plots", "*.png"))):
            out.append(image_file_html(png, f"{r['name']}: {os.path.basename(png)}"))
    return "".join(out)


def band_figure(run):
    """Nominal response and the envelope of the runs with the law's 95 % band variants."""
    if not run.get("band"):
        return ""
    import numpy as np
    nominal = os.path.join(run["dir"], "timeseries.csv")
    if not os.path.exists(nominal):
        return ""
    _, _, d0 = read_table(nominal)
    if "slider_velocity" not in d0:
        return ""
    t = np.array(d0["t"])
    curves = []
    for b in run["band"]:
        csv = os.path.join(b["dir"], "timeseries.csv")
        if os.path.exists(csv):
            _, _, d = read_table(csv)
            curves.append(np.interp(t, d["t"], d["slider_velocity"]))
    if not curves:
        return ""
    lo, hi = np.min(curves, axis=0), np.max(curves, axis=0)
    fig, ax = plt.subplots(figsize=(9, 4))
    ax.fill_between(t, lo, hi, color="C1", alpha=0.35, label="K, n across their 95 % region")
    ax.plot(t, d0["slider_velocity"], "k-", lw=1, label="fitted law")
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("slider velocity [m/s]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    width = float(np.max(hi - lo))
    return figure_html(fig, f"{run['name']}: response band from the fit's uncertainty "
                            f"(largest width {width:.3g} m/s; variants: "
                            f"{', '.join(b['variant'] for b in run['band'])})")


def timing_section(summary):
    rows = ["<h2>Wall time of each stage</h2><table><tr><th>task</th><th>outcome</th>"
            "<th>wall time [s]</th></tr>"]
    totals = {}
    for t in summary["tasks"]:
        w = t["wall_time"]["value"]
        totals[t["stage"]] = totals.get(t["stage"], 0.0) + w
        rows.append(f"<tr><td>{html.escape(t['name'])}</td><td>{t['outcome']}</td><td>{w:.2f}</td></tr>")
    rows.append("</table><p>Totals (time of the run that produced each result): " +
                ", ".join(f"{k}: {v:.1f} s" for k, v in sorted(totals.items())) + "</p>")
    return "".join(rows)


CSS = """body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}
table{border-collapse:collapse;margin:1em 0;font-size:90%}td,th{border:1px solid #bbb;padding:3px 8px}
th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:90%;color:#555}"""


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py report")
    p.add_argument("summary")
    p.add_argument("--output", required=True)
    a = p.parse_args(argv)
    summary = load(a.summary)
    base = os.path.dirname(os.path.abspath(a.output))
    parts = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>clearjoint report — "
             f"{html.escape(summary['run'])}</title><style>{CSS}</style></head><body>",
             f"<h1>clearjoint report: run “{html.escape(summary['run'])}”, preset "
             f"{html.escape(summary['preset'])}</h1>",
             f"<p>Pipeline file: {html.escape(summary['pipeline_file'])}. Laws are shown in SI "
             f"(δ in m, F in N) and in the paper's units (δ in mm, F in N).</p>"]
    parts.append(preset_section(summary))
    for study in summary["studies"]:
        parts.append(study_section(study, base))
    if summary["mbd_runs"]:
        parts.append(mbd_section(summary["mbd_runs"], base))
    parts.append(timing_section(summary))
    parts.append("</body></html>")
    tmp = a.output + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(parts))
    os.replace(tmp, a.output)
    return 0
