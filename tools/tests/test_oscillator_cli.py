#!/usr/bin/env python3
"""`cvtplant oscillator` as a user drives it: outputs, summaries, bad input."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=300)


class Outputs(unittest.TestCase):
    def test_csv_header_and_rows(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "osc.csv")
            r = run("oscillator", "--friction", "coulomb", "--x0", "0,3,0,6", "--t-end", "1",
                    "--dt", "1e-3", "--integrator", "ros2", "--csv", path)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(path) as f:
                rows = list(csv.reader(f))
            self.assertEqual(rows[0][:5], ["t", "x1", "v1", "x2", "v2"])
            self.assertEqual(len(rows), 1 + 1001)  # t = 0 plus every step
            self.assertEqual([float(v) for v in rows[1][1:5]], [0.0, 3.0, 0.0, 6.0])
            self.assertAlmostEqual(float(rows[-1][0]), 1.0, places=9)

    def test_json_summary_settles_for_coulomb(self):
        r = run("oscillator", "--friction", "coulomb", "--x0", "0,0,0,0", "--t-end", "40",
                "--dt", "1e-3", "--integrator", "ros2", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertTrue(j["settled"])
        self.assertEqual(j["behaviour"], "settled")
        self.assertAlmostEqual(j["final_state"]["x1_m"], j["sliding_equilibrium_m"], delta=1e-5)
        self.assertGreater(j["wall_s"], 0.0)

    def test_json_summary_oscillates_for_stribeck(self):
        r = run("oscillator", "--friction", "stribeck", "--x0", "0,3,0,6", "--t-end", "60",
                "--dt", "1e-4", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertFalse(j["settled"])
        self.assertEqual(j["behaviour"], "oscillating")
        self.assertGreater(j["last_window"]["x1_peak_to_peak_m"], 0.5)
        self.assertGreater(j["period_s"], 0.5)

    def test_every_scalar_type_runs(self):
        for scalar in ("double", "float", "fixed"):
            r = run("oscillator", "--friction", "coulomb", "--t-end", "30", "--dt", "0.0009765625",
                    "--integrator", "ros2", "--scalar", scalar, "--json")
            self.assertEqual(r.returncode, 0, scalar + r.stderr)
            j = json.loads(r.stdout)
            # q16.16 resolves 1.5e-5 m; float and double agree far better.
            self.assertAlmostEqual(j["final_state"]["x1_m"], j["sliding_equilibrium_m"], delta=3e-4, msg=scalar)

    def test_help(self):
        r = run("oscillator", "--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn("--friction", r.stdout)


class BadInput(unittest.TestCase):
    def assert_usage_error(self, *args, mentions):
        r = run(*args)
        self.assertEqual(r.returncode, 2, f"{args}: rc={r.returncode} stderr={r.stderr}")
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("error", lines[0])
        self.assertIn(mentions, lines[0])
        self.assertEqual(r.stdout, "")

    def test_bad_values(self):
        base = ["oscillator", "--t-end", "1"]
        self.assert_usage_error(*base, "--friction", "viscous", mentions="--friction")
        self.assert_usage_error(*base, "--x0", "0,1,2", mentions="--x0")
        self.assert_usage_error(*base, "--x0", "0,1,nan,3", mentions="--x0")
        self.assert_usage_error(*base, "--x0", "0,a,2,3", mentions="--x0")
        self.assert_usage_error(*base, "--dt", "-1", mentions="--dt")
        self.assert_usage_error(*base, "--dt", "0", mentions="--dt")
        self.assert_usage_error(*base, "--integrator", "rk45", mentions="--integrator")
        self.assert_usage_error(*base, "--scalar", "half", mentions="--scalar")
        self.assert_usage_error(*base, "--scalar", "fixed", "--dt", "1e-5", mentions="--dt")
        self.assert_usage_error("oscillator", "--t-end", "inf", mentions="--t-end")
        self.assert_usage_error("oscillator", "--t-end", "-3", mentions="--t-end")
        self.assert_usage_error("oscillator", mentions="--t-end")  # required
        self.assert_usage_error(*base, "--no-such-flag", mentions="no-such-flag")
        self.assert_usage_error(*base, "--csv", "/nonexistent-dir/x.csv", mentions="/nonexistent-dir/x.csv")

    def test_no_subcommand(self):
        r = run()
        self.assertEqual(r.returncode, 2)


if __name__ == "__main__":
    unittest.main(verbosity=2)
