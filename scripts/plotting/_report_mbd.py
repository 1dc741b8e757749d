"""The report's MBD part: headline numbers per contact model, all models overlaid (the paper's
Figs. 14–17, energy on a scale where the losses show and a zoom on the first 10 ms as Fig. 17b),
the response band from the law's uncertainty split into regression and mesh, warnings from the
stages' counters, and every run's own plots folded away.

mbd_stage's summary.json is read tolerantly: keys may be added (counters) by newer stages."""
import glob
import os

import matplotlib.pyplot as plt

from plotting._common import read_table
from plotting._report_common import (details, esc, figure_html, get, image_file_html,
                                     load_or_none, rel_link, value_of)

ANCHOR = "mbd"


class Run:
    def __init__(self, entry):
        self.entry = entry
        self.name = entry["name"]
        self.dir = entry["dir"]
        self.summary = load_or_none(os.path.join(self.dir, "summary.json")) or {}
        self.data = None
        csv = os.path.join(self.dir, "timeseries.csv")
        if os.path.exists(csv):
            try:
                _, _, self.data = read_table(csv)
            except (OSError, ValueError):
                self.data = None
        cj = get(self.summary, "clearance_joints", default=[])
        self.joint = cj[0] if cj else None

    def col(self, name):
        return self.data.get(name) if self.data else None

    def joint_col(self, suffix):
        if not self.joint or not self.data:
            return None
        return self.data.get(self.joint["name"] + "_" + suffix)

    def model_words(self):
        if not self.joint:
            return "ideal joint"
        nm = self.joint.get("normal_model") or {}
        law = get(nm, "law", "form", default="")
        damping = nm.get("damping")
        name = nm.get("name", "")
        words = name or law
        if damping and damping != "none":
            words += f", damping {damping}"
        mu = get(self.joint, "friction", "mu")
        if mu is not None:
            words += f", μ = {mu:g}"
        return words

    def n_impacts(self):
        n = get(self.joint, "n_impacts", default={})
        return sum(v for v in n.values() if isinstance(v, (int, float))) if isinstance(n, dict) else None


def _counters(obj, path=""):
    """Every counter in the summary that counts something out of range: keys naming
    out_of_range, n_evaluations_*, beyond or clamped, and the n_* counts inside an out_of_range
    block (mbd_stage: normal_model.out_of_range.n_accepted_steps_above / _below)."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            p = f"{path}.{k}" if path else k
            if isinstance(v, (dict, list)):
                yield from _counters(v, p)
            elif isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0 and \
                    ("out_of_range" in k or k.startswith("n_evaluations_") or "beyond" in k
                     or "clamped" in k or ("out_of_range" in path and k.startswith("n_"))):
                yield p, v
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _counters(v, f"{path}[{i}]")


def run_problems(run):
    """The run's problems as short texts: status, counters, law outside its fitted range."""
    out = []
    status = get(run.summary, "status")
    if status != "complete":
        out.append(f"status {esc(str(status))}: "
                   f"{esc(str(get(run.summary, 'failure', default='no summary.json')))}")
    counters = list(_counters(run.summary))
    nm = get(run.joint, "normal_model", default={}) or {}
    top = value_of(get(nm, "valid_range", "delta_max"))
    pen = value_of(get(run.summary, "peaks", "penetration_max"))
    if pen is not None and top and pen > top:
        out.append(f"the contact law was used beyond its fitted range: the penetration reached "
                   f"{pen * 1e6:.3g} µm, the law was fitted up to {top * 1e6:.3g} µm "
                   f"(policy {esc(str(get(nm, 'out_of_range', 'policy', default='?')))})")
    if counters:
        # mbd_stage counts accepted steps only (trial stages never count, docs/mbd.md)
        out.append("range counters " + ", ".join(f"{esc(p)} = {v:g}" for p, v in counters))
    return out


def run_warnings(run, warnings, label=None):
    for text in run_problems(run):
        warnings.add(label or f"MBD {run.name}", text, ANCHOR)


def band_warnings(run, warnings):
    """One line for all the band variants of a run (they are the same scene with moved laws)."""
    band = run.entry.get("band") or []
    texts = {}
    for b in band:
        br = Run({"name": b["variant"], "dir": b["dir"]})
        for t in run_problems(br):
            key = t.split(" = ")[0] if t.startswith("range counters") else t
            texts.setdefault(key, []).append(b["variant"])
    if texts:
        variants = sorted({v for vs in texts.values() for v in vs})
        warnings.add(f"MBD {run.name}, band runs ({', '.join(variants)})",
                     "the same kinds of warnings as the nominal run (range counters, see each run's "
                     "summary.json)", ANCHOR)


def headline_table(runs):
    rows = ["<table><tr><th>run</th><th>contact model</th><th>peak contact force [N]</th>"
            "<th>first-impact peak [N]</th><th>impacts (radial + axial)</th>"
            "<th>energy lost by t_end [mJ] (% of E(0))</th><th>friction / damping work [mJ]</th>"
            "<th>max δ [µm]</th><th>wall [s]</th></tr>"]
    for r in runs:
        s = r.summary
        E0 = value_of(get(s, "energy", "E0"))
        Ee = value_of(get(s, "energy", "E_total_final"))
        loss = (E0 - Ee) if E0 is not None and Ee is not None else None
        Wf = value_of(get(s, "energy", "W_friction"))
        Wd = value_of(get(s, "energy", "W_damping"))
        pk = value_of(get(s, "peaks", "contact_force_max"))
        fi = value_of(get(s, "peaks", "first_impact_peak_force"))
        dm = value_of(get(s, "peaks", "penetration_max"))
        wall = value_of(get(s, "wall_time"))

        def f(v, fmt):
            return fmt.format(v) if v is not None else "–"
        rows.append(
            f"<tr><td><a href='#mbd-run-{esc(r.name)}'>{esc(r.name)}</a></td><td>{esc(r.model_words())}</td>"
            f"<td>{f(pk, '{:.0f}')}</td><td>{f(fi, '{:.0f}')}</td><td>{f(r.n_impacts(), '{:.0f}')}</td>"
            f"<td>{f(loss * 1e3 if loss is not None else None, '{:.2f}')}"
            f"{f' ({100 * loss / E0:.2f} %)' if loss is not None and E0 else ''}</td>"
            f"<td>{f(abs(Wf) * 1e3 if Wf is not None else None, '{:.2f}')} / "
            f"{f(abs(Wd) * 1e3 if Wd is not None else None, '{:.2f}')}</td>"
            f"<td>{f(dm * 1e6 if dm is not None else None, '{:.2f}')}</td><td>{f(wall, '{:.2f}')}</td></tr>")
    rows.append("</table><p>Energy lost = E(0) − E_total(t_end) with E_total = kinetic + potential "
                "+ contact-elastic energy; friction and damping work as written by mbd_stage "
                "(shown as positive losses).</p>")
    return "".join(rows)


def overlay_figures(runs):
    have = [r for r in runs if r.data and "t" in r.data]
    if not have:
        return ""
    out = []
    # one colour per run in every panel and figure (each axes' own colour cycle would give the
    # journal orbit, which the ideal joint lacks, other colours than the legend's)
    colour = {r.name: f"C{i % 10}" for i, r in enumerate(have)}
    fig, ax = plt.subplots(2, 2, figsize=(13, 8.5))
    for r in have:
        d, c = r.data, colour[r.name]
        if "slider_velocity" in d:
            ax[0][0].plot(d["t"], d["slider_velocity"], lw=0.8, color=c, label=r.name)
            ax[1][0].plot(d["slider_position"], d["slider_velocity"], lw=0.6, color=c, label=r.name)
        if "slider_acceleration" in d:
            ax[0][1].plot(d["t"], d["slider_acceleration"], lw=0.5, color=c, label=r.name)
        e1, e2 = r.joint_col("ecc_1"), r.joint_col("ecc_2")
        if e1 and e2:
            ax[1][1].plot([1e3 * x for x in e1], [1e3 * y for y in e2], lw=0.5, color=c, label=r.name)
    ax[0][0].set(xlabel="time t [s]", ylabel="slider velocity [m/s]", title="Fig. 14: slider velocity")
    ax[0][1].set(xlabel="time t [s]", ylabel="slider acceleration [m/s²]",
                 title="Fig. 15: slider acceleration")
    ax[1][0].set(xlabel="slider position [m]", ylabel="slider velocity [m/s]",
                 title="Fig. 16: phase portrait")
    ax[1][1].set(xlabel="eccentricity h1 [mm]", ylabel="eccentricity h2 [mm]",
                 title="journal centre in the bearing")
    ax[1][1].set_aspect("equal", adjustable="datalim")
    for a in ax.flat:
        a.grid(True, alpha=0.3)
    ax[0][0].legend(fontsize=7, ncol=2)
    if ax[1][1].lines:
        ax[1][1].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out.append(figure_html(fig, "Every contact model overlaid: slider velocity, acceleration, "
                                "phase portrait and journal orbit (the paper's Figs. 14–16)."))

    # Fig. 17: the total energy is ~2.5 J and the losses are mJ: plot E_total − E(0)
    fig, ax = plt.subplots(1, 2, figsize=(13, 4.6))
    for r in have:
        d = r.data
        if "E_total" not in d:
            continue
        E0 = d["E_total"][0]
        dE = [1e3 * (e - E0) for e in d["E_total"]]
        ax[0].plot(d["t"], dE, lw=0.9, color=colour[r.name], label=r.name)
        idx = [i for i, t in enumerate(d["t"]) if t <= 0.010]
        ax[1].plot([d["t"][i] * 1e3 for i in idx], [dE[i] for i in idx], lw=1.0,
                   color=colour[r.name], label=r.name)
    ax[0].set(xlabel="time t [s]", ylabel="E_total(t) − E(0) [mJ]",
              title="Fig. 17a: mechanical energy change")
    ax[1].set(xlabel="time t [ms]", ylabel="E_total(t) − E(0) [mJ]",
              title="Fig. 17b: the first 10 ms")
    for a in ax:
        a.grid(True, alpha=0.3)
    ax[0].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    out.append(figure_html(fig, "Change of the total mechanical energy (kinetic + potential + "
                                "contact-elastic) from its start value, every model, and a zoom on "
                                "the first 10 ms (the paper's Fig. 17b). Losses are friction and "
                                "contact damping; a model without either stays at zero."))
    return "".join(out)


def band_section(runs):
    """The band of the slider velocity and of the contact force when the law moves across the
    fit's 95 % region (regression) and by the preset's measured mesh error (discretisation)."""
    import numpy as np
    out = []
    for r in runs:
        band = r.entry.get("band")
        if not band or not r.data or "slider_velocity" not in r.data:
            continue
        t = np.array(r.data["t"])
        v0 = np.array(r.data["slider_velocity"])
        groups = {}
        peaks = {}
        for b in band:
            br = Run({"name": b["variant"], "dir": b["dir"]})
            if not br.data or "slider_velocity" not in br.data:
                continue
            # older pipeline summaries have no "source": the mesh variants are named mesh_*
            src = b.get("source") or ("discretisation" if b["variant"].startswith("mesh") else "regression")
            groups.setdefault(src, []).append(np.interp(t, br.data["t"], br.data["slider_velocity"]))
            pk = value_of(get(br.summary, "peaks", "first_impact_peak_force"))
            if pk is not None:
                peaks.setdefault(src, []).append(pk)
        if not groups:
            continue
        fig, ax = plt.subplots(figsize=(11, 4.3))
        colours = {"regression": "C0", "discretisation": "C1"}
        widths = {}
        for src, curves in sorted(groups.items()):
            lo, hi = np.min(curves, axis=0), np.max(curves, axis=0)
            widths[src] = float(np.max(hi - lo))
            ax.fill_between(t, lo, hi, color=colours.get(src, "C2"), alpha=0.35,
                            label=f"{src}: {len(curves)} variants (max width {widths[src]:.3g} m/s)")
        ax.plot(t, v0, "k-", lw=0.8, label="fitted law")
        ax.set(xlabel="time t [s]", ylabel="slider velocity [m/s]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        nominal_peak = value_of(get(r.summary, "peaks", "first_impact_peak_force"))
        spreads = {}
        for src, ps in peaks.items():
            if nominal_peak:
                spreads[src] = max(abs(p - nominal_peak) for p in ps) / nominal_peak
        # Two measures: the first-impact peak force (what the law change does directly) and the
        # velocity band over the whole run (after a few impacts the response is sensitive to any
        # change of the law — the paper's "nonlinear, eventually chaotic" — so late widths say
        # more about that sensitivity than about the size of the law's uncertainty).
        early = t <= 0.02
        early_w = {}
        for src, curves in groups.items():
            lo, hi = np.min(curves, axis=0), np.max(curves, axis=0)
            early_w[src] = float(np.max((hi - lo)[early])) if np.any(early) else 0.0
        if len(groups) > 1:
            by = spreads if len(spreads) == len(groups) else early_w
            dominant = max(by, key=by.get)
            other = min(by, key=by.get)
            measure = ("first-impact peak force" if by is spreads else
                       "slider velocity over the first 20 ms")
            verdict = (f"<strong>The {dominant} part dominates</strong> by the {measure} "
                       f"({', '.join(f'{k}: ±{100 * v:.3g} %' if by is spreads else f'{k}: {v:.3g} m/s' for k, v in sorted(by.items()))})")
            wide = max(widths, key=widths.get)
            if wide != dominant:
                verdict += (f"; over the whole 0.1 s the {wide} band is the wider one "
                            f"({widths[wide]:.3g} against {widths[dominant]:.3g} m/s): late in the "
                            f"run any change of the law shifts the impacts, whatever its size")
            verdict += "."
        else:
            only = next(iter(groups))
            verdict = (f"Only the {only} part is in this band" +
                       ("; the preset's mesh error was not measured, so the band is narrower than "
                        "the truth." if only == "regression" else "."))
            if only in spreads:
                verdict += f" It moves the first-impact peak force by up to {100 * spreads[only]:.3g} %."
        peak_txt = []
        out.append(figure_html(fig, f"{esc(r.name)}: slider velocity when the law moves across the "
                                    f"fit's 95 % region (regression) and by ± the preset's measured "
                                    f"error of F (discretisation)."))
        out.append(f"<p>{verdict} {esc('; '.join(peak_txt))}{'.' if peak_txt else ''} The envelope "
                   f"of each part is drawn; they are independent and add. The mesh variants "
                   f"scale F by 1 ∓ e at every δ (n kept): the presets measure the error of "
                   f"F(δ_max) only, and the mesh also moves n (docs/fe.md), which is not yet "
                   f"measured per preset.</p>")
    if not out:
        return ""
    return "<h3 id='band'>Uncertainty of the response</h3>" + "".join(out)


# What each of mbd_stage's per-run plots (scripts/plotting/mbd.py) shows: the caption, never the
# file name alone.
RUN_PLOT_CAPTIONS = {
    "slider_motion": "slider velocity and acceleration over time (the paper's Figs. 14–15)",
    "phase_portrait": "phase portrait: slider velocity over slider position (the paper's Fig. 16)",
    "energy": "kinetic, potential and contact-elastic energy, friction and damping work, and the "
              "energy balance error E − W − E(0) (the paper's Fig. 17)",
    "ground_reactions": "reaction forces of the ground joints on the moving bodies",
    "constraint_drift": "constraint drift: largest |Φ| and Euler-parameter norm error (accuracy "
                        "of the integration)",
}
RUN_PLOT_SUFFIX_CAPTIONS = {
    "_orbit": "journal centre's orbit in the clearance circle of joint {}",
    "_contact": "penetration, normal and friction force, and axial (end-face) forces of joint {}",
}


def run_plot_caption(png):
    stem = os.path.splitext(os.path.basename(png))[0]
    if stem in RUN_PLOT_CAPTIONS:
        return RUN_PLOT_CAPTIONS[stem]
    for suffix, text in RUN_PLOT_SUFFIX_CAPTIONS.items():
        if stem.endswith(suffix):
            return text.format(stem[:-len(suffix)])
    return stem.replace("_", " ")


def per_run_details(runs, base):
    out = []
    for r in runs:
        body = [f"<p>{esc(str(get(r.summary, 'description', default='')))}</p><p>"]
        links = [rel_link(p, base) for p in (os.path.join(r.dir, f) for f in
                 ("timeseries.csv", "summary.json", "stage.log", "scene_used.json"))
                 if os.path.exists(p)]
        body.append(" · ".join(links) + "</p>")
        for png in sorted(glob.glob(os.path.join(r.dir, "plots", "*.png"))):
            body.append(image_file_html(png, f"{esc(r.name)}: {esc(run_plot_caption(png))} "
                                             f"({rel_link(png, base, os.path.basename(png))})"))
        out.append(f"<div id='mbd-run-{esc(r.name)}'>" +
                   details(f"{esc(r.name)} ({esc(r.model_words())}): plots and files",
                           "".join(body)) + "</div>")
    return "".join(out)


def mbd_section(entries, base, warnings):
    runs = [Run(e) for e in entries]
    for r in runs:
        run_warnings(r, warnings)
        band_warnings(r, warnings)
    parts = [f"<h2 id='{ANCHOR}'>Multibody simulations: the paper's slider–crank</h2>",
             "<p>The paper's slider–crank (§4, SPEC §4) with the clearance joint in the rod–slider "
             "pin, run with every contact model: the law fitted here for t_B = 4 mm (without and "
             "with Lankarani–Nikravesh damping, and without friction), the paper's own t_B = 4 mm "
             "law, the textbook models, the ideal joint and, beyond the paper, a crank tilted by "
             "1° with the misalignment law family.</p>",
             "<p>Peak forces, impacts and energy losses per model: the table in the "
             "<a href='#summary'>summary</a>.</p>",
             overlay_figures(runs), band_section(runs),
             "<h3>Every run</h3>", per_run_details(runs, base)]
    return "".join(parts), runs
