#!/usr/bin/env python3
"""Every subcommand's --json follows one naming convention (docs/cli.md#json-output).

Each subcommand runs on a tiny input; every numeric leaf of its JSON must name
its unit by a suffix, or be a documented dimensionless name, or sit under a key
that carries the unit. Quantities shared between commands use the shared name.
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"

# SI unit suffixes (docs/cli.md#json-output). `_Nm` is newton-metre, `_N_m`
# newton per metre, `_Ns_m` newton-second per metre; `_iter` counts map iterations.
UNIT_SUFFIXES = ("_s", "_ns", "_rad_s", "_rad", "_m", "_m_s", "_N", "_Nm", "_N_m", "_Ns_m", "_kg", "_J", "_W", "_Hz",
                 "_iter")
# Dimensionless by a suffix or prefix that says so.
DIMENSIONLESS_SUFFIXES = ("_rel", "_count", "_efolds")
DIMENSIONLESS_PREFIXES = ("ratio", "rel_")  # rel_rms: relative RMS error
# Dimensionless names: counts, indices, tolerances and ratios.
DIMENSIONLESS = {
    "steps", "frames", "substeps", "samples", "links", "sheaves", "states", "case", "iterations", "residuals",
    "creep_strain", "rhs_evals", "jac_evals", "linear_setups", "newton_iters", "error_test_fails", "newton_fails", "jacobian_nnz",
    "plant_evaluations", "plant_faults", "status", "points", "rtol", "slip", "max_abs_slip", "ci_level",
    "symmetry_zero_exponents", "zero_index", "wrap_links_end", "cost_start", "cost_end", "rms_residual_start",
    "rms_residual_end", "ref_substeps", "atol", "rejected", "rhs", "jacobians", "factorizations", "solves",
}
# Lyapunov rates are in the unit the enclosing object states in `exponent_unit`;
# the state (`x0`, `x_final`, `params`) is the scene's own.
EXPONENT_KEYS = {
    "exponents", "ci", "batch_sd", "sum", "mean_trace_jacobian", "mean_log_abs_det_jacobian", "sum_minus_trace",
    "lambda1_extrapolated", "lambda1_extrapolated_ci", "flow_direction_rate", "exponents_dt_half", "difference",
    "max_abs_difference", "final_speed", "x0", "x_final", "params",
}
# Series analysis (analyze ami ... classify) works on sample indices; its
# measures keep the names of the literature (docs/analysis.md).
SERIES_MEASURES = {
    "acf", "ami", "E1", "E2", "fraction", "fraction_rtol", "fraction_atol", "atol", "threshold", "amplitude_decay",
    "DET", "ENTR", "L", "LAM", "RR", "TT", "K", "K_q25", "K_q75", "eps", "lambda", "slope", "slope_se", "ci95", "r2",
    "window_spread", "divergence", "mean_neighbours", "worst_harmonic_error", "fundamental_cycles_per_sample",
    "peaks_cycles_per_sample", "tau", "m", "theiler", "bins", "tau_acf_zero", "tau_ami_first_minimum", "dimension",
    "k_begin", "k_end", "k_max", "Lmax", "Vmax", "lmin", "vmin", "n_c", "subsample",
}
# Keys of rows whose unit is named beside them (`unit`, or a `name` with a unit suffix).
ROW_VALUES = {"value", "start", "sigma", "plant_ss", "reference_ss", "mean", "std", "peak_to_peak", "line_amplitude"}
# One name for one quantity: the names a command must not use, and the shared one.
NOT_SHARED = {"dt": "dt_s / frame_s", "t_end": "t_end_s", "t": "t_s", "t_transient": "t_transient_s",
              "t_renorm": "t_renorm_s", "t_warmup": "t_warmup_s", "sample_dt_s": "sample_s", "method": "integrator",
              "wall_time_s": "wall_s", "run_time_s": "wall_s"}


def has_unit(key):
    return (key.endswith(UNIT_SUFFIXES) or key.endswith(DIMENSIONLESS_SUFFIXES) or key.startswith(DIMENSIONLESS_PREFIXES)
            or "ns_per_" in key)  # a cost per frame or step: the unit leads


def offences(node, path="", parent="", siblings=None, exempt=frozenset()):
    """Yield (path, reason) for every numeric leaf that breaks the convention."""
    if isinstance(node, dict):
        if "exponent_unit" in node:
            exempt = exempt | EXPONENT_KEYS
        for k, v in node.items():
            # `method` is the ROM integrator only beside `scalar` (mbd and lle have methods of their own)
            if k in NOT_SHARED and (k != "method" or "scalar" in node):
                yield path + "." + k, "use the shared name " + NOT_SHARED[k]
            if k.endswith("_relative"):
                yield path + "." + k, "relative quantities end in _rel"
            # the members of an exempt object (a scene's `params`) are exempt too
            inner = exempt | set(v) if isinstance(v, dict) and k in exempt else exempt
            yield from offences(v, path + "." + k, k, node, inner)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from offences(v, "%s[%d]" % (path, i), parent, siblings, exempt)
    elif isinstance(node, (int, float)) and not isinstance(node, bool) or node is None:
        if node is None:
            return  # a value that does not exist (documented per command)
        key = parent
        if has_unit(key) or key in DIMENSIONLESS or key in exempt:
            return
        s = siblings or {}
        if key in ROW_VALUES and ("unit" in s or has_unit(str(s.get("name", "")))):
            return
        grand = path.rsplit(".", 2)
        # a value under a key that carries the unit: {"F_ax1_ripple_N": {"plant": ..}}
        if len(grand) >= 3 and has_unit(re.sub(r"\[\d+\]$", "", grand[-2])):
            return
        yield path, "no unit suffix and not a documented dimensionless name"


def run_json(*args):
    r = subprocess.run([CLI, *args, "--json"], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        raise AssertionError("%s: exit %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return json.loads(r.stdout)


class Schema(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        t = [0.01 * i for i in range(2000)]
        csv = os.path.join(cls.tmp.name, "series.csv")
        with open(csv, "w") as f:
            f.write("t,s\n")
            for ti in t:
                f.write("%r,%r\n" % (ti, math.sin(5 * ti) + 0.3 * math.sin(13 * ti)))
        cls.csv = csv

    def check(self, j, exempt=frozenset()):
        bad = list(offences(j, exempt=exempt))
        self.assertEqual(bad, [])
        return j

    def test_the_checker_catches_offences(self):
        # The rule itself: unit-less names, the old names and "_relative" are caught.
        bad = dict(offences({"speed": 1.0, "t_end": 2.0, "x_relative": 0.1, "dt": 1e-3, "ok_s": 1.0,
                             "slip": 0.2, "rows": [{"err_omega1": 0.1}], "q_N": {"plant": 1.0}}))
        self.assertIn(".speed", bad)
        self.assertIn(".rows[0].err_omega1", bad)
        self.assertIn(".t_end", bad)
        self.assertIn(".x_relative", bad)
        self.assertIn(".dt", bad)
        self.assertNotIn(".ok_s", bad)
        self.assertNotIn(".slip", bad)
        self.assertNotIn(".q_N.plant", bad)

    def test_scenes(self):
        for s in run_json("scenes"):
            self.check(s)
            self.assertIn("scene", s)
            self.assertIn("frame_s", s)
            self.assertIn("t_end_s", s)
            self.assertIn("integrator", s)

    def test_run(self):
        j = self.check(run_json("run", "--scene", "seed-case1", "--t-end", "0.05"))
        self.assertEqual(j["subcommand"], "run")
        self.assertEqual(j["frame_s"], 1e-3)
        self.assertEqual(j["t_end_s"], 0.05)
        for k in ("scene", "scalar", "integrator", "substeps", "wall_s"):
            self.assertIn(k, j)

    def test_run_adaptive(self):
        j = self.check(run_json("run", "--scene", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "scenes",
                                              "seed-case1-clamped.toml"), "--t-end", "0.05", "--solver", "adaptive"))
        self.assertEqual(j["frame_s"], 1e-3)
        self.assertEqual(j["integrator"], "rodas4")
        for k in ("rtol", "atol", "work", "wall_s"):
            self.assertIn(k, j)

    def test_rom_accuracy(self):
        j = self.check(run_json("rom-accuracy", "--scene", "seed-case1", "--t-end", "0.02"))
        self.assertEqual(j["subcommand"], "rom-accuracy")
        self.assertEqual(j["frame_s"], 1e-3)
        self.assertEqual(j["t_end_s"], 0.02)
        self.assertIn("integrator", j["rows"][0])
        self.assertIn("err_omega1_rel", j["rows"][0])

    def test_lyapunov_flow_and_map(self):
        j = self.check(run_json("lyapunov", "--scene", "lorenz", "--t-end", "2", "--t-transient", "1", "--dt-check"))
        self.assertEqual(j["exponent_unit"], "1/s")
        self.assertEqual(j["t_end_s"], 2.0)
        self.assertIn("t_s", j["convergence"][0])
        self.assertIn("dt_half_s", j["dt_check"])
        m = self.check(run_json("lyapunov", "--scene", "henon", "--t-end", "1000"))
        self.assertEqual(m["exponent_unit"], "1/iteration")
        self.assertEqual(m["t_end_iter"], 1000.0)

    def test_oscillator(self):
        j = self.check(run_json("oscillator", "--t-end", "0.1"))
        self.assertEqual(j["t_end_s"], 0.1)
        self.assertIn("x1_m", j["final_state"])
        self.assertIn("wall_s", j)

    def test_mbd(self):
        j = self.check(run_json("mbd", "--case", "1", "--t-end", "0.02"))
        self.assertEqual(j["t_end_s"], 0.02)
        self.assertIn("sample_s", j)
        self.assertIn("wall_s", j)

    def test_mbd_start_at_speed(self):
        # A slow start at speed (the spin-up and hold are fixed work, cheaper at low speed).
        j = self.check(run_json("mbd", "--case", "1", "--t-end", "0.01", "--omega0", "20,13.3", "--road-load",
                                "1,0.1,0", "--tau-in", "0:10,0.01:12"))
        self.assertIn("holding_torque_mean_Nm", j["start_at_speed"])

    def test_mbd_figures(self):
        out = os.path.join(self.tmp.name, "mf")
        j = self.check(run_json("mbd", "figures", "--out-dir", out, "--t-end", "0.02"))
        self.assertIn("wall_s", j["runs"][0])

    def test_validate_and_calibrate(self):
        out = os.path.join(self.tmp.name, "v")
        j = self.check(run_json("validate", "--scene", "seed-case1", "--t-end", "0.2", "--no-figures", "--out-dir", out))
        self.assertEqual(j["scenes"][0]["t_end_s"], 0.2)
        self.check(run_json("calibrate", "--scene", "seed-case1", "--t-end", "0.2", "--out-dir", out))

    def test_analyze_series(self):
        for sub in ("ami", "fnn", "cao", "lle", "rqa", "test01", "classify"):
            self.check(run_json("analyze", sub, "--csv", self.csv, "--column", "s"), exempt=SERIES_MEASURES)
        png = os.path.join(self.tmp.name, "rp.png")
        self.check(run_json("analyze", "recurrence", "--csv", self.csv, "--column", "s", "--png", png),
                   exempt=SERIES_MEASURES)

    def test_analyze_ripple(self):
        j = self.check(run_json("analyze", "ripple", "--csv", self.csv, "--column", "s", "--windows", "0:10,10:20",
                                "--min-hz", "0.5", "--unit", "m"))
        self.assertEqual(j["windows"][0]["unit"], "m")
        self.assertEqual(j["windows"][1]["t_begin_s"], 10.0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
