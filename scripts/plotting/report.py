"""The pipeline's HTML report: one self-contained file (figures embedded as PNG data, no network
resources) that leads with the answer — a summary of what ran, the headline laws beside the
paper's, the MBD headline numbers and every warning of the run — then a table of contents, one
section per FE sweep (what was modelled, how it differs from the paper, F–δ with the paper's law,
F_ref and n against the parameter, the paper's claims beside ours, pictures of the fields), the
FE impact sweep beside the quasi-static curves (and the MBD laws where compared), the FE rolling
study (spin rates against the paper's Eqs. 7–8, energy split, strain profile, slip stages), the
multibody results (all contact models overlaid, energy, the response band split into regression
and mesh error), the presets' measured cost and error, and stage wall times. Per-run plots are
folded away under each run (<details>).

    plot.py report out/<run>/pipeline_summary.json --output out/<run>/report.html

Pictures of the FE fields are written to out/<run>/pictures/ and embedded.
"""
import argparse
import html
import os

from plotting import _paper
from plotting._report_common import Warnings, esc, get, load, load_or_none, value_of
from plotting._report_fe import (case_label, f_ref_interval, largest_own_estimate, mesh_error,
                                 own_estimate_words, start_pictures, sweep_section,
                                 trend_finding)
from plotting._report_impact import both_journals_html, impact_headline, impact_section
from plotting._report_mbd import headline_table, mbd_section
from plotting._report_rolling import rolling_headline, rolling_section


# What each preset error (presets.<p>.measured.error_F_max.<name>) is the error of: F(δ_max) for
# a quasi-static FE sweep; the impact study's peak force; the rolling study's plastic dissipation
# (pipeline.yaml, docs/pipeline.md "Presets' measured error and cost").
ERROR_OF = {"impact": "peak force", "impact_deformable": "peak force",
            "rolling": "plastic dissipation"}

# The presets' measured times [s]: key in measured, column heading, format, and the summary
# section whose presence shows the column even when no preset has measured it (None: always).
PRESET_TIMES = [("fe_case_time", "one FE curve", "{:.3g}", None),
                ("impact_time", "FE impact sweep", "{:.3g}", "impact"),
                ("impact_deformable_time", "FE impact sweep, deformable journal", "{:.3g}",
                 "impact_deformable"),
                ("rolling_time", "FE rolling study", "{:.3g}", "rolling"),
                ("pipeline_time", "whole pipeline", "{:.0f}", None)]

# A measured time is stale when this run misses it by more than this factor, either way
# (pipeline/presets.h stale_factor): too low, it makes the time-left estimate and the Slurm time
# limits too short; too high, it overstates the preset's cost — either way it no longer
# describes the code on this machine.
STALE_FACTOR = 1.5


def measured_time(measured, key):
    """measured[key] for "fe_case_time" & co., measured["case_times"][sweep] for
    "case_times.<sweep>"."""
    if key.startswith("case_times."):
        return ((measured or {}).get("case_times") or {}).get(key.split(".", 1)[1])
    return (measured or {}).get(key)


def run_times(summary):
    """This run's time per measured-time key: {key: (seconds, n tasks that ran, n reused)}.
    An FE case's key is the one run_pipeline compared it with (its task's preset_time.key);
    the whole pipeline's is the run's wall time (without the report), only when every task
    ran."""
    out = {}
    tasks = summary.get("tasks") or []
    for t in tasks:
        key = (t.get("preset_time") or {}).get("key")
        if not key:
            continue
        seconds, ran, reused = out.get(key, (0.0, 0, 0))
        if t.get("outcome") == "ran":
            out[key] = (seconds + t["wall_time"]["value"], ran + 1, reused)
        else:
            out[key] = (seconds, ran, reused + 1)
    out = {k: ((s / n if n else None), n, r) for k, (s, n, r) in out.items()}
    wall = value_of(summary.get("wall_time"))
    if wall is not None and tasks:
        reused = sum(t.get("outcome") != "ran" for t in tasks)
        out["pipeline_time"] = (wall if reused == 0 else None, len(tasks) - reused, reused)
    return out


def stale(run_seconds, figure_seconds):
    return (run_seconds > STALE_FACTOR * figure_seconds or
            figure_seconds > STALE_FACTOR * run_seconds)


def summary_sweeps(summary):
    """The FE sweeps of pipeline_summary.json: `sweeps`, or `studies` in a run folder written
    before issue 29 renamed them (the report still reads those)."""
    if "sweeps" in summary:
        return summary["sweeps"]
    return summary.get("studies") or []


def preset_section(summary):
    """Every preset's measured cost (DoFs, times of one FE curve, the impact sweep, the rolling
    study and the whole pipeline) and error per FE sweep (of F(δ_max); the impact study's of its
    peak force, the rolling study's of its plastic dissipation), each error with where it was
    measured; the chosen preset marked. A null value reads "not measured"."""
    presets = summary.get("presets") or []
    if not presets:
        return ""
    # one error column per FE sweep, then the other names measured (impact, rolling)
    columns = [s["name"] for s in summary_sweeps(summary)]
    for p in presets:
        for name in ((p.get("measured") or {}).get("error_F_max") or {}):
            if name not in columns:
                columns.append(name)
    times = [t for t in PRESET_TIMES
             if t[3] is None or summary.get(t[3])
             or any((p.get("measured") or {}).get(t[0]) for p in presets)]
    # an FE sweep's own case time (bench/measure_presets.py writes case_times.<sweep>)
    case_sweeps = []
    for p in presets:
        for name in ((p.get("measured") or {}).get("case_times") or {}):
            if name not in case_sweeps:
                case_sweeps.append(name)
    times[1:1] = [(f"case_times.{n}", f"one FE case, {n}", "{:.3g}", None) for n in case_sweeps]

    def quantity(q, fmt, unit):
        if not q:
            return "not measured"
        shown = fmt.format(q["value"])
        return shown if q.get("unit", unit) == unit else f"{shown} {html.escape(q['unit'])}"

    def error_heading(s):
        return f"error of {ERROR_OF.get(s, 'F(δ_max)')}, {html.escape(s)} [%]"

    rows = ["<h2 id='presets'>Presets: measured cost and error</h2>",
            "<p>Estimated relative error per FE sweep — of the force at δ_max (against a Richardson "
            "extrapolation over the mesh levels), of the impact study's peak force, of the rolling "
            "study's plastic dissipation (over the time steps) — and cost, as measured "
            "(docs/benchmarks.md, docs/fe.md). Point at an error to see where it was measured "
            "(also listed below the table). “not measured” and “not yet measured” mean no number "
            "exists yet.</p>",
            "<table><tr><th>preset</th><th>FE scene settings</th><th>FE DoFs [1]</th>" +
            "".join(f"<th>{label} [s]</th>" for _, label, _, _ in times) +
            "".join(f"<th>{error_heading(s)}</th>" for s in columns) +
            "<th>source</th></tr>"]
    missed = []
    chosen_name = next((p["name"] for p in presets if p.get("chosen")), "")

    def this_run_row(p, times, columns, measured_by_run):
        """The row of this run's times under the chosen preset's figures: a figure this run
        misses by more than STALE_FACTOR either way is marked; reused tasks measure nothing."""
        m = p.get("measured") or {}
        cells = []
        for key, label, fmt, _ in times:
            seconds, ran, reused = measured_by_run.get(key, (None, 0, 0))
            figure = value_of(measured_time(m, key))
            if seconds is None:
                cells.append("<td>reused</td>" if reused else "<td>—</td>")
                continue
            shown = fmt.format(seconds) + (f" (mean of {ran})" if ran > 1 else "")
            if key == "pipeline_time":
                shown += " (without the report)"
            if figure is not None and stale(seconds, figure):
                ratio = seconds / figure
                cells.append(f"<td style='background:#f8c0c0' title='this run / the figure = "
                             f"{ratio:.2g}'>⚠ {shown}: {ratio:.2g}× the figure</td>")
                missed.append(f"{html.escape(label)}: {fmt.format(seconds)} s against "
                              f"{fmt.format(figure)} s measured ({ratio:.2g}×)")
            else:
                cells.append(f"<td>{shown}</td>")
        return (f"<tr><td>this run</td><td>times of this run's tasks (those that ran) under "
                f"preset {html.escape(p['name'])}</td><td></td>" + "".join(cells) +
                "".join("<td></td>" for _ in columns) + "<td>pipeline_summary.json</td></tr>",
                missed)

    for p in presets:
        m = p.get("measured") or {}
        errors = m.get("error_F_max") or {}
        cells = []
        for s in columns:
            e = errors.get(s)
            if e is None:
                cells.append("<td>not stated</td>")
            elif e.get("percent") is None:
                cells.append(f"<td title='{html.escape(e['where'])}'><em>not yet measured</em></td>")
            else:
                cells.append(f"<td title='{html.escape(e['where'])}'>{e['percent']:.3g} %</td>")
        settings = ", ".join(f"{k} = {v}" for k, v in sorted((p.get("fe") or {}).items())) or "defaults"
        # a sweep's own settings for this preset (fe_sweeps[i].presets), after the preset's
        for sweep, own in sorted((p.get("sweeps") or {}).items()):
            if own:
                settings += f"; sweep {sweep}: " + ", ".join(f"{k} = {v}" for k, v in sorted(own.items()))
        # and the rolling study's own settings for it (rolling.presets), after rolling.overrides
        if p.get("rolling"):
            settings += "; rolling study: " + ", ".join(f"{k} = {v}" for k, v in sorted(p["rolling"].items()))
        # and the impact study's (impact.presets), after impact.overrides
        if p.get("impact"):
            settings += "; impact study: " + ", ".join(f"{k} = {v}" for k, v in sorted(p["impact"].items()))
        name = html.escape(p["name"]) + (" <strong>(this run)</strong>" if p.get("chosen") else "")
        style = " style='background:#ffe9b3'" if p.get("chosen") else ""
        rows.append(f"<tr{style}><td>{name}</td><td>{html.escape(settings)}</td>"
                    f"<td>{quantity(m.get('fe_dofs'), '{:.0f}', '1')}</td>" +
                    "".join(f"<td>{quantity(measured_time(m, key), fmt, 's')}</td>"
                            for key, _, fmt, _ in times) +
                    "".join(cells) +
                    f"<td>{html.escape(m.get('note', 'no measurements stated'))}</td></tr>")
        if p.get("chosen") and summary.get("tasks"):
            row, missed = this_run_row(p, times, columns, run_times(summary))
            rows.append(row)
    rows.append("</table>")
    if missed:
        rows.append("<p class='warning'><strong>Stale preset figures:</strong> this run missed "
                    f"{len(missed)} of the preset's measured times by more than {STALE_FACTOR}× "
                    "(marked ⚠ above): " + "; ".join(missed) + ". Refresh them on a quiet "
                    "machine with <code>bench/measure_presets.py --presets "
                    f"{html.escape(chosen_name)}</code> (docs/benchmarks.md, \"Preset figures\").</p>")
    # Where each error was measured, per column, each distinct text once with its presets.
    items = []
    for s in columns:
        wheres = {}
        for p in presets:
            e = ((p.get("measured") or {}).get("error_F_max") or {}).get(s)
            if e is not None:
                wheres.setdefault(e["where"], []).append(p["name"])
        items += [f"<li>{html.escape(s)} ({html.escape(', '.join(names))}): {html.escape(w)}</li>"
                  for w, names in wheres.items()]
    if items:
        rows.append("<p>Where each error was measured:</p><ul>" + "".join(items) + "</ul>")
    return "".join(rows)


def timing_section(summary):
    rows = ["<h2 id='timing'>Wall time of each stage</h2><table><tr><th>task</th><th>outcome</th>"
            "<th>wall time [s]</th></tr>"]
    totals = {}
    for t in summary["tasks"]:
        w = t["wall_time"]["value"]
        totals[t["stage"]] = totals.get(t["stage"], 0.0) + w
        rows.append(f"<tr><td>{html.escape(t['name'])}</td><td>{t['outcome']}</td><td>{w:.2f}</td></tr>")
    rows.append("</table><p>Totals (time of the run that produced each result): " +
                ", ".join(f"{k}: {v:.1f} s" for k, v in sorted(totals.items())) + "</p>")
    return "".join(rows)




def chosen_preset(summary):
    for p in summary.get("presets") or []:
        if p.get("chosen"):
            return p
    return None


def own_estimate_words_html(fs, preset_percent):
    """"; this run's own estimate, the largest over its cases: …" for a sweep of adaptive cases (fe_stage's estimate
    from each case's sequence), with "(the figure to use)" where the preset states none."""
    worst = largest_own_estimate(fs)
    if worst is None:
        return ""
    est, case = worst
    return (f"; this run's own estimate, the largest over its cases: "
            f"{esc(own_estimate_words(est))} at {esc(case_label(fs.sweep, case))}"
            + (", <strong>the figure to use</strong>" if preset_percent is None else ""))


def what_ran(summary, sweeps):
    preset = chosen_preset(summary)
    errors = get(preset, "measured", "error_F_max", default={}) or {}
    items = []
    for fs in sweeps:
        st = fs.sweep
        scene = fs.first_scene()
        e = get(errors, st["name"], "percent")
        loading = get(scene, "loading", "journal", default="?")
        mu = get(scene, "contact", "mu")
        values = ", ".join(f"{v:.4g}" for v in fs.values_shown())
        from plotting._report_fe import param_axis_label
        items.append(
            f"<li><a href='#{esc(fs.anchor)}'>{esc(st['name'])}</a>: {esc(param_axis_label(st))} ∈ "
            f"{{{esc(values)}}}, journal loading <code>{esc(loading)}</code>, "
            f"{'frictionless' if mu == 0 else f'μ = {mu:g}' if mu is not None else 'friction not stated'}; "
            f"measured error of F(δ_max) with this preset: "
            f"{f'{e:.3g} %' if e is not None else 'not measured'}{own_estimate_words_html(fs, e)}</li>")
    settings = ", ".join(f"{k} = {v}" for k, v in sorted((get(preset, "fe", default={}) or {}).items()))
    return (f"<p>Preset <strong>{esc(summary['preset'])}</strong> "
            f"({esc(settings or 'the scenes as they are')})."
            f" FE sweeps:</p><ul>{''.join(items)}</ul>")


def headline_laws(sweeps, has_band):
    """Our t_B = 4 mm law beside the paper's, in mm/N and SI, and F at 0.05 mm."""
    rows = ["<table><tr><th>law</th><th>δ in mm, F in N</th><th>SI: K [N/m^n]</th><th>n</th>"
            "<th>F(0.05 mm) [N]</th><th>uncertainty of F(0.05 mm)</th></tr>"]
    rows.append(f"<tr><td>paper, t_B = 4 mm (axis-line loading, μ = 0.1)</td>"
                f"<td>F = {_paper.TB4_K_MM:.6g}·δ^{_paper.TB4_N}</td><td>{_paper.tb4_K_si():.5g}</td>"
                f"<td>{_paper.TB4_N}</td><td>{_paper.tb4_force(_paper.DELTA_MAX):.0f}</td>"
                f"<td>its mesh study: 3.12 %</td></tr>")
    verdict = ""
    for fs in sweeps:
        if fs.sweep["parameter"] != "t_B":
            continue
        for case, law, _ in fs.cases:
            if abs(case["value"] - _paper.TB4_T_B) > 1e-9:
                continue
            K, n = law["law"]["K"], law["law"]["n"]
            f, hw = f_ref_interval(law, _paper.DELTA_MAX)
            e = mesh_error(law)
            pf = _paper.tb4_force(_paper.DELTA_MAX)
            unc = f"fit 95 %: ±{100 * (hw or 0) / f:.2g} %; mesh: " + \
                (f"±{100 * e:.3g} %" if e else "not measured")
            rows.append(f"<tr><td>this run, t_B = 4 mm</td><td>F = {law['mm_N']['K']:.6g}·δ^{n:.4f}</td>"
                        f"<td>{K:.5g}</td><td>{n:.4f}</td><td>{f:.0f} ({round(100 * (f - pf) / pf, 1) + 0.0:+.1f} % "
                        f"against the paper)</td><td>{unc}</td></tr>")
            # hw is 0 when the data follow one power law exactly: the mesh error still dominates
            if e and hw is not None:
                dom = "the mesh (discretisation) error" if e > hw / f else "the regression interval"
                verdict = (f"<p>Uncertainty of our t_B = 4 mm law at 0.05 mm: the fit's 95 % "
                           f"interval is ±{100 * hw / f:.2g} %, the preset's measured mesh error "
                           f"±{100 * e:.3g} %: <strong>{dom} dominates</strong>." +
                           (" The MBD band moves the law by both (<a href='#band'>response "
                            "band</a>)." if has_band else "") + "</p>")
            elif hw and not e:
                verdict = ("<p>The preset's mesh error is not measured: the law's uncertainty "
                           "shown is the regression's only and narrower than the truth.</p>")
    rows.append("</table>")
    return "".join(rows) + verdict


def summary_section(summary, sweeps, runs, warnings, has_band):
    parts = ["<section class='summary'><h2 id='summary'>Summary</h2>",
             "<h3>What ran</h3>", what_ran(summary, sweeps)]
    mus = sorted({get(r.joint, "friction", "mu") for r in runs if r.joint} - {None})
    if runs:
        parts.append(f"<p>Multibody: the paper's slider–crank over "
                     f"{value_of(get(runs[0].summary, 'duration'), 0):.3g} s, {len(runs)} runs "
                     f"(contact models, the ideal joint, the tilted crank); joint friction μ ∈ "
                     f"{{{', '.join(f'{m:g}' for m in mus)}}}.</p>")
    parts.append(impact_headline(summary.get("impact")))
    parts.append(impact_headline(summary.get("impact_deformable"), "impact_deformable"))
    parts.append(rolling_headline(summary.get("rolling")))
    parts.append("<h3>Headline law beside the paper's</h3>")
    parts.append(headline_laws(sweeps, has_band))
    findings = [t for t in (trend_finding(fs) for fs in sweeps if fs.cases) if t]
    if findings:
        parts.append("<h3>Trends beside the paper's claims</h3><ul>" +
                     "".join(f"<li>{t}</li>" for t in findings) + "</ul>")
    if runs:
        parts.append("<h3>Multibody headline numbers</h3>")
        parts.append(headline_table(runs))
    parts.append(f"<h3 id='warnings'>Warnings ({len(warnings.items)})</h3>")
    parts.append(warnings.html())
    parts.append("</section>")
    return "".join(parts)


def toc(sweeps, has_mbd, has_band, has_impact=False, has_rolling=False,
        has_impact_deformable=False):
    items = ["<li><a href='#summary'>Summary</a> (<a href='#warnings'>warnings</a>)</li>"]
    for fs in sweeps:
        items.append(f"<li><a href='#{esc(fs.anchor)}'>FE sweep “{esc(fs.sweep['name'])}”</a></li>")
    if has_impact:
        items.append("<li><a href='#impact'>FE impact study</a></li>")
    if has_impact_deformable:
        items.append("<li><a href='#impact_deformable'>FE impact study, deformable "
                     "journal</a></li>")
    if has_rolling:
        items.append("<li><a href='#rolling'>FE rolling study</a></li>")
    if has_mbd:
        items.append("<li><a href='#mbd'>Multibody simulations</a>" +
                     (" (<a href='#band'>uncertainty of the response</a>)" if has_band else "") +
                     "</li>")
    items.append("<li><a href='#presets'>Presets: measured cost and error</a></li>")
    items.append("<li><a href='#timing'>Wall time of each stage</a></li>")
    return f"<nav><h2>Contents</h2><ol>{''.join(items)}</ol></nav>"


CSS = """body{font-family:sans-serif;max-width:1150px;margin:2em auto;color:#222;line-height:1.4}
table{border-collapse:collapse;margin:1em 0;font-size:88%}td,th{border:1px solid #bbb;padding:3px 7px;vertical-align:top}
th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:90%;color:#555}
.summary{background:#f6f8fb;border:1px solid #d5dbe5;padding:0.2em 1.2em 1em}
.warn{background:#fff3e0;border-left:4px solid #e69500;padding:0.4em 0.8em}
.warnings li{margin:0.3em 0}.ok{color:#2a6a2a}
.flag{background:#fff3e0;border-left:3px solid #e69500;padding:0 0.3em;font-size:92%}
details{margin:0.4em 0;border:1px solid #ddd;padding:0.3em 0.7em}summary{cursor:pointer;color:#124}
nav ol{columns:2}"""


def main(argv):
    p = argparse.ArgumentParser(prog="plot.py report")
    p.add_argument("summary")
    p.add_argument("--output", required=True)
    a = p.parse_args(argv)
    summary = load(a.summary)
    base = os.path.dirname(os.path.abspath(a.output))
    os.makedirs(base, exist_ok=True)
    warnings = Warnings()
    start_pictures(summary_sweeps(summary), base)
    sweep_html, sweeps = [], []
    for st in summary_sweeps(summary):
        html_, fs = sweep_section(st, base, warnings,
                                  get(chosen_preset(summary), "measured", "error_F_max", st["name"]))
        sweep_html.append(html_)
        sweeps.append(fs)
    impact_html = impact_section(summary.get("impact"), base, warnings)
    deformable_html = impact_section(summary.get("impact_deformable"), base, warnings,
                                     "impact_deformable")
    if impact_html and deformable_html:
        deformable_html += both_journals_html(summary["impact"], summary["impact_deformable"])
    rolling_html = rolling_section(summary.get("rolling"), base, warnings)
    mbd_html, runs = ("", [])
    if summary.get("mbd_runs"):
        mbd_html, runs = mbd_section(summary["mbd_runs"], base, warnings)
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>clearjoint report — "
             f"{esc(summary['run'])}</title><style>{CSS}</style></head><body>",
             f"<h1>clearjoint report: run “{esc(summary['run'])}”, preset "
             f"{esc(summary['preset'])}</h1>",
             f"<p>Pipeline file: {esc(summary['pipeline_file'])}. Laws are shown in SI "
             f"(δ in m, F in N) and in the paper's units (δ in mm, F in N).</p>",
             summary_section(summary, sweeps, runs, warnings, "id='band'" in mbd_html),
             toc(sweeps, bool(runs), "id='band'" in mbd_html, bool(impact_html),
                 bool(rolling_html), bool(deformable_html))]
    parts += sweep_html
    parts.append(impact_html)
    parts.append(deformable_html)
    parts.append(rolling_html)
    parts.append(mbd_html)
    parts.append(preset_section(summary))
    parts.append(timing_section(summary))
    parts.append("</body></html>")
    tmp = a.output + ".tmp"
    try:
        with open(tmp, "w") as f:
            f.write("\n".join(parts))
        os.replace(tmp, a.output)
    except OSError:  # a full disk: no half-written report left (plot.py reports the error)
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    return 0
