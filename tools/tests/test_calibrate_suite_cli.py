#!/usr/bin/env python3
"""`cvtplant calibrate --suite ci` (docs/validation.md#calibration-suite): the fit on
the ci suite's two manoeuvres with the reference runs `validate --suite`
makes, through the same cache (a second run and validate read them back),
the same result twice, and bad suite options refused before any run.
About 4 s of CPU (1.4 s of it the reference's two 60 ms runs)."""
import os
import subprocess
import sys
import tempfile
import unittest

from cli_checks import assert_usage_error, quiet_json

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


class Suite(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.d = cls.tmp.name
        cls.out = os.path.join(cls.d, "fitted.toml")
        args = ["calibrate", "--suite", "ci", "--fit", "c1_Ns_m", "--max-evals", "6", "--out-dir", cls.d, "--json"]
        cls.first = run(*args, "--out", cls.out)
        cls.second = run(*args)
        cls.validate = run("validate", "--suite", "ci", "--no-maps", "--uncertainty", "none", "--out-dir", cls.d,
                           "--json")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_fit_on_the_suite(self):
        j = quiet_json(self, self.first)
        self.assertEqual(j["suite"], "ci")
        self.assertEqual(j["set"], "production")
        self.assertEqual(j["scenes"], ["hold-150-1.5-60", "step-up-150-1.5-0.1"])
        self.assertGreater(j["reference_cpu_s"], 0)
        self.assertLessEqual(j["plant_evaluations"], 6)
        self.assertLessEqual(j["cost_end"], j["cost_start"])
        self.assertEqual([c["held_out"] for c in j["cases"]], [False, False])
        for c in j["cases"]:
            self.assertEqual(sorted(k for k in c if k not in ("scene", "held_out")),
                             ["F_ax1", "omega1", "omega2", "ratio", "torque_driver"])
        # 61 samples (60 ms every 1 ms, t = 0 included) of five quantities in each run.
        self.assertEqual(j["residuals"], 2 * 5 * 61)
        with open(self.out) as f:
            text = f.read()
        self.assertIn("cvtplant calibrate --suite ci --scene ratio-control --fit c1_Ns_m", text)
        self.assertIn("--set production", text)

    def test_the_cache_is_shared_with_validate(self):
        a, b = quiet_json(self, self.first), quiet_json(self, self.second)
        self.assertEqual(b["reference_cpu_s"], 0)
        # The same result from the cached runs, to the last digit.
        self.assertEqual(a["parameters"], b["parameters"])
        self.assertEqual(a["cost_end"], b["cost_end"])
        v = quiet_json(self, self.validate)
        self.assertEqual(v["from_cache"], v["reference_runs"])
        self.assertEqual(v["reference_runs"], 2)

    def test_bad_suite_options(self):
        def check(args, needle):
            assert_usage_error(self, run(*args, "--out-dir", self.d), needle, args)
        check(["calibrate", "--suite", "nope"], "unknown suite 'nope'")
        check(["calibrate", "--suite", "ci", "--measured", "x.csv"], "one or the other")
        check(["calibrate", "--suite", "ci", "--max-t-end", "0.01"], "--max-t-end")
        check(["calibrate", "--suite", "ci", "--t-end", "0.1"], "--t-end does not apply")
        check(["calibrate", "--max-t-end", "10"], "no --suite")
        check(["calibrate", "--suite", "ci", "--scene", "seed-case1"], "wedging")
        check(["calibrate", "--suite", "ci", "--scene", "ratio-control,clamp-step"], "one scene")


if __name__ == "__main__":
    unittest.main()
