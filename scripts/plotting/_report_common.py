"""Helpers shared by the report's sections: embedding figures, folding, tolerant JSON reading,
units for display, and the list of warnings every section adds to (shown in the summary)."""
import base64
import html
import io
import json
import math
import os
import re

import matplotlib.pyplot as plt
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

esc = html.escape


def load(path):
    with open(path) as f:
        return json.load(f)


def load_or_none(path):
    """The JSON at `path`, or None if it is missing or unreadable (the report still renders)."""
    try:
        return load(path)
    except (OSError, ValueError):
        return None


def get(obj, *keys, default=None):
    """obj[k1][k2]... or `default` where a key is missing or a level is not a mapping/list.
    The stages add keys over time (issue 15: counters, yield checks); the report reads what is
    there and says "not reported" for the rest."""
    for k in keys:
        if isinstance(obj, dict) and k in obj:
            obj = obj[k]
        elif isinstance(obj, list) and isinstance(k, int) and -len(obj) <= k < len(obj):
            obj = obj[k]
        else:
            return default
    return obj


def value_of(q, default=None):
    """A quantity written as {"value": v, "unit": u} or as a bare number."""
    if isinstance(q, dict):
        q = q.get("value")
    return q if isinstance(q, (int, float)) and not isinstance(q, bool) else default


def png_html(data, caption, alt=None):
    b64 = base64.b64encode(data).decode()
    return (f'<figure><img src="data:image/png;base64,{b64}" alt="{esc(alt or caption)}">'
            f"<figcaption>{caption}</figcaption></figure>")


def figure_html(fig, caption, dpi=100):
    """`caption` is HTML (escape what comes from files before passing it)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return png_html(buf.getvalue(), caption, alt=re.sub("<[^>]+>", "", caption))


def image_file_html(path, caption):
    with open(path, "rb") as f:
        return png_html(f.read(), caption, alt=re.sub("<[^>]+>", "", caption))


def details(summary_html, body_html, open_=False):
    return (f"<details{' open' if open_ else ''}><summary>{summary_html}</summary>"
            f"{body_html}</details>")


def rel_link(path, base, text=None):
    return f'<a href="{esc(os.path.relpath(path, base))}">{esc(text or os.path.basename(path))}</a>'


def shown(value, unit):
    """SI value → the unit a reader of the paper expects (mm for lengths, ° for angles)."""
    if unit == "rad":
        return value * 180 / math.pi, "°"
    if unit == "deg":
        return value, "°"
    if unit == "m":
        return value * 1e3, "mm"
    return value, unit


def thousands(x):
    """A whole number with its thousands apart as the SI brochure writes them: 16 344. Only the
    number: replacing commas in a whole sentence would take its commas out too."""
    return f"{x:,.0f}".replace(",", " ")


def readable_log_axis(axis):
    """Log axis ticks at 1, 2, 5 × 10^k, labelled in plain numbers: a decade of data (δ from
    0.005 to 0.05 mm) would otherwise carry one labelled tick."""
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


class Warnings:
    """Every warning of the run, collected by the sections and listed in the summary."""

    def __init__(self):
        self.items = []  # (where, text, anchor)

    def add(self, where, text, anchor=None):
        self.items.append((where, text, anchor))

    def html(self):
        if not self.items:
            return "<p class='ok'>No warnings: every stage complete, no law used outside its " \
                   "fitted range, no range counter above zero.</p>"
        rows = []
        for where, text, anchor in self.items:
            link = f' (<a href="#{esc(anchor)}">details</a>)' if anchor else ""
            rows.append(f"<li><strong>{esc(where)}</strong>: {text}{link}</li>")
        return f"<ul class='warnings'>{''.join(rows)}</ul>"
