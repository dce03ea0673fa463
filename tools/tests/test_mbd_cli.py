#!/usr/bin/env python3
"""`cvtplant mbd` and `cvtplant mbd figures` as a user drives them (docs/cli.md#mbd)."""
import csv
import json
import os
import pty
import select
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"

SHORT = ["--t-end", "0.05"]
JSON_KEYS = ["t_end_s", "wall_s", "steps", "rhs_evals", "jac_evals", "energy_residual_rel", "omega1_end_rad_s", "omega2_end_rad_s",
             "ratio_mean", "F_ax1_mean_N", "F_ax1_ripple_N", "links", "method"]


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


class Run(unittest.TestCase):
    def test_json_summary_has_the_listed_keys(self):
        r = run("mbd", "--case", "1", *SHORT, "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "")
        j = json.loads(r.stdout)
        for k in JSON_KEYS:
            self.assertIn(k, j)
        self.assertEqual(j["status"], "ok")
        self.assertEqual(j["method"], "bdf")
        self.assertEqual(j["links"], 44)
        self.assertEqual(j["t_end_s"], 0.05)
        self.assertLessEqual(j["energy_residual_rel"], 1e-6)
        self.assertGreater(j["steps"], 0)
        self.assertGreater(j["omega1_end_rad_s"], 0)

    def test_json_params_are_the_runs_inputs(self):
        # Every input of the model as a row (the reference's field list): the
        # options given show up there, a nested field carries its group.
        r = run("mbd", "--case", "2", *SHORT, "--links", "40", "--tau-in", "0:20,0.02:80", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = {p["name"]: p for p in json.loads(r.stdout)["params"]}
        self.assertEqual(len(rows), len(json.loads(r.stdout)["params"]))  # one row a field
        self.assertEqual(rows["links"]["value"], 40)
        self.assertEqual(rows["tau_in_Nm"]["value"], [[0.0, 20.0], [0.02, 80.0]])
        self.assertEqual(rows["tau_in_Nm"]["unit"], "N.m")
        self.assertEqual(rows["friction.law"]["value"], "case2")
        self.assertEqual(rows["sheaves"]["value"], "fixed")
        self.assertEqual(rows["road.T0_Nm"], {"name": "road.T0_Nm", "value": 0.0, "unit": "N.m"})
        self.assertFalse(rows["start.active"]["value"])

    def test_csv_rows_and_columns(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "out.csv")
            links = os.path.join(d, "links.csv")
            r = run("mbd", "--case", "2", *SHORT, "--sample", "0.01", "--csv", path, "--links-csv", links,
                    "--links-every", "0.025")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(path) as f:
                rows = list(csv.DictReader(f))
            with open(links) as f:
                lrows = list(csv.DictReader(f))
        self.assertEqual(len(rows), 6)  # t = 0, 0.01, ..., 0.05
        for col in ("t_s", "omega1_rad_s", "omega2_rad_s", "ratio", "F_ax1_N", "F_ax2_N", "T_transmitted_Nm",
                    "slip1_m_s", "slip2_m_s", "T_tight_N", "T_slack_N", "wrap_links1", "wrap_links2", "W_in_J",
                    "W_load_J", "D_friction_J", "D_damping_J", "E_kin_J", "E_el_J", "ledger_residual_rel"):
            self.assertIn(col, rows[0])
        self.assertAlmostEqual(float(rows[-1]["t_s"]), 0.05)
        self.assertEqual(len(lrows), 3 * 44)  # t = 0, 0.025, 0.05
        self.assertEqual({int(r["pulley"]) for r in lrows}, {-1, 0, 1})
        # Text summary when not --json.
        self.assertIn("Multibody chain CVT", r.stdout)

    def test_clamped_sheaves_carry_the_clamping_force(self):
        r = run("mbd", "--case", "1", "--t-end", "0.1", "--sheaves", "clamped", "--clamp-N", "3300", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertAlmostEqual(j["F_ax1_mean_N"] / 3300.0, 1.0, delta=0.02)
        self.assertAlmostEqual(j["F_ax2_mean_N"] / 3636.8, 1.0, delta=0.02)  # static thrust ratio theta2/theta1

    def test_production_set(self):
        # docs/mbd-production.md: 53 links, clamped sheaves by default, its own friction.
        r = run("mbd", "--set", "production", "--clamp-N", "12500", "--clamp2-N", "12500", "--tau-in", "0",
                "--tau-load", "0", "--t-end", "0.002", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["set"], "production")
        self.assertEqual(j["links"], 53)
        self.assertEqual(j["sheaves"], "clamped")
        self.assertIsNone(j["case"])
        self.assertAlmostEqual(j["F_ax2_mean_N"] / 12500.0, 1.0, delta=0.05)

    def test_rk4_option(self):
        r = run("mbd", "--case", "1", "--t-end", "0.005", "--method", "rk4", "--dt", "1e-6", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["method"], "rk4")
        self.assertEqual(j["steps"], 5000)
        self.assertEqual(j["rhs_evals"], 20000)


class BadInput(unittest.TestCase):
    """Each kind of bad input: one line on stderr, exit 2, nothing on stdout, before any work."""

    def bad(self, *args, needle):
        r = run("mbd", *args)
        self.assertEqual(r.returncode, 2, (args, r.stderr))
        self.assertEqual(r.stdout, "")
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertTrue(lines[0].startswith("cvtplant mbd"), lines[0])
        self.assertIn(needle, lines[0])

    def test_case(self):
        self.bad("--t-end", "1", needle="--case")
        self.bad("--case", "3", needle="--case")

    def test_parameter_set(self):
        self.bad("--set", "stock", needle="--set")
        self.bad("--set", "production", "--case", "1", "--clamp-N", "12500", needle="--case")
        self.bad("--set", "production", "--links", "44", "--clamp-N", "12500", needle="--links")
        self.bad("--set", "production", needle="--clamp-N")
        self.bad("figures", "--out-dir", "/tmp", "--set", "production", "--clamp-N", "12500", needle="--set seed")

    def test_numbers_not_numbers_or_out_of_range(self):
        self.bad("--case", "1", "--t-end", "abc", needle="--t-end")
        self.bad("--case", "1", "--t-end", "nan", needle="--t-end")
        self.bad("--case", "1", "--t-end", "0", needle="--t-end")
        self.bad("--case", "1", "--t-end", "1e9", needle="--t-end")
        self.bad("--case", "1", "--rtol", "0.1", needle="--rtol")
        self.bad("--case", "1", "--links", "35", needle="--links")
        self.bad("--case", "1", "--links", "54", needle="--links")
        self.bad("--case", "1", "--t-end", "1", "--sample", "2", needle="--sample")
        self.bad("--case", "1", "--tau-in", "5000", needle="--tau-in")
        self.bad("--case", "1", "--ledger-tol", "0", needle="--ledger-tol")
        self.bad("--case", "1", "--method", "rk4", "--dt", "1e-3", needle="--dt")

    def test_options_for_the_other_method_or_mode(self):
        self.bad("--case", "1", "--dt", "1e-6", needle="--dt")
        self.bad("--case", "1", "--method", "rk4", "--rtol", "1e-6", needle="--rtol")
        self.bad("--case", "1", "--method", "euler", needle="--method")
        self.bad("--case", "1", "--linear-solver", "lapack", needle="--linear-solver")
        self.bad("--case", "1", "--method", "rk4", "--linear-solver", "klu", needle="--linear-solver")
        self.bad("--case", "1", "--sheaves", "clamped", needle="--clamp-N")
        self.bad("--case", "1", "--clamp-N", "3300", needle="--clamp-N")
        self.bad("--case", "1", "--sheaves", "floating", needle="--sheaves")

    def test_clamping_profiles(self):
        self.bad("--case", "1", "--sheaves", "clamped", "--clamp-N", "x", needle="--clamp-N")
        self.bad("--case", "1", "--sheaves", "clamped", "--clamp-N", "0:3000,0:4000", needle="times must increase")
        self.bad("--case", "1", "--sheaves", "clamped", "--clamp-N", "-1:3000", needle=">= 0")
        self.bad("--case", "1", "--sheaves", "clamped", "--clamp-N", "10", needle="--clamp-N")
        self.bad("--case", "1", "--sheaves", "clamped", "--clamp-N", "0:3000,1", needle="t:value")

    def bad_values(self, option, needles):
        """Seed case 1 with `option` at each value of `needles`: refused, naming the value's needle."""
        for value, needle in needles.items():
            self.bad("--case", "1", option, value, needle=needle)

    def test_torque_profiles(self):
        self.bad_values("--tau-in", {"0:20,0.5:x": "--tau-in", "0:20,0:120": "times must increase", "-0.5:20": ">= 0"})
        self.bad_values("--tau-load", {"0:50,1:1e4": "--tau-load", "0:50,1:nan": "--tau-load"})

    def test_road_load(self):
        self.bad_values("--road-load", {"10,0.05": "T0,cv,ca", "10,0.05,0.002,1,2": "T0,cv,ca",
                                        "-1,0.05,0.002": "--road-load T0", "10,nan,0.002": "--road-load",
                                        "10,0.05,0.002,0": "w_eps", "10,0.05,x": "--road-load"})

    def test_start_at_speed(self):
        self.bad_values("--omega0", {"150": "expected 2", "150,0": "(0, 1000]", "-150,100": "(0, 1000]",
                                     "150,inf": "--omega0", "2000,100": "(0, 1000]"})

    def test_work_and_memory_caps(self):
        self.bad("--case", "1", "--method", "rk4", "--t-end", "10", "--max-steps", "1000", needle="--max-steps")
        self.bad("--case", "1", "--t-end", "10", "--sample", "1e-6", needle="--max-rows")
        self.bad("--case", "1", "--max-steps", "0", needle="--max-steps")

    def test_outputs(self):
        self.bad("--case", "1", *SHORT, "--csv", "/nonexistent-dir/x.csv", needle="cannot write")
        self.bad("--case", "1", *SHORT, "--csv", "-", "--json", needle="--csv")
        self.bad("--case", "1", *SHORT, "--links-every", "0.01", needle="--links-csv")
        self.bad("--case", "1", "--no-such-option", needle="no-such-option")

    def test_figures(self):
        with tempfile.TemporaryDirectory() as d:
            self.bad("figures", "--out-dir", d, "--t-end", "0.1", "--picture-t", "1", needle="--picture-t")
            f = os.path.join(d, "file")
            open(f, "w").close()
            self.bad("figures", "--out-dir", f, "--t-end", "0.1", needle="--out-dir")
            self.bad("figures", "--t-end", "0.1", needle="--out-dir")


class Failures(unittest.TestCase):
    def test_a_run_that_goes_bad_exits_1_naming_time_and_quantity(self):
        r = run("mbd", "--case", "1", "--t-end", "0.1", "--ledger-tol", "1e-12", "--json")
        self.assertEqual(r.returncode, 1)
        self.assertRegex(r.stderr.strip(), r"^cvtplant mbd: failed: at t = [0-9.e-]+ s: energy ledger residual")
        j = json.loads(r.stdout)
        self.assertEqual(j["status"], "failed")
        self.assertIn("energy ledger", j["failure"]["quantity"])
        # A cap below the run's estimated work is refused before the run
        # (docs/cli.md#caps); one at the estimate that the run needs more
        # than (184 steps over 2 ms, estimated at 100) stops it.
        r = run("mbd", "--case", "1", "--t-end", "0.1", "--max-steps", "30")
        self.assertEqual(r.returncode, 2)
        self.assertIn("needs an estimated 5000 integrator steps", r.stderr)
        r = run("mbd", "--case", "1", "--t-end", "0.002", "--max-steps", "100")
        self.assertEqual(r.returncode, 1)
        self.assertIn("step cap of 100 steps", r.stderr)


class Progress(unittest.TestCase):
    def test_piped_output_carries_data_only(self):
        r = run("mbd", "--case", "1", "--t-end", "0.2", "--json")
        self.assertEqual(r.returncode, 0)
        self.assertEqual(r.stderr, "")
        json.loads(r.stdout)

    def test_terminal_shows_a_bar_and_clears_it(self):
        # stderr on a pseudo-terminal, stdout on a pipe.
        master, slave = pty.openpty()
        # CI runners may set CI, which turns the bar off by design (docs/cli.md#progress).
        env = {k: v for k, v in os.environ.items() if k != "CI"}
        p = subprocess.Popen([CLI, "mbd", "--case", "1", "--t-end", "1", "--json"], stdout=subprocess.PIPE,
                             stderr=slave, text=True, env=env)
        os.close(slave)
        seen = b""
        while True:
            ready, _, _ = select.select([master], [], [], 60)
            if not ready:
                break
            try:
                chunk = os.read(master, 4096)
            except OSError:
                break
            if not chunk:
                break
            seen += chunk
        out, _ = p.communicate(timeout=600)
        os.close(master)
        self.assertEqual(p.returncode, 0)
        json.loads(out)  # stdout stays clean
        text = seen.decode()
        self.assertIn("mbd case 1 (Coulomb) [", text)
        self.assertRegex(text, r"\d+%  t [0-9.e-]+/1 s  wall [0-9.]+ s  left ")
        self.assertTrue(text.endswith("\r\x1b[K"), repr(text[-40:]))


class Figures(unittest.TestCase):
    def test_figures_are_png_files(self):
        with tempfile.TemporaryDirectory() as d:
            r = run("mbd", "figures", "--out-dir", d, "--t-end", "0.1", "--picture-t", "0.05", "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            self.assertEqual([os.path.basename(p) for p in j["png"]],
                             ["fig13_pulley_speeds.png", "fig14_driver_axial_force.png", "chain_case1.png",
                              "chain_case2.png"])
            self.assertAlmostEqual(j["picture_t_s"], 0.05)
            for p in j["png"]:
                with open(p, "rb") as f:
                    self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
                self.assertGreater(os.path.getsize(p), 10000)


if __name__ == "__main__":
    unittest.main()
