#!/usr/bin/env python3
"""The figures a controls engineer puts in a report (docs/analysis.md#figures):
each produced by its command, of the documented size, not blank, with the
expected number of stacked panels, and labelled (the gnuplot script the
command ran names the units and the parameters)."""
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "support"))
import pngread  # noqa: E402

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


class Figures(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.d = cls.tmp.name

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def look(self, path, w, h, panels, min_ink=0.02):
        pw, ph, rows = pngread.read(path)
        self.assertEqual((pw, ph), (w, h), path)
        ink = pngread.ink_fraction(rows)
        self.assertGreater(ink, min_ink, path + ": nearly blank")
        self.assertLess(ink, 0.6, path + ": mostly ink")
        self.assertEqual(pngread.panel_count(rows), panels, path)
        return rows

    def test_plant_scene_time_history_in_panels_by_unit(self):
        out = os.path.join(self.d, "case2")
        r = run("analyze", "figures", "--scene", "seed-case2", "--t-end", "2", "--out-dir", out, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        files = [os.path.basename(f) for f in json.loads(r.stdout)["files"]]
        self.assertEqual(files, ["scene_time_history.png", "scene_phase_lump1.png", "scene_phase_lump2.png"])
        # Six panels: speeds, ratio, forces, slip, lump displacement, lump velocity.
        self.look(os.path.join(out, "scene_time_history.png"), 1100, 6 * 210 + 90, 6)
        for lump in (1, 2):
            self.look(os.path.join(out, "scene_phase_lump%d.png" % lump), 800, 700, 1)
        with open(os.path.join(out, "scene.gp")) as f:
            gp = f.read()
        with open(os.path.join(out, "scene.dat")) as f:
            names = f.readline().split()[1:]
            data = [[float(v) for v in l.split()] for l in f]
        # Lengths are shown in m, mm or um after the largest magnitude (docs/analysis.md#figures).
        def length_unit(cols):
            peak = max(abs(r[names.index(c)]) for r in data for c in cols)
            return "m" if peak >= 1 else "mm" if peak >= 1e-3 else "um"
        ux, uv = length_unit(["x1", "x2"]), length_unit(["xd1", "xd2"]) + "/s"
        for label in ("speed [rad/s]", "speed ratio [-]", "force [kN]", "slip [-]", "lump displacement [%s]" % ux,
                      "lump velocity [%s]" % uv, "time t [s]", "x1 [%s]" % ux, "xd1 [%s]" % uv):
            self.assertIn("'" + label + "'", gp)
        # The ratio is left out where the driven pulley nearly stands (|omega2| < 1 rad/s), not drawn as +-1000.
        for r in data:
            ratio = r[names.index("speed_ratio")]
            self.assertEqual(ratio != ratio, abs(r[names.index("omega2")]) < 1.0)
        # The ratio's axis spans its 2nd to 98th percentile (padded), not the start's spike.
        ratios = sorted(r[names.index("speed_ratio")] for r in data if r[names.index("speed_ratio")] == r[names.index("speed_ratio")])
        lo, hi = ratios[len(ratios) // 50], ratios[len(ratios) - 1 - len(ratios) // 50]
        m = re.search(r"set yrange \[([-0-9.e+]+):([-0-9.e+]+)\]\nset ylabel 'speed ratio", gp)
        self.assertIsNotNone(m, "the ratio panel has its own y range")
        self.assertLess(float(m.group(1)), lo)
        self.assertGreater(float(m.group(2)), hi)
        self.assertLess(float(m.group(2)) - float(m.group(1)), 1.5 * (hi - lo) + 0.2 * max(abs(lo), abs(hi)))
        # The title names the scene, the scalar, the integrator and the frame step.
        self.assertIn("seed-case2: double, ros2 x 1 substeps, frame 1 ms", gp)
        # Only the bottom panel carries the time axis.
        self.assertEqual(gp.count("set xlabel 'time t [s]'"), 1)
        # The force panel is in kN: the driver's 3.3 kN clamping force reads 3.3.
        self.assertAlmostEqual(data[-1][names.index("F_ax")] * 1e-3, 3.3, delta=0.05)

    def test_model_time_history_one_panel_per_state(self):
        out = os.path.join(self.d, "lorenz")
        r = run("analyze", "figures", "--scene", "lorenz", "--t-end", "20", "--out-dir", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.look(os.path.join(out, "scene_time_history.png"), 1000, 3 * 150 + 90, 3)
        with open(os.path.join(out, "scene.gp")) as f:
            gp = f.read()
        # The title names the integrator and step and the classic parameters (sigma 10, rho 28, beta 8/3).
        self.assertRegex(gp, r"'lorenz: RK4, dt = [0-9.e-]+ s, beta = 2.66667, rho = 28, sigma = 10'")


if __name__ == "__main__":
    unittest.main()
