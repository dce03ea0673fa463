#!/usr/bin/env python3
"""`cvtplant validate` and `cvtplant calibrate` as a user drives them, on a
shortened span (docs/validation.md): the table, the overlays, the reference
cache, the parameter file, and bad input."""
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest

from cli_checks import assert_usage_error, quiet_json

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
SHORT = ["--t-end", "0.2"]


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


class Validate(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = os.path.join(cls.tmp.name, "v")
        cls.first = run("validate", "--scene", "seed-case1", *SHORT, "--out-dir", cls.out, "--json")
        with open(os.path.join(cls.out, "seed-case1.csv")) as f:
            cls.first_csv_lines = f.read().splitlines()
        cls.second = run("validate", "--scene", "seed-case1", *SHORT, "--out-dir", cls.out, "--json")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_json_rows_and_files(self):
        j = quiet_json(self, self.first)
        (s,) = j["scenes"]
        self.assertEqual(s["status"], "ok")
        self.assertFalse(s["reference"]["from_cache"])
        self.assertLessEqual(s["reference"]["energy_residual_rel"], 1e-6)
        names = [e["quantity"] for e in s["errors"]]
        for q in ("omega1", "omega2", "ratio omega1/omega2", "F_ax1 (mean)", "torque on the driver", "driver slip"):
            self.assertIn(q, names)
        for e in s["errors"]:
            # Not computed (docs/cli.md#nulls): null, checked one by one below.
            if e["quantity"] == "F_ax2 (mean)" or e["quantity"].startswith("ratio"):
                continue
            self.assertIsNotNone(e["rel_rms"], e)
            self.assertGreaterEqual(e["rel_rms"], 0.0)
        by_name = {e["quantity"]: e for e in s["errors"]}
        # seed-case1's plant has no driven axial force (no wedging), and in
        # its first 0.2 s the reference's driven pulley turns slower than
        # 1 rad/s (the ratio's threshold): neither has an error, not a zero one.
        self.assertIsNone(by_name["F_ax2 (mean)"]["rel_rms"])
        self.assertIsNone(by_name["F_ax2 (mean)"]["plant_ss"])
        self.assertIsNotNone(by_name["F_ax2 (mean)"]["reference_ss"])
        self.assertIsNone(by_name["ratio omega1/omega2"]["rel_rms"])
        self.assertTrue(os.path.getsize(s["png"]) > 10000)
        self.assertEqual(s["csv"], os.path.join(self.out, "seed-case1.csv"))
        self.assertEqual(len(self.first_csv_lines), 1 + 201)  # t = 0, 1 ms, ..., 0.2 s
        # seed-case1 runs the seed's fixed pulleys (docs/rom.md#tension), so
        # --sheaves scene (the default) compares it with the reference's.
        self.assertEqual(j["sheaves"], "scene")
        self.assertEqual(s["sheaves"], "fixed")
        self.assertEqual(s["sheave_at_stop_s"], {"driver": None, "driven": None})
        # Both models' axial force is the chain's own on fixed sheaves; at the
        # release it is the settled pretension's in both, T_max theta1 /
        # (2 tan beta0) = 2.99 kN (the plant's T_max is the reference's at rest).
        rows = list(csv.DictReader(self.first_csv_lines))
        self.assertAlmostEqual(float(rows[0]["F_ax1_ref_N"]) / 2994.4, 1.0, delta=1e-3)
        self.assertAlmostEqual(float(rows[0]["F_ax1_plant_N"]) / float(rows[0]["F_ax1_ref_N"]), 1.0, delta=2e-3)
        # The whole wrap's slip never exceeds the mean over the wrap.
        for row in rows:
            for m in ("plant", "ref"):
                self.assertLessEqual(abs(float(row["wrap_slip1_%s_m_s" % m])), abs(float(row["slip1_%s_m_s" % m])) + 1e-12)

    def test_run_too_short_for_a_ratio_still_draws(self):
        # 50 ms: the driven pulley stays below 1 rad/s, so the ratio panel has
        # no defined value; the overlay is still drawn on the run's time axis.
        with tempfile.TemporaryDirectory() as d:
            r = run("validate", "--scene", "seed-case1", "--t-end", "0.05", "--out-dir", d, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            (s,) = json.loads(r.stdout)["scenes"]
            self.assertTrue(os.path.getsize(s["png"]) > 10000)

    def test_second_run_reuses_the_reference_and_reports_the_same(self):
        self.assertEqual(self.second.returncode, 0, self.second.stderr)
        a = json.loads(self.first.stdout)["scenes"][0]
        b = json.loads(self.second.stdout)["scenes"][0]
        self.assertTrue(b["reference"]["from_cache"])
        self.assertEqual(a["errors"], b["errors"])

    def test_a_changed_input_misses_the_cache(self):
        r = run("validate", "--scene", "seed-case1", "--t-end", "0.1", "--out-dir", self.out, "--json",
                "--no-figures")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertFalse(json.loads(r.stdout)["scenes"][0]["reference"]["from_cache"])

    def test_scenes_the_reference_cannot_run_are_named_with_the_reason(self):
        r = run("validate", "--scene", "oscillator-coulomb", "--out-dir", self.out, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        s = json.loads(r.stdout)["scenes"][0]
        self.assertEqual(s["status"], "not run")
        self.assertIn("held pulleys", s["reason"])
        with tempfile.TemporaryDirectory() as d:
            scene = os.path.join(d, "wobble.toml")
            with open(scene, "w") as f:
                f.write('name = "wobble"\nbase = "seed-case1"\n[inputs]\n'
                        'tau_in = { kind = "sine", offset = 100.0, amplitude = 10.0, freq_hz = 2.0 }\n')
            r = run("validate", "--scene", scene, "--out-dir", d, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            s = json.loads(r.stdout)["scenes"][0]
            self.assertEqual(s["status"], "not run")
            self.assertIn("sine torque profile", s["reason"])

    def test_clamped_sheaves_are_another_reference_run(self):
        r = run("validate", "--scene", "seed-case1", "--t-end", "0.05", "--sheaves", "clamped", "--out-dir", self.out,
                "--json", "--no-figures")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["sheaves"], "clamped")
        (s,) = j["scenes"]
        self.assertEqual(s["sheaves"], "clamped")
        self.assertFalse(s["reference"]["from_cache"])
        # The clamped reference holds the scene's 3.3 kN (its clamping profile,
        # which the plant's fixed sheaves do not use).
        fax = next(e for e in s["errors"] if e["quantity"] == "F_ax1 (mean)")
        self.assertAlmostEqual(fax["reference_ss"] / 3300.0, 1.0, delta=0.05)

    def test_scene_sheaves_are_fixed_only_where_the_plant_has_fixed_sheaves(self):
        # docs/validation.md#method: fixed_sheaves acts with the tension
        # feature only. A tension plant held by its actuator, and an axial
        # plant whose parameters carry fixed_sheaves from seed-case1, are both
        # compared with the clamped reference (the same run: same inputs).
        with tempfile.TemporaryDirectory() as d:
            clamped = os.path.join(d, "held.toml")
            with open(clamped, "w") as f:
                f.write('name = "held"\nbase = "seed-case1"\nfeatures = ["axial", "tension"]\n'
                        '[params]\nfixed_sheaves = false\n')
            axial = os.path.join(d, "axial.toml")
            with open(axial, "w") as f:
                f.write('name = "axial"\nbase = "seed-case1"\nfeatures = ["axial"]\n')
            got = []
            for scene in (clamped, axial):
                r = run("validate", "--scene", scene, "--t-end", "0.05", "--out-dir", d, "--json", "--no-figures")
                self.assertEqual(r.returncode, 0, r.stderr)
                got.append(json.loads(r.stdout)["scenes"][0])
            self.assertEqual([s["sheaves"] for s in got], ["clamped", "clamped"])
            self.assertFalse(got[0]["reference"]["from_cache"])
            self.assertTrue(got[1]["reference"]["from_cache"])

    def test_gross_slip_is_the_whole_wrap_sliding_in_both_models(self):
        # gross-slip (1 kN): both models' driver wrap slides as a whole within
        # 0.6 s (docs/validation.md#method: plant 0.22 s, reference 0.47 s),
        # the first sample whose whole-wrap slip passes 1 m/s; that slip never
        # exceeds the mean over the wrap.
        with tempfile.TemporaryDirectory() as d:
            r = run("validate", "--scene", "gross-slip", "--t-end", "0.6", "--out-dir", d, "--json", "--no-figures")
            self.assertEqual(r.returncode, 0, r.stderr)
            (s,) = json.loads(r.stdout)["scenes"]
            g = s["gross_slip_s"]
            self.assertEqual(g["threshold_m_s"], 1.0)
            self.assertIsNotNone(g["plant"])
            self.assertIsNotNone(g["reference"])
            self.assertLess(g["plant"], g["reference"])
            with open(s["csv"]) as f:
                rows = list(csv.DictReader(f))
            for m in ("plant", "ref"):
                first = next(float(row["t_s"]) for row in rows if abs(float(row["wrap_slip1_%s_m_s" % m])) > 1.0)
                self.assertAlmostEqual(first, g["plant" if m == "plant" else "reference"], places=9)
                for row in rows:
                    self.assertLessEqual(abs(float(row["wrap_slip1_%s_m_s" % m])),
                                         abs(float(row["slip1_%s_m_s" % m])) + 1e-12)

    def test_text_table(self):
        r = run("validate", "--scene", "seed-case1", *SHORT, "--out-dir", self.out, "--no-figures")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| omega1 | rad/s |", r.stdout)
        self.assertIn("| F_ax2 (mean) | N | n/a | n/a |", r.stdout)
        self.assertIn("time to gross slip", r.stdout)


class AtSpeed(unittest.TestCase):
    def test_tip_in_runs_from_its_start_at_speed(self):
        # tip-in: road load, a torque ramp (later than 50 ms) and a start at
        # 150 / 100 rad/s (docs/mbd.md#start-at-speed); 50 ms after the release.
        with tempfile.TemporaryDirectory() as d:
            r = run("validate", "--scene", "tip-in", "--t-end", "0.05", "--out-dir", d, "--json", "--no-figures")
            self.assertEqual(r.returncode, 0, r.stderr)
            (s,) = json.loads(r.stdout)["scenes"]
            self.assertEqual(s["status"], "ok", s)
            self.assertFalse(s["reference"]["from_cache"])
            self.assertIsNone(s["reference"]["failure"])
            self.assertLessEqual(s["reference"]["energy_residual_rel"], 1e-6)
            self.assertEqual(len(s["errors"]), 8)
            with open(s["csv"]) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(len(rows), 51)
            first = rows[0]
            self.assertEqual(float(first["omega1_plant"]), 150.0)
            self.assertEqual(float(first["omega1_ref"]), 150.0)
            # The reference's driven pulley finds its own speed in the hold:
            # near the plant's 100 rad/s.
            self.assertAlmostEqual(float(first["omega2_ref"]) / 100.0, 1.0, delta=0.1)
            # Running, not starting: both driven pulleys stay near their speeds.
            for row in rows:
                self.assertAlmostEqual(float(row["omega2_ref"]) / float(first["omega2_ref"]), 1.0, delta=0.02)


TOML = r"^(\w+) = ([-+0-9.eE]+)"
HPP = r"^  p\.(\w+) = ([-+0-9.eE]+);"


def values(text, pattern):
    return {m.group(1): float(m.group(2)) for m in re.finditer(pattern, text, re.M)}


class CalibratedSet(unittest.TestCase):
    def test_the_checked_in_headers_hold_the_parameter_files_values(self):
        # The built-in scenes read the headers; docs and users read the files.
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
        for toml_name, hpp_name in (("calibrated.toml", "calibrated_params.hpp"),
                                    ("wrap-tension.toml", "calibrated_wrap_tension.hpp"),
                                    ("tension.toml", "calibrated_tension.hpp")):
            with open(os.path.join(root, "tools", "params", toml_name)) as f:
                toml_values = values(f.read(), TOML)
            with open(os.path.join(root, "lib", "include", "cvtplant", "scene", hpp_name)) as f:
                hpp_values = values(f.read(), HPP)
            self.assertTrue(toml_values, toml_name)
            self.assertEqual(hpp_values, toml_values, toml_name)

    def test_the_stop_scenes_carry_the_derived_and_calibrated_tension(self):
        # docs/validation.md#tension-on-the-stops. T_max on the closing stops:
        # the fixed sheaves' T_max plus the stretch of the chain (44 links,
        # k = 90 kN/m) whose every wrap runs 25 mm further out, less the bolts'
        # extra sink under the higher tension (Table 1: K_b, L; beta0 = 15 deg),
        # from the settled strands' 516 N (docs/mbd.md#open-choices).
        k, n, L, Kb, b = 90e3, 44, 0.03, 200e3, math.radians(15.0)
        r = (0.0762, 0.1143)
        d = math.asin((r[1] - r[0]) / 0.5)
        theta = (math.pi - 2 * d, math.pi + 2 * d)
        dr = 0.013397459621556135 / (2 * math.tan(b))  # the sheave's stop s_max (docs/mbd.md#clamped-sheaves), radially
        sink = lambda T, rho: T * L / (4 * Kb * math.tan(b) ** 2 * rho)
        T0, dT = 516.0, 0.0
        for _ in range(50):
            dT = k / n * sum(th * (dr - (sink(T0 + dT, rj + dr) - sink(T0, rj))) for th, rj in zip(theta, r))
        root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
        with open(os.path.join(root, "tools", "params", "tension.toml")) as f:
            fixed = values(f.read(), TOML)
        with open(os.path.join(root, "tools", "params", "tension-stops.toml")) as f:
            stops = values(f.read(), TOML)
        T_max = 536.86268306837  # RomParams' default: the reference at rest on fixed sheaves
        for name in ("tip-in-tension.toml", "clamp-step-tension.toml"):
            with open(os.path.join(root, "tools", "scenes", name)) as f:
                v = values(f.read(), TOML)
            self.assertAlmostEqual(v["stop_tension_N"], T_max + dT, delta=0.01, msg=name)
            self.assertEqual(v["centrifugal_gain"], stops["centrifugal_gain"], name)
            self.assertEqual(v["stop_tension_share"], fixed["stop_tension_share"], name)

    def test_params_moves_the_plant_only(self):
        with tempfile.TemporaryDirectory() as d:
            uncal = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "params",
                                 "uncalibrated.toml")
            a = run("validate", "--scene", "gross-slip", *SHORT, "--out-dir", d, "--json", "--no-figures")
            b = run("validate", "--scene", "gross-slip", *SHORT, "--out-dir", d, "--json", "--no-figures",
                    "--params", uncal)
            self.assertEqual(a.returncode, 0, a.stderr)
            self.assertEqual(b.returncode, 0, b.stderr)
            sa, sb = json.loads(a.stdout)["scenes"][0], json.loads(b.stdout)["scenes"][0]
            self.assertTrue(sb["reference"]["from_cache"])  # the same reference run
            ta = next(e for e in sa["errors"] if e["quantity"] == "torque on the driver")
            tb = next(e for e in sb["errors"] if e["quantity"] == "torque on the driver")
            self.assertEqual(ta["reference_ss"], tb["reference_ss"])
            # The lower calibrated normal load gives a lower sliding torque.
            self.assertLess(ta["plant_ss"], tb["plant_ss"])


class DefaultOutputDir(unittest.TestCase):
    """Without --out-dir both commands write under build/validation of the
    working directory (its parents created), never into a folder named like
    a module of the source tree."""

    def test_default_is_under_build(self):
        with tempfile.TemporaryDirectory() as d:
            r = subprocess.run([os.path.abspath(CLI) if os.sep in CLI else CLI, "validate", "--scene", "gross-slip",
                                "--t-end", "0.05", "--json", "--no-figures"],
                               capture_output=True, text=True, timeout=600, cwd=d)
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            self.assertEqual(j["out_dir"], "build/validation")
            self.assertTrue(os.path.isfile(os.path.join(d, "build", "validation", "gross-slip.csv")))
            self.assertTrue(os.path.isdir(os.path.join(d, "build", "validation", "reference-cache")))
            self.assertFalse(os.path.exists(os.path.join(d, "validation")))
            r = subprocess.run([os.path.abspath(CLI) if os.sep in CLI else CLI, "calibrate", "--scene", "gross-slip",
                                "--t-end", "0.05", "--fit", "normal_load_factor", "--max-evals", "3", "--json"],
                               capture_output=True, text=True, timeout=600, cwd=d)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(sorted(os.listdir(d)), ["build"])


class BadInput(unittest.TestCase):
    def check(self, args, needle):
        assert_usage_error(self, run(*args), needle, args)

    def test_bad_options(self):
        with tempfile.TemporaryDirectory() as d:
            self.check(["validate", "--scene", "no-such-scene", "--out-dir", d], "neither a built-in")
            self.check(["validate", "--t-end", "nan", "--out-dir", d], "--t-end")
            self.check(["validate", "--t-end", "-1", "--out-dir", d], "--t-end")
            self.check(["validate", "--rtol", "1", "--out-dir", d], "--rtol")
            self.check(["validate", "--scene", "seed-case1", "--max-t-end", "1", "--out-dir", d], "--max-t-end")
            self.check(["validate", "--scene", "seed-case1", "--out-dir", "/proc/no/such/dir"], "--out-dir")
            self.check(["validate", "--scene", "seed-case1", "--sheaves", "floating", "--out-dir", d], "--sheaves")
            self.check(["validate", "--scene-dir", os.path.join(d, "missing"), "--out-dir", d], "--scene-dir")
            self.check(["calibrate", "--sheaves", "loose", "--out-dir", d], "--sheaves")
            self.check(["calibrate", "--fit", "k9", "--out-dir", d], "--fit: unknown parameter")
            self.check(["calibrate", "--fit", "k1_N_m,k1_N_m", "--out-dir", d], "twice")
            self.check(["calibrate", "--scene", "oscillator-coulomb", "--out-dir", d], "held pulleys")
            self.check(["calibrate", "--every", "0", "--out-dir", d], "--every")
            self.check(["calibrate", "--function", "1apply", "--out-dir", d], "--function")
            self.check(["calibrate", "--function", "apply;", "--out-dir", d], "--function")
            bad = os.path.join(d, "bad.toml")
            with open(bad, "w") as f:
                f.write("[params]\nk1_N_m = -5.0\n")
            self.check(["calibrate", "--scene", "seed-case1", "--start", bad, "--out-dir", d], "k1")
            with open(bad, "w") as f:
                f.write("[params]\nk1_typo = 5.0\n")
            self.check(["calibrate", "--scene", "seed-case1", "--start", bad, "--out-dir", d], "k1_typo")
            self.check(["validate", "--scene", "seed-case1", "--params", bad, "--out-dir", d], "k1_typo")
            with open(bad, "w") as f:
                f.write("[params]\nentry_load_share = 1.0\n")
            self.check(["validate", "--scene", "seed-case1", "--params", bad, "--out-dir", d], "entry_load_share")
            wedging = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "scenes",
                                   "seed-case1-wedging.toml")
            for v in ("1.0", "-0.1", "nan"):
                with open(bad, "w") as f:
                    f.write("[params]\nwrap_tension_share = %s\n" % v)
                self.check(["validate", "--scene", wedging, "--params", bad, "--out-dir", d], "wrap_tension_share")


class Calibrate(unittest.TestCase):
    def test_fit_lowers_the_residual_and_writes_a_loadable_file(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "p.toml")
            hpp = os.path.join(d, "p.hpp")
            r = run("calibrate", "--scene", "seed-case1", "--t-end", "0.3", "--fit", "r1_m,r2_m", "--every", "5",
                    "--max-evals", "40", "--out-dir", d, "--out", out, "--header", hpp, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            self.assertLess(j["cost_end"], j["cost_start"])
            for p in j["parameters"]:
                self.assertTrue(p["identifiable"], p)
                self.assertGreater(p["sigma"], 0.0)
            with open(out) as f:
                text = f.read()
            self.assertIn("[params]", text)
            self.assertIn("cvtplant calibrate --scene seed-case1", text)
            with open(hpp) as f:
                self.assertEqual(values(f.read(), HPP), values(text, TOML))
            # The file starts a second fit where the first ended: nothing left to gain.
            r2 = run("calibrate", "--scene", "seed-case1", "--t-end", "0.3", "--fit", "r1_m,r2_m", "--every", "5",
                     "--max-evals", "40", "--out-dir", d, "--start", out, "--json")
            self.assertEqual(r2.returncode, 0, r2.stderr)
            j2 = json.loads(r2.stdout)
            self.assertAlmostEqual(j2["cost_start"], j["cost_end"], delta=1e-9 + 1e-6 * j["cost_end"])

    def test_a_share_fit_from_zero_and_a_named_header_function(self):
        # The wrap-tension share on the variable-ratio seed case: the built-in
        # value is replaced by 0 (the term off); the fit starts from 0.5 and
        # ends in (0, 1); the header's function carries the given name.
        scene = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "scenes",
                             "seed-case1-wedging.toml")
        with tempfile.TemporaryDirectory() as d:
            off = os.path.join(d, "off.toml")
            with open(off, "w") as f:
                f.write("[params]\nwrap_tension_share = 0.0\n")
            hpp = os.path.join(d, "w.hpp")
            r = run("calibrate", "--scene", scene, "--t-end", "0.5", "--fit", "wrap_tension_share", "--every", "5",
                    "--max-evals", "30", "--out-dir", d, "--start", off, "--out", os.path.join(d, "w.toml"),
                    "--header", hpp, "--function", "apply_wrap", "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            (p,) = json.loads(r.stdout)["parameters"]
            self.assertEqual(p["start"], 0.5)
            self.assertGreater(p["value"], 0.0)
            self.assertLess(p["value"], 1.0)
            with open(hpp) as f:
                text = f.read()
            self.assertIn("constexpr void apply_wrap(RomParams& p) {", text)
            self.assertIn("--function apply_wrap", text)


if __name__ == "__main__":
    unittest.main()
