#!/usr/bin/env python3
"""`cvtplant calibrate --measured` as a user drives it (docs/validation.md#measured-csv):
the example rig log fitted from a start 15-25 % off recovers the values it
was made with within three of the standard deviations the fit states, the
parameter the log cannot see is flagged, the files it writes, and every kind
of bad log or option is refused with one line and exit 2. About 0.5 s of CPU."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

from cli_checks import assert_usage_error, quiet_json

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
HERE = os.path.dirname(os.path.abspath(__file__))
LOG = os.path.join(HERE, "..", "measured", "rig-log.csv")
PLANT = os.path.join(HERE, "..", "measured", "rig-plant.toml")
# The values rig-log.csv was made with (rig-plant.toml's [params]).
TRUTH = {"normal_load_factor": 1.0, "k1_N_m": 2707.8729961981267, "c1_Ns_m": 81.236189885943800}
FIT = "normal_load_factor,k1_N_m,c1_Ns_m,creep_gain"
START = "[params]\nnormal_load_factor = 1.15\nk1_N_m = 2166.3\nc1_Ns_m = 97.48\n"

HEADER = "time_s,tau_in_Nm,clamp1_N,omega1_rad_s,omega2_rad_s\n"
ROWS = "".join("%.3f,60,3300,%.1f,100\n" % (0.001 * i, 150 + 0.1 * i) for i in range(20))


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


class Example(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.start = os.path.join(cls.tmp.name, "start.toml")
        with open(cls.start, "w") as f:
            f.write(START)
        cls.out = os.path.join(cls.tmp.name, "fitted.toml")
        cls.hpp = os.path.join(cls.tmp.name, "fitted.hpp")
        cls.r = run("calibrate", "--measured", LOG, "--scene", PLANT, "--fit", FIT, "--start", cls.start,
                    "--out", cls.out, "--header", cls.hpp, "--json")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_recovers_the_values_within_three_sigma(self):
        j = quiet_json(self, self.r)
        self.assertEqual(j["measured"], [LOG])
        self.assertEqual(j["plant_faults"], 0)
        # 301 rows of two speeds and the ratio.
        self.assertEqual(j["residuals"], 3 * 301)
        params = {p["name"]: p for p in j["parameters"]}
        for name, truth in TRUTH.items():
            p = params[name]
            self.assertTrue(p["identifiable"], p)
            self.assertLess(abs(p["value"] - truth), 3 * p["sigma"], p)
            self.assertLess(p["sigma_rel"], 0.1, p)
            # The start was far outside it: the fit moved the value.
            self.assertGreater(abs(p["start"] - truth), 10 * p["sigma"], p)
        # creep_gain is the tension feature's, which the plant has not.
        self.assertFalse(params["creep_gain"]["identifiable"])
        self.assertIsNone(params["creep_gain"]["sigma"])
        case = j["cases"][0]
        self.assertTrue(case["measured"])
        # The start speeds, fitted too: the plant's 150 and 100 rad/s.
        v = case["start_speeds"]
        self.assertLess(abs(v["omega1_rad_s"] - 150.0), 3 * v["sigma1_rad_s"], v)
        self.assertLess(abs(v["omega2_rad_s"] - 100.0), 3 * v["sigma2_rad_s"], v)
        for q in ("omega1", "omega2", "ratio"):
            self.assertLess(case[q]["rel_rms_end"], case[q]["rel_rms_start"], q)
        # What is left is about the noise: 0.2 rad/s on about 157 rad/s.
        self.assertLess(case["omega1"]["rel_rms_end"], 0.002)

    def test_files_carry_the_values_and_the_command(self):
        j = quiet_json(self, self.r)
        with open(self.out) as f:
            text = f.read()
        self.assertIn("fitted to measured logs", text)
        self.assertIn("cvtplant calibrate --measured " + LOG, text)
        self.assertIn("--every 1 ", text)
        for p in j["parameters"]:
            self.assertIn("%s = %.17g" % (p["name"], p["value"]), text)
        with open(self.hpp) as f:
            self.assertIn("constexpr void apply(RomParams& p)", f.read())

    def test_two_logs_fit_together(self):
        other = os.path.join(self.tmp.name, "second-rig-log.csv")
        shutil.copyfile(LOG, other)
        j = quiet_json(self, run("calibrate", "--measured", LOG, "--measured", other, "--scene", PLANT, "--fit",
                                 "k1_N_m", "--max-evals", "7", "--json"))
        self.assertEqual(j["measured"], [LOG, other])
        self.assertEqual(j["residuals"], 2 * 3 * 301)
        self.assertEqual(len(j["cases"]), 2)
        self.assertLessEqual(j["plant_evaluations"], 7)
        # One parameter and two start speeds per log: 7 evaluations at the least.
        r = run("calibrate", "--measured", LOG, "--measured", other, "--scene", PLANT, "--fit", "k1_N_m",
                "--max-evals", "6")
        assert_usage_error(self, r, "4 start speed(s)")

    def test_text_table(self):
        r = run("calibrate", "--measured", LOG, "--scene", PLANT, "--fit", "k1_N_m", "--start", self.start)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| log | quantity |", r.stdout)
        self.assertIn("| ratio |", r.stdout)
        self.assertIn("start speeds fitted to omega1 = ", r.stdout)


class BadInput(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def file(self, name, text):
        path = os.path.join(self.tmp.name, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    def check_log(self, text, needle, scene=PLANT):
        path = self.file("bad.csv", text)
        args = ["calibrate", "--measured", path, "--scene", scene, "--fit", "k1_N_m"]
        assert_usage_error(self, run(*args), needle, args)

    def check(self, args, needle):
        assert_usage_error(self, run(*args), needle, args)

    def test_a_good_log_of_the_same_shape_runs(self):
        path = self.file("good.csv", HEADER + ROWS)
        r = run("calibrate", "--measured", path, "--scene", PLANT, "--fit", "k1_N_m", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_bad_logs(self):
        self.check_log("time_s,tau_in_Nm,clamp1_N,omega1_rad_s\n0,1,2,3\n1,1,2,3\n2,1,2,3\n", "no column of the secondary speed")
        self.check_log(HEADER + ROWS + "0.010,60,3300,150,100\n", "time must increase")
        self.check_log(HEADER + ROWS + "0.100,60,nan,150,100\n", "NaN")
        self.check_log(HEADER + "0,60,3300,150,100\n0.001,60,3300,150,100\n", "at least 3")
        self.check_log(HEADER.replace("omega1_rad_s", "omega1_deg_s") + ROWS, "unknown column 'omega1_deg_s'")
        self.check_log(HEADER.replace("clamp1_N", "p1_bar") + ROWS, "piston area")
        self.check_log(HEADER + ROWS + "0.100,60,3300,150\n", "cells")
        self.check_log(HEADER + ROWS + "0.100,60,-1,150,100\n", "clamping must be >= 0")
        # A driven clamping on a plant without (clamp-step: no wedging).
        self.check_log("time_s,tau_in_Nm,clamp1_N,clamp2_N,omega1_rad_s,omega2_rad_s\n" +
                       "".join("%.3f,60,3300,3600,150,100\n" % (0.001 * i) for i in range(5)),
                       "no wedging", scene="clamp-step")
        self.check(["calibrate", "--measured", os.path.join(self.tmp.name, "missing.csv"), "--scene", PLANT],
                   "missing.csv")

    def test_no_output_over_an_input(self):
        log = self.file("log.csv", HEADER + ROWS)
        with open(log) as f:
            before = f.read()
        self.check(["calibrate", "--measured", log, "--scene", PLANT, "--fit", "k1_N_m", "--out", log], "--out")
        self.check(["calibrate", "--measured", log, "--scene", PLANT, "--fit", "k1_N_m", "--header", log], "--header")
        with open(log) as f:
            self.assertEqual(f.read(), before)

    def test_bad_options(self):
        log = self.file("log.csv", HEADER + ROWS)
        self.check(["calibrate", "--measured", log, "--fit", "k1_N_m"], "--measured needs --scene")
        # The same log twice (by another name too) would count twice.
        self.check(["calibrate", "--measured", log, "--measured", log, "--scene", PLANT], "given twice")
        self.check(["calibrate", "--measured", log, "--measured", os.path.join(self.tmp.name, ".", "log.csv"),
                    "--scene", PLANT], "given twice")
        self.check(["calibrate", "--measured", log, "--scene", PLANT + ",clamp-step"], "one scene")
        self.check(["calibrate", "--measured", log, "--scene", PLANT, "--set", "production"], "--set is the reference's")
        self.check(["calibrate", "--measured", log, "--scene", PLANT, "--fit", "k1_N_m", "--max-evals", "4"],
                   "--max-evals")
        self.check(["calibrate", "--measured", log, "--scene", PLANT, "--piston-area1", "0"], "--piston-area1")
        self.check(["calibrate", "--scene", "gross-slip", "--piston-area1", "0.01"], "no --measured")


if __name__ == "__main__":
    unittest.main()
