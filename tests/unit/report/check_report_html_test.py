#!/usr/bin/python3
"""The report checker (check_report_html.py) can fail: a clean page passes, a page with an image
that does not decode, one that refers to the network, and one with a dead link each fail.

    check_report_html_test.py CASE     CASE: clean | broken_image | network | dead_link
"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
# a 1×1 PNG (valid), and bytes that are not an image
PNG_1x1 = ("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk+M9QDwADhgGAWjR9awAAAABJRU5E"
           "rkJggg==")
PAGES = {
    "clean": (0, f'<img src="data:image/png;base64,{PNG_1x1}" alt="ok">'
                 '<a href="data.csv">csv</a><a href="#top">top</a>'
                 '<details><summary>folded</summary>'
                 f'<img src="data:image/png;base64,{PNG_1x1}" alt="folded ok"></details>'),
    "broken_image": (1, '<img src="data:image/png;base64,AAAAAAAA" alt="not a png">'),
    "network": (1, '<img src="https://example.invalid/x.png" alt="remote">'),
    "dead_link": (1, '<a href="missing.csv">gone</a>'),
}


def main():
    case = sys.argv[1]
    expected, body = PAGES[case]
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "data.csv"), "w") as f:
            f.write("x\n1\n")
        page = os.path.join(d, "report.html")
        with open(page, "w") as f:
            f.write(f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>t</title></head>"
                    f"<body><h1 id='top'>t</h1>{body}</body></html>")
        r = subprocess.run([sys.executable, os.path.join(HERE, "check_report_html.py"), page],
                           capture_output=True, text=True)
    print(r.stdout + r.stderr)
    if r.returncode != expected:
        print(f"FAIL: case {case}: exit {r.returncode}, expected {expected}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
