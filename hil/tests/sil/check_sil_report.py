#!/usr/bin/python3
"""The HTML report of a cvtplant-sil run (docs/sil.md#report), opened in
headless Chromium: the summary table has a row per scenario with its
verdict, the criteria tables hold every JUnit check with its verdict and
measured value, and every scenario's figure is embedded and decoded by the
browser. A run with an undersized clamp must show FAIL where it fails.

usage: check_sil_report.py CVTPLANT_SIL SIL_REPORT OUT_DIR
"""
import base64
import html.parser
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tests", "support"))
import pngread  # noqa: E402

SIL, REPORT, OUT = sys.argv[1:4]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


class Dom(html.parser.HTMLParser):
    """Rows of the summary and criteria tables, images, the body's attributes."""

    def __init__(self):
        super().__init__()
        self.rows, self.images, self.body, self.verdict = [], [], {}, ""
        self._row = self._cell = None
        self._in_verdict = False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "body":
            self.body = a
        elif tag == "tr" and a.get("class") in ("scenario", "check"):
            self._row = {"class": a["class"], "cells": []}
        elif tag == "td" and self._row is not None:
            self._cell = ""
        elif tag == "img":
            self.images.append(a.get("src", ""))
        elif tag == "p" and a.get("id") == "verdict":
            self._in_verdict = True

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data
        if self._in_verdict:
            self.verdict += data

    def handle_endtag(self, tag):
        if tag == "td" and self._row is not None and self._cell is not None:
            self._row["cells"].append(self._cell.strip())
            self._cell = None
        elif tag == "tr" and self._row is not None:
            self.rows.append(self._row)
            self._row = None
        elif tag == "p":
            self._in_verdict = False


def chromium_dom(path):
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        print("FAIL: chromium is not installed (tools/apt-packages.txt)")
        sys.exit(1)
    with tempfile.TemporaryDirectory() as profile:
        p = subprocess.run([exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                            "--user-data-dir=" + profile, "--dump-dom", "file://" + os.path.abspath(path)],
                           capture_output=True, text=True, timeout=180)
    check(p.returncode == 0, "chromium opened %s (exit %d)" % (path, p.returncode))
    d = Dom()
    d.feed(p.stdout)
    return d


def one_run(name, args, expect_fail):
    out = os.path.join(OUT, name)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    junit = os.path.join(out, "sil-junit.xml")
    r = subprocess.run([SIL, "run", "--loopback", "--out", out, "--junit", junit, *args], capture_output=True,
                       text=True, timeout=600)
    check(r.returncode == (1 if expect_fail else 0), "%s: cvtplant-sil exit %d" % (name, r.returncode))
    g = subprocess.run([REPORT, out], capture_output=True, text=True, timeout=300)
    check(g.returncode == 0, "%s: sil-report exit %d %s" % (name, g.returncode, g.stderr.strip()))
    report = os.path.join(out, "sil-report.html")
    dom = chromium_dom(report)
    suites = list(ET.parse(junit).getroot().iter("testsuite"))
    scen = [r["cells"] for r in dom.rows if r["class"] == "scenario"]
    checks = [r["cells"] for r in dom.rows if r["class"] == "check"]
    check([c[0] for c in scen] == [s.get("name")[4:] for s in suites],
          "%s: one summary row per scenario, in the run's order: %s" % (name, [c[0] for c in scen]))
    for s, row in zip(suites, scen):
        failed = int(s.get("failures"))
        check(row[-1] == ("FAIL" if failed else "PASS") and int(row[4]) == failed and int(row[2]) == int(s.get("tests")),
              "%s: %s summary: %s" % (name, row[0], row[2:]))
        check(bool(row[1]), "%s: %s is described" % (name, row[0]))
    want = [(c.get("name"), "FAIL" if c.find("failure") is not None else
             "not judged" if c.find("skipped") is not None else "PASS", (c.findtext("system-out") or "").strip())
            for s in suites for c in s.iter("testcase")]
    got = [(c[0], c[3], c[2]) for c in checks]
    check(got == want, "%s: every criterion with its verdict and measured value (%d)" % (name, len(want)))
    check(all(c[1] for c in checks), "%s: every criterion says what it asks" % name)
    check(dom.verdict.startswith("Verdict: " + ("FAIL" if expect_fail else "PASS")), "%s: %s" % (name, dom.verdict))
    pngs = [s for s in dom.images if s.startswith("data:image/png;base64,")]
    check(len(pngs) == len(suites) == len(dom.images), "%s: one embedded figure per scenario (%d)" % (name, len(pngs)))
    check(dom.body.get("data-figures-shown") == str(len(suites)),
          "%s: Chromium decoded %s of %d figures" % (name, dom.body.get("data-figures-shown"), len(suites)))
    for i, src in enumerate(pngs):
        path = os.path.join(out, "figure-%d.png" % i)
        with open(path, "wb") as f:
            f.write(base64.b64decode(src.split(",", 1)[1]))
        w, h, rows = pngread.read(path)
        ink = pngread.ink_fraction(rows)
        panels = pngread.panel_count(rows)
        check((w, h) == (1100, 1000) and 0.02 < ink < 0.6 and panels == 4,
              "%s: figure %d is 1100 x 1000 with 4 panels and ink %.3f (%d x %d, %d panels)" % (name, i, ink, w, h,
                                                                                                  panels))
    check(os.path.getsize(report) < 4e6, "%s: report is %d bytes" % (name, os.path.getsize(report)))


one_run("ratio-sweep", ["--scenario", "ratio-sweep"], False)
one_run("undersized", ["--scenario", "load-step", "--safety", "0.8"], True)
sys.exit(1 if failures else 0)
