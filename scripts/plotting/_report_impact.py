"""The report's impact section (issue 12): the FE impact sweep — peak force, δ_max, contact
duration, restitution, energy left in the bearing and the dynamic peak's excess over the
quasi-static force at the same δ — its sweep plot, each velocity's F(t), δ(t), F(δ) and energy
plot folded away, and, where impact_compare ran, the MBD laws' comparison."""
import os

from plotting._common import read_table
from plotting._report_common import details, esc, image_file_html, load_or_none, rel_link


def impact_section(impact, base, warnings):
    """HTML of the impact section, or "" if the run has no impact study."""
    if not impact:
        return ""
    fe_dir = impact["fe_dir"]
    parts = ["<h2 id='impact'>FE impact study (paper §3.2)</h2>",
             "<p>The journal is launched at first touch toward the bearing (t_B as in the "
             "impact scene) and followed through the impact by Hilber–Hughes–Taylor α implicit "
             "dynamics, with the exact active-set contact at every step and the contact nodes "
             "massless (docs/fe.md). Beside each impact, the quasi-static curve of the same mesh: "
             "the dynamic peak is compared with the quasi-static force at the same δ. The paper "
             "reports that this gap vanishes as v → 0; in this linear-elastic model the whole "
             "response scales with v, so the gap is the same at every velocity — it is the "
             "bearing ring's inertia, which a quasi-static law cannot hold.</p>"]
    sweep = impact.get("sweep")
    if not sweep or not os.path.exists(sweep):
        warnings.add("impact study", f"no sweep table in {esc(fe_dir)} (did the FE task fail?)",
                     "impact")
        return "\n".join(parts)
    _, _, s = read_table(sweep)
    rows = ["<table><tr><th>v [m/s]</th><th>peak force [N]</th><th>δ_max [µm]</th>"
            "<th>contact duration [µs]</th><th>restitution [1]</th>"
            "<th>quasi-static F at the peak's δ [N]</th><th>dynamic gap</th>"
            "<th>energy left in the bearing [% of ½mv²]</th></tr>"]
    for i, v in enumerate(s["v_in_m_per_s"]):
        separated = s["separated"][i] > 0.5
        rows.append(
            f"<tr><td>{v:.3g}</td><td>{s['peak_force_N'][i]:.4g}</td>"
            f"<td>{s['delta_max_m'][i] * 1e6:.4g}</td>"
            f"<td>{s['contact_duration_s'][i] * 1e6:.4g}</td>"
            f"<td>{s['restitution'][i]:.4f}" + ("" if separated else " (still in contact)") +
            f"</td><td>{s['quasi_static_force_at_peak_delta_N'][i]:.4g}</td>"
            f"<td>{100 * s['dynamic_gap'][i]:+.2f} %</td>"
            f"<td>{100 * s['bearing_energy_left_J'][i] / s['kinetic_initial_J'][i]:.2f}</td></tr>")
        if not separated:
            warnings.add(f"impact at v = {v:.3g} m/s",
                         "the journal had not left the bearing at the end time", "impact")
    rows.append("</table>")
    parts.append("".join(rows))
    png = os.path.join(fe_dir, "impact_sweep.png")
    if os.path.exists(png):
        parts.append(image_file_html(png, "Impact sweep: peak force (with the quasi-static force "
                                          "at the same δ), δ_max, contact duration and "
                                          "restitution against the impact velocity"))
    cases = sorted(d for d in os.listdir(fe_dir) if d.startswith("v_"))
    for c in cases:
        # the linear-elastic model's validity at the peak force (its yield check)
        man = load_or_none(os.path.join(fe_dir, c, "manifest.json")) or {}
        yc = man.get("extra", {}).get("yield_check", {})
        if yc.get("exceeded"):
            worst = max(yc.get("bodies", []), key=lambda b: b["max_von_mises"]["value"],
                        default=None)
            if worst:
                warnings.add(f"impact at v = {esc(c[2:].replace('mps', ''))} m/s",
                             f"von Mises reaches {worst['max_von_mises']['value'] / 1e6:.4g} MPa "
                             f"in the {esc(worst['body'])} at the peak force, above the yield "
                             f"stress {yc['yield_stress']['value'] / 1e6:.4g} MPa: the linear-"
                             "elastic result is not valid there", "impact")
    for c in cases:
        img = os.path.join(fe_dir, c, "impact.png")
        if os.path.exists(img):
            parts.append(details(f"v = {esc(c[2:].replace('mps', ''))} m/s: F(t), δ(t), F(δ), "
                                 "energy balance",
                                 image_file_html(img, f"{esc(c)}: impact history "
                                                      f"({rel_link(os.path.join(fe_dir, c), base)})")))
    compare = impact.get("compare_dir")
    if compare and os.path.isdir(compare):
        parts.append("<h3>Against the MBD contact laws</h3>")
        for name in sorted(os.listdir(compare)):
            if name.endswith(".png"):
                parts.append(image_file_html(os.path.join(compare, name),
                                             f"FE impact against the MBD law ({esc(name)})"))
        man = load_or_none(os.path.join(compare, "manifest.json"))
        if man is None:
            warnings.add("impact comparison", "no manifest in " + esc(compare), "impact")
            return "\n".join(parts)
        fits = man.get("extra", {}).get("fitted_restitution_coefficient", {})
        if fits:
            rows = ["<p>The c_e with which each damping model's single impact (the journal's "
                    "mass on the MBD law, bearing rigid) returns the FE restitution:</p><table>"
                    "<tr><th>damping model</th><th>c_e (mean over v)</th><th>spread over v</th>"
                    "<th>depends on v?</th></tr>"]
            for name, f in sorted(fits.items()):
                rows.append(f"<tr><td>{esc(name)}</td><td>{f['c_e_mean']:.5f}</td>"
                            f"<td>{f['spread_over_v']:.2g}</td>"
                            f"<td>{'yes' if f['depends_on_v'] else 'no'}</td></tr>")
            rows.append("</table>")
            parts.append("".join(rows))
    return "\n".join(parts)


def impact_headline(impact):
    """One sentence for the report's summary: the dynamic peak against the quasi-static force,
    the restitution, and the c_e that reproduces it; "" without an impact study."""
    if not impact or not impact.get("sweep") or not os.path.exists(impact["sweep"]):
        return ""
    _, _, s = read_table(impact["sweep"])
    v = s["v_in_m_per_s"]
    gaps = [100 * g for g in s["dynamic_gap"]]
    e = s["restitution"]
    def span(values, fmt):
        """'a–b', or 'a' at every v when they agree to the digits shown."""
        lo, hi = fmt.format(min(values)), fmt.format(max(values))
        return lo if lo == hi else f"{lo} to {hi}"

    slow, fast = gaps[v.index(min(v))], gaps[v.index(max(v))]
    if abs(slow) < 0.5 * abs(fast):
        trend = "it shrinks as v falls, as the paper reports"
    else:
        trend = ("the bearing's inertia: it does not shrink as v falls, unlike the paper's "
                 "claim (docs/fe.md)")
    text = (f"<p>Impact (<a href='#impact'>FE impact study</a>), v = {min(v):.3g}–{max(v):.3g} m/s: "
            f"peak force {min(s['peak_force_N']):.4g}–{max(s['peak_force_N']):.4g} N, "
            f"<strong>{span(gaps, '{:+.1f}')} % above the quasi-static force at the same δ"
            f"</strong> ({trend}), restitution {span(e, '{:.4f}')}")
    man = load_or_none(os.path.join(impact.get("compare_dir", ""), "manifest.json")) or {}
    fits = man.get("extra", {}).get("fitted_restitution_coefficient", {})
    if fits:
        text += ("; the damping models return it with c_e = " +
                 ", ".join(f"{f['c_e_mean']:.4f} ({esc(n.replace('_', ' '))})"
                           for n, f in sorted(fits.items())))
    return text + ".</p>"
