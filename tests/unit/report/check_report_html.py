#!/usr/bin/python3
"""Checks a clearjoint report.html the way a reader's browser sees it (issue 15 item 9):

    tests/report/check_report_html.py REPORT.html [--chromium PATH]

1. Static: no attribute or CSS refers to the network (http:, https:, ftp:, protocol-relative
   //host), every relative link names an existing file, every #anchor exists.
2. Headless Chromium (Debian package chromium) with the network made unreachable: a copy of the
   page with one added script reports, after the load event, every <img> that did not decode
   (complete and naturalWidth > 0) and every resource the browser fetched that is not data: or
   file: — the page itself is not changed.
Prints what failed and exits 1; exits 0 when all holds. Exit 2 if Chromium cannot run.
"""
import argparse
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

NETWORK = re.compile(r"^\s*(https?:|ftp:|//)", re.I)
CSS_URL = re.compile(r"url\(\s*['\"]?\s*(https?:|ftp:|//)|@import", re.I)

PROBE = """<script>
window.addEventListener('load', function () {
  setTimeout(function () {
    var imgs = Array.prototype.slice.call(document.images);
    var broken = imgs.filter(function (i) { return !(i.complete && i.naturalWidth > 0); })
                     .map(function (i) { return i.alt || i.src.slice(0, 80); });
    var fetched = performance.getEntriesByType('resource').map(function (e) { return e.name; })
                     .filter(function (n) { return !/^(data|file):/.test(n); });
    var pre = document.createElement('pre');
    pre.id = '__report_check__';
    pre.textContent = JSON.stringify({n_images: imgs.length, broken: broken, fetched: fetched});
    document.body.appendChild(pre);
  }, 0);
});
</script>"""


class Collect(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.refs, self.ids, self.styles, self.in_style = [], set(), [], False

    def handle_starttag(self, tag, attrs):
        for k, v in attrs:
            if k == "id" and v:
                self.ids.add(v)
            if v is None:
                continue
            if k in ("src", "href", "srcset", "action", "data", "poster", "background"):
                self.refs.append((tag, k, v))
            if k == "style":
                self.styles.append(v)
        self.in_style = tag == "style"

    def handle_endtag(self, tag):
        self.in_style = False

    def handle_data(self, data):
        if self.in_style:
            self.styles.append(data)


def static_problems(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    c = Collect()
    c.feed(text)
    base = os.path.dirname(os.path.abspath(path))
    problems = []
    for tag, attr, v in c.refs:
        if NETWORK.match(v):
            problems.append(f"<{tag} {attr}> refers to the network: {v[:100]}")
        elif v.startswith("#"):
            if v[1:] not in c.ids:
                problems.append(f"<{tag} {attr}> names a missing anchor {v}")
        elif not v.startswith("data:") and not v.startswith("mailto:"):
            target = os.path.join(base, v.split("#")[0])
            if not os.path.exists(target):
                problems.append(f"<{tag} {attr}> names a missing file {v}")
    for s in c.styles:
        if CSS_URL.search(s):
            problems.append(f"CSS refers to the network: {CSS_URL.search(s).group(0)}")
    return problems, text


def browser_result(text, chromium, base):
    """The probe's JSON from headless Chromium, or raises RuntimeError."""
    with tempfile.TemporaryDirectory() as tmp:
        # A copy in a scratch folder with <base> pointing at the report's folder, so relative
        # links resolve as in the original and nothing is written beside the report.
        probe_page = os.path.join(tmp, "probe.html")
        page = text.replace("</body>", PROBE + "</body>") if "</body>" in text else text + PROBE
        basetag = f'<base href="file://{base}/">'
        page = re.sub(r"<head>", "<head>" + basetag, page, count=1) if "<head>" in page \
            else basetag + page
        with open(probe_page, "w", encoding="utf-8") as f:
            f.write(page)
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
               "--disable-background-networking", "--disable-component-update",
               "--disable-sync", "--metrics-recording-only", "--no-default-browser-check",
               f"--user-data-dir={os.path.join(tmp, 'profile')}",
               # any host resolves to nothing and any proxy is unreachable: a page that
               # needs the network shows it as broken images or fetched resources
               "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=127.0.0.1:9",
               "--virtual-time-budget=20000", "--dump-dom", "file://" + probe_page]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    m = re.search(r'<pre id="__report_check__">(.*?)</pre>', r.stdout, re.S)
    if not m:
        raise RuntimeError(f"chromium gave no result (exit {r.returncode}): {r.stderr[-800:]}")
    return json.loads(html.unescape(m.group(1)))


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("report")
    p.add_argument("--chromium", default=shutil.which("chromium") or shutil.which("chromium-browser"))
    a = p.parse_args()
    problems, text = static_problems(a.report)
    if not a.chromium:
        print("check_report_html: chromium not found (Debian package chromium; scripts/setup)")
        return 2
    try:
        res = browser_result(text, a.chromium, os.path.dirname(os.path.abspath(a.report)))
    except (RuntimeError, subprocess.TimeoutExpired, OSError) as e:
        print(f"check_report_html: {e}")
        return 2
    for b in res["broken"]:
        problems.append(f"image did not load in Chromium: {b}")
    for u in res["fetched"]:
        problems.append(f"Chromium fetched a non-local resource: {u}")
    print(f"{a.report}: {res['n_images']} images, {len(res['broken'])} broken, "
          f"{len(res['fetched'])} non-local fetches, {len(problems)} problems")
    for pr in problems:
        print("  " + pr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
