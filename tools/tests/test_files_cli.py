#!/usr/bin/env python3
"""Nothing lost, nothing made up (docs/cli.md#files, #names, #interruption, #caps, #nulls).

Each class of the command line's file and output rules, as a user meets it:
outputs never over an input or each other (through links too), names that
become file names follow one rule, the reference cache is checked, an
interrupted run ends on a whole row with its summary and exit 128 + signal,
runs above their estimated work are refused before they start, what was not
computed is null (JSON) or n/a (text), bad input is refused with the flag
and the value as given, and CSV inputs are read once, whatever their bytes.

usage: test_files_cli.py CVTPLANT [CVTPLANT_SIL] [CVTPLANT_BRIDGE]
Cost: about 25 s on the host-release build (reference runs of 10 to 20 ms,
interrupted runs stopped after a second).
"""
import csv
import io
import json
import os
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
SIL = sys.argv.pop(1) if len(sys.argv) > 1 else ""
BRIDGE = sys.argv.pop(1) if len(sys.argv) > 1 else ""
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")


def run(*args, prog=None, **kw):
    return subprocess.run([prog or CLI, *args], capture_output=True, text=True, timeout=600, **kw)


def write(path, text, mode="w"):
    with open(path, mode) as f:
        f.write(text)
    return path


def read(path, mode="r"):
    with open(path, mode) as f:
        return f.read()


class Case(unittest.TestCase):
    def refused(self, args, needle, sub=None, prog=None, prefix=None):
        """Exit 2, nothing on stdout, one stderr line naming the problem."""
        r = run(*args, prog=prog)
        self.assertEqual(r.returncode, 2, (args, r.stdout, r.stderr))
        self.assertEqual(r.stdout, "", args)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        if prefix is None:
            prefix = f"cvtplant {sub or args[0]}: error: "
        self.assertTrue(lines[0].startswith(prefix), lines[0])
        self.assertIn(needle, lines[0])
        return lines[0]


class OutputsNeverOverInputs(Case):
    """Class 1: every output is compared, by the file it resolves to, with every input and output."""

    def test_calibrate_out_over_start_scene_or_header(self):
        with tempfile.TemporaryDirectory() as d:
            start = write(os.path.join(d, "P.toml"), "[params]\nk1_N_m = 2500.0\n")
            os.symlink(start, os.path.join(d, "L.toml"))
            scene = write(os.path.join(d, "s.toml"), 'name = "s"\nbase = "seed-case1"\n')
            before = read(start)
            for out, needle in ((start, "is the input of --start"), (os.path.join(d, "L.toml"), "is the input of --start"),
                                (scene, "is the input of --scene")):
                self.refused(["calibrate", "--scene", scene, "--start", start, "--out", out, "--out-dir", d], needle)
            self.refused(["calibrate", "--scene", "seed-case1", "--out", os.path.join(d, "x.toml"), "--header",
                          os.path.join(d, "x.toml"), "--out-dir", d], "--header: ")
            self.assertEqual(read(start), before)
            self.assertFalse(os.path.exists(os.path.join(d, "x.toml")))

    def test_validate_never_writes_over_a_scene_or_params_file(self):
        with tempfile.TemporaryDirectory() as d:
            # A scene file whose name is the comparison CSV's.
            scene = write(os.path.join(d, "v.csv"), 'name = "v"\nbase = "seed-case1"\n')
            self.refused(["validate", "--scene", scene, "--out-dir", d, "--no-figures"], "is the input of --scene")
            self.assertIn("base", read(scene))
            params = write(os.path.join(d, "seed-case1.png"), "[params]\nk1_N_m = 2500.0\n")
            self.refused(["validate", "--scene", "seed-case1", "--params", params, "--out-dir", d],
                         "is the input of --params")
            self.assertIn("k1_N_m", read(params))

    def test_two_scenes_of_one_name_in_scene_dir(self):
        with tempfile.TemporaryDirectory() as d:
            dir_ = os.path.join(d, "scenes")
            os.mkdir(dir_)
            write(os.path.join(dir_, "a.toml"), 'name = "twin"\nbase = "seed-case1"\n')
            write(os.path.join(dir_, "b.toml"), 'name = "twin"\nbase = "seed-case2"\n')
            line = self.refused(["validate", "--scene-dir", dir_, "--out-dir", os.path.join(d, "out"), "--t-end",
                                 "0.01"], "one would overwrite the other")
            self.assertIn("a.toml", line)
            self.assertIn("b.toml", line)
            self.assertFalse(os.path.exists(os.path.join(d, "out")))

    def test_mbd_two_tables_in_one_file(self):
        with tempfile.TemporaryDirectory() as d:
            f = os.path.join(d, "F.csv")
            self.refused(["mbd", "--case", "1", "--t-end", "0.01", "--csv", f, "--links-csv", f],
                         "--links-csv: ")
            os.symlink(f, os.path.join(d, "link.csv"))
            self.refused(["mbd", "--case", "1", "--t-end", "0.01", "--csv", f, "--links-csv",
                          os.path.join(d, "link.csv")], "also the output of --csv")
            self.refused(["mbd", "--case", "1", "--t-end", "0.01", "--csv", "-", "--links-csv", "-"],
                         "stdout is already the output of --csv")
            self.assertFalse(os.path.exists(f))

    def test_run_and_oscillator_outputs(self):
        with tempfile.TemporaryDirectory() as d:
            scene = write(os.path.join(d, "s.toml"), 'name = "s"\nbase = "seed-case1"\n')
            os.link(scene, os.path.join(d, "hard.toml"))
            self.refused(["run", "--scene", scene, "--csv", os.path.join(d, "hard.toml")], "is the input of --scene")
            self.assertIn("base", read(scene))

    def test_analyze_outputs_over_inputs(self):
        with tempfile.TemporaryDirectory() as d:
            series = write(os.path.join(d, "series.dat"), "t,x\n" + "".join(f"{i},{i % 7}\n" for i in range(200)))
            self.refused(["analyze", "figures", "--csv", series, "--column", "x", "--out-dir", d], "--csv: ",
                         sub="analyze figures")
            self.assertTrue(read(series).startswith("t,x\n"))
            scene = write(os.path.join(d, "summary.json"), 'name = "s"\nbase = "seed-case1"\n')
            self.refused(["analyze", "seed-section4", "--scene", scene, "--out-dir", d, "--t-end", "3"],
                         "is the input of --scene", sub="analyze seed-section4")

    @unittest.skipUnless(SIL and os.path.exists(SIL), "cvtplant-sil not built")
    def test_sil_junit_over_a_trace(self):
        with tempfile.TemporaryDirectory() as d:
            r = run("run", "--loopback", "--scenario", "tip-in", "--out", d, "--junit",
                    os.path.join(d, "sil-tip-in.csv"), prog=SIL)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn("--junit: ", r.stderr)
            self.assertIn("also the output of --out (scenario tip-in)", r.stderr)
            self.assertEqual(os.listdir(d), [])
            r = run("run", "--loopback", "--scenario", "tip-in", "--out", d, "--junit", "", prog=SIL)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn("--junit: empty file name", r.stderr)

    @unittest.skipUnless(BRIDGE and os.path.exists(BRIDGE), "cvtplant-bridge not built")
    def test_bridge_log_and_summary(self):
        with tempfile.TemporaryDirectory() as d:
            f = os.path.join(d, "x")
            r = run("--iface", "no-such-iface", "--log", f, "--summary", f, prog=BRIDGE)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn("--summary: ", r.stderr)
            self.assertIn("also the output of --log", r.stderr)
            self.assertFalse(os.path.exists(f))


class Names(Case):
    """Class 2: one rule for a scene's name and for paths that reach files (docs/cli.md#names)."""

    def test_scene_names_that_would_escape_or_break_lines(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            for name, needle in (("../escaped", "starts with"), ("", "empty name"), ("two\\nlines", "control"),
                                 ("a/b", "holds '/'"), (".hidden", "starts with"), ("a b", "a space")):
                scene = write(os.path.join(d, "s.toml"), f'name = "{name}"\nbase = "seed-case1"\n')
                for args in (["run", "--scene", scene, "--t-end", "0.01"],
                             ["validate", "--scene", scene, "--out-dir", out, "--t-end", "0.01"]):
                    line = self.refused(args, needle)
                    self.assertIn("s.toml:1: name: ", line)
            self.assertEqual(sorted(os.listdir(d)), ["s.toml"])

    def test_a_newline_in_a_path_never_reaches_a_generated_file(self):
        with tempfile.TemporaryDirectory() as d:
            start = os.path.join(d, "p\nk1_N_m = 5.0\n#")
            write(start, "[params]\nk1_N_m = 2500.0\n")
            self.refused(["calibrate", "--scene", "seed-case1", "--start", start, "--out", os.path.join(d, "o.toml"),
                          "--out-dir", d], "holds a control character")
            self.assertFalse(os.path.exists(os.path.join(d, "o.toml")))

    def test_header_function_must_compile(self):
        with tempfile.TemporaryDirectory() as d:
            for bad in ("class", "int", "__x", "a-b"):
                self.refused(["calibrate", "--function", bad, "--header", os.path.join(d, "h.hpp"), "--out-dir", d],
                             "--function: ")
            self.assertFalse(os.path.exists(os.path.join(d, "h.hpp")))


def validate_json(*args):
    r = run("validate", *args, "--json")
    return r, (json.loads(r.stdout) if r.returncode == 0 else None)


class ReferenceCache(Case):
    """Class 3: a cache entry is checked; a bad one is named and run again (docs/validation.md#cache)."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.out = cls.tmp.name
        cls.args = ["--scene", "seed-case1", "--t-end", "0.02", "--no-figures", "--out-dir", cls.out]
        r, cls.first = validate_json(*cls.args)
        assert r.returncode == 0, r.stderr
        cache = os.path.join(cls.out, "reference-cache")
        (cls.csv,) = [os.path.join(cache, f) for f in os.listdir(cache) if f.endswith(".csv")]

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def damaged_run(self, change):
        """Damages the entry's CSV with change(text) -> text; the next run names it and reruns."""
        text = read(self.csv)
        write(self.csv, change(text))
        r, j = validate_json(*self.args)
        self.assertEqual(r.returncode, 0, r.stderr)
        s = j["scenes"][0]
        self.assertFalse(s["reference"]["from_cache"])
        self.assertIn(os.path.basename(self.csv), s["reference"]["cache_problem"])
        self.assertIn("note: a cache entry failed its checks", r.stderr)
        self.assertEqual(s["compared_s"], 0.02)
        self.assertEqual(s["errors"], self.first["scenes"][0]["errors"])
        # The new entry is whole: the next run is a hit.
        r, j = validate_json(*self.args)
        self.assertTrue(j["scenes"][0]["reference"]["from_cache"], r.stderr)
        self.assertIsNone(j["scenes"][0]["reference"]["cache_problem"])
        return s["reference"]["cache_problem"]

    def test_truncated_rows(self):
        lines = lambda t: t.splitlines(keepends=True)
        self.assertIn("checksum", self.damaged_run(lambda t: "".join(lines(t)[:-5])))

    def test_bad_cells(self):
        def cell(value):
            def change(t):
                rows = t.splitlines(keepends=True)
                cells = rows[4].split(",")
                cells[1] = value
                rows[4] = ",".join(cells)
                return "".join(rows)
            return change
        for v in ("abc", "nan", "1e308", "1,2"):
            self.damaged_run(cell(v))

    def test_a_hit_reports_the_stored_run_and_no_time_spent(self):
        r, j = validate_json(*self.args)
        ref = j["scenes"][0]["reference"]
        self.assertTrue(ref["from_cache"])
        self.assertIsNone(ref["cpu_s"])
        self.assertIsNone(ref["wall_s"])
        self.assertGreater(ref["steps"], 0)

    def test_calibrate_on_a_damaged_cache_fits_the_whole_run(self):
        args = ["--scene", "seed-case1", "--t-end", "0.02", "--fit", "k1_N_m", "--every", "1", "--max-evals", "5",
                "--out-dir", self.out, "--json"]
        r = run("calibrate", *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        whole = json.loads(r.stdout)["residuals"]
        write(self.csv, "".join(read(self.csv).splitlines(keepends=True)[:-8]))
        r = run("calibrate", *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.loads(r.stdout)["residuals"], whole)
        self.assertIn("note: a cache entry failed its checks", r.stderr)
        self.assertLessEqual(json.loads(r.stdout)["plant_evaluations"], 5)

    def test_two_runs_creating_one_new_out_dir(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "a", "b", "c")
            args = [CLI, "validate", "--scene", "seed-case1", "--t-end", "0.01", "--no-figures", "--out-dir", out,
                    "--json"]
            procs = [subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                     for _ in range(2)]
            outs = [p.communicate(timeout=300) for p in procs]
            for p, (o, e) in zip(procs, outs):
                self.assertEqual(p.returncode, 0, e)
            a, b = (json.loads(o)["scenes"][0]["errors"] for o, _ in outs)
            self.assertEqual(a, b)
            cache = os.path.join(out, "reference-cache")
            self.assertEqual(sorted(f.split(".")[-1] for f in os.listdir(cache)), ["csv", "key"])
            r, j = validate_json("--scene", "seed-case1", "--t-end", "0.01", "--no-figures", "--out-dir", out)
            self.assertTrue(j["scenes"][0]["reference"]["from_cache"])


def start(args, **kw):
    return subprocess.Popen([CLI, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, **kw)


def wait_for(predicate, timeout=60):
    end = time.time() + timeout
    while time.time() < end:
        if predicate():
            return True
        time.sleep(0.05)
    return False


class Interruption(Case):
    """Class 4: SIGINT/SIGTERM end a run on a whole row, with its summary, exit 130/143."""

    def check_rows(self, text):
        rows = list(csv.reader(io.StringIO(text)))
        self.assertGreater(len(rows), 2)
        for row in rows[1:]:
            self.assertEqual(len(row), len(rows[0]), row)
        for cell in rows[-1]:
            if cell not in ("none",):
                float(cell)  # every cell of the last row reads back
        return rows

    def interrupted_file_run(self, args, out, sig, min_bytes=20000):
        p = start(args)
        self.assertTrue(wait_for(lambda: os.path.exists(out) and os.path.getsize(out) > min_bytes), "no rows")
        p.send_signal(sig)
        stdout, stderr = p.communicate(timeout=120)
        self.assertEqual(p.returncode, 128 + sig, stderr)
        lines = stderr.decode().strip().splitlines()
        self.assertEqual(len(lines), 1, stderr)
        self.assertRegex(lines[0], r"interrupted at t = [0-9.e+-]+ s \((SIGINT|SIGTERM)\)$")
        return stdout.decode(), self.check_rows(read(out))

    def test_run_csv_sigint_and_sigterm(self):
        with tempfile.TemporaryDirectory() as d:
            for sig in (signal.SIGINT, signal.SIGTERM):
                out = os.path.join(d, f"r{int(sig)}.csv")
                stdout, rows = self.interrupted_file_run(
                    ["run", "--scene", "seed-case1", "--t-end", "40", "--substeps", "100", "--csv", out, "--json"],
                    out, sig)
                j = json.loads(stdout)
                self.assertEqual(j["status"], "interrupted")
                # The last row is the summary's final frame.
                self.assertEqual(float(rows[-1][0]), j["t_end_s"])
                self.assertEqual(len(rows) - 2, j["frames"])
                self.assertLess(j["t_end_s"], 40)

    def test_mbd_csv_and_csv_to_stdout(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "m.csv")
            stdout, rows = self.interrupted_file_run(
                ["mbd", "--case", "1", "--t-end", "20", "--sample", "1e-4", "--csv", out, "--json"], out,
                signal.SIGINT, min_bytes=5000)
            j = json.loads(stdout)
            self.assertEqual(j["status"], "interrupted")
            self.assertAlmostEqual(float(rows[-1][0]), j["t_reached_s"], places=7)
            # To stdout: the CSV is the pipe's content, the summary goes to stderr.
            p = start(["mbd", "--case", "1", "--t-end", "20", "--sample", "1e-4", "--csv", "-"])
            chunks = []
            got = threading.Event()

            def pump():
                for line in iter(p.stdout.readline, b""):
                    chunks.append(line)
                    if len(chunks) > 30:
                        got.set()
            t = threading.Thread(target=pump)
            t.start()
            self.assertTrue(got.wait(120))
            p.send_signal(signal.SIGTERM)
            t.join(120)
            stderr = p.stderr.read().decode()
            p.wait(60)
            self.assertEqual(p.returncode, 143, stderr)
            self.assertIn("interrupted at t = ", stderr)
            self.check_rows(b"".join(chunks).decode())

    def test_oscillator_csv(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "o.csv")
            stdout, rows = self.interrupted_file_run(
                ["oscillator", "--t-end", "5000", "--dt", "1e-5", "--csv", out, "--json"], out, signal.SIGINT)
            j = json.loads(stdout)
            self.assertEqual(j["status"], "interrupted")
            self.assertEqual(j["behaviour"], "interrupted")
            self.assertIsNone(j["settled"])

    def test_validate_keeps_no_partial_reference_and_reports_the_scenes_done(self):
        with tempfile.TemporaryDirectory() as d:
            p = start(["validate", "--scene", "seed-case1", "--t-end", "5", "--no-figures", "--out-dir", d, "--json"])
            time.sleep(1.5)
            p.send_signal(signal.SIGINT)
            stdout, stderr = p.communicate(timeout=120)
            self.assertEqual(p.returncode, 130, stderr)
            j = json.loads(stdout)
            self.assertEqual(j["status"], "interrupted")
            self.assertIn("interrupted at scene seed-case1's reference, t = ", stderr.decode())
            cache = os.path.join(d, "reference-cache")
            self.assertEqual([f for f in os.listdir(cache)], [])

    def test_calibrate_writes_no_parameter_file(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "p.toml")
            p = start(["calibrate", "--scene", "seed-case1", "--t-end", "5", "--out", out, "--out-dir", d, "--json"])
            time.sleep(1.5)
            p.send_signal(signal.SIGTERM)
            stdout, stderr = p.communicate(timeout=120)
            self.assertEqual(p.returncode, 143, stderr)
            j = json.loads(stdout)
            self.assertEqual(j, {"subcommand": "calibrate", "status": "interrupted",
                                 "interrupted_at": j["interrupted_at"]})
            self.assertFalse(os.path.exists(out))


class Caps(Case):
    """Class 5: physical bounds, and the estimated work refused before the run (docs/cli.md#caps)."""

    def test_road_load_bounds_are_one_range(self):
        self.refused(["mbd", "--case", "1", "--t-end", "0.02", "--road-load", "1000,100,10,1e-300"],
                     "--road-load w_eps: 1e-300 is outside [0.001, 1000] rad/s")
        self.refused(["mbd", "--case", "1", "--t-end", "0.02", "--road-load", "1000,100,10,1e-12"], "1e-12")
        with tempfile.TemporaryDirectory() as d:
            scene = write(os.path.join(d, "r.toml"), 'name = "r"\nbase = "seed-case1"\nfeatures = ["road_load"]\n'
                          '[params]\nroad_w_eps_rad_s = 1e-12\n')
            for args in (["run", "--scene", scene], ["validate", "--scene", scene, "--out-dir", d]):
                self.refused(args, "road_w_eps_rad_s: must be in [0.001, 1000] rad/s")

    def test_input_torques_one_range(self):
        with tempfile.TemporaryDirectory() as d:
            scene = write(os.path.join(d, "t.toml"), 'name = "t"\nbase = "seed-case1"\n[inputs]\ntau_in = 1e300\n')
            for args in (["run", "--scene", scene], ["validate", "--scene", scene, "--out-dir", d]):
                self.refused(args, "tau_in: must stay within [-1000, 1000] N m")
            self.refused(["mbd", "--case", "1", "--tau-in", "1000.5"], "--tau-in: 1000.5 is outside [-1000, 1000] N m")

    def test_estimated_work_above_the_cap_is_refused_before_the_run(self):
        line = self.refused(["mbd", "--case", "1", "--t-end", "0.02", "--max-steps", "100"],
                            "needs an estimated 1000 integrator steps")
        self.assertIn("raise it with --max-steps", line)
        # The production set's stiffer chain: its own measured rate.
        line = self.refused(["mbd", "--set", "production", "--t-end", "0.02", "--max-steps", "100"],
                            "needs an estimated 3600 integrator steps (0.02 s x 180000 BDF steps per simulated second")
        line = self.refused(["mbd", "--case", "1", "--t-end", "3600", "--rtol", "1e-11"], "above the cap of 1e+08")
        self.assertIn("rtol 1e-11", line)
        self.refused(["validate", "--scene", "seed-case1", "--max-steps", "10", "--out-dir", "/nonexistent/x"],
                     "scene seed-case1's reference run needs an estimated")
        self.refused(["calibrate", "--scene", "seed-case1", "--max-steps", "10", "--out-dir", "/nonexistent/x"],
                     "scene seed-case1's reference run needs an estimated")

    def test_max_evals_counts_every_plant_run(self):
        self.refused(["calibrate", "--scene", "seed-case1", "--max-evals", "1", "--out-dir", "/nonexistent/x"],
                     "--max-evals: 1 is below the 9 plant evaluations a fit of 7 parameter(s) needs")


class Nulls(Case):
    """Class 6: what was not computed is null in JSON and n/a in text (docs/cli.md#nulls)."""

    def test_validate_ratio_of_a_run_whose_driven_pulley_never_turns(self):
        with tempfile.TemporaryDirectory() as d:
            r, j = validate_json("--scene", "seed-case1", "--t-end", "0.005", "--no-figures", "--out-dir", d)
            self.assertEqual(r.returncode, 0, r.stderr)
            ratio = next(e for e in j["scenes"][0]["errors"] if e["quantity"].startswith("ratio"))
            self.assertEqual(ratio, {"quantity": ratio["quantity"], "unit": "-", "rel_rms": None, "plant_ss": None,
                                     "reference_ss": None, "ss_rel": None})
            t = run("validate", "--scene", "seed-case1", "--t-end", "0.005", "--no-figures", "--out-dir", d)
            row = next(l for l in t.stdout.splitlines() if l.startswith("| ratio"))
            self.assertEqual(row.count("n/a"), 4, row)
            self.assertNotIn("0.0 %", row)

    def test_mbd_failed_before_its_first_sample(self):
        # A start at 1000 rad/s flings a link off the drive during the hold,
        # before the release: the run made no sample.
        args = ["mbd", "--case", "1", "--t-end", "0.01", "--omega0", "1000,1000"]
        r = run(*args, "--json")
        self.assertEqual(r.returncode, 1, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["status"], "failed")
        self.assertEqual(j["samples"], 0)
        for k in ("t_reached_s", "omega1_end_rad_s", "omega2_end_rad_s", "ratio_end", "ratio_mean", "F_ax1_mean_N",
                  "F_ax1_ripple_N", "F_ax1_last_window_mean_N", "T_tight_end_N", "T_slack_end_N", "wrap_links_end",
                  "energy_residual_rel"):
            self.assertIsNone(j[k], k)
        for k, v in j["energy"].items():
            self.assertIsNone(v, k)
        t = run(*args)
        self.assertEqual(t.returncode, 1)
        self.assertIn("t = n/a s: omega1 n/a rad/s", t.stdout)
        self.assertIn("energy ledger: max residual n/a", t.stdout)

    def test_mbd_ripple_of_one_sample(self):
        # The window is the run's last second: at a 2 s sample over 2 s it
        # holds one sample, and a peak to peak of one sample is no ripple.
        r = run("mbd", "--case", "1", "--t-end", "2", "--sample", "2", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["samples"], 2)
        self.assertIsNone(j["F_ax1_ripple_N"])
        self.assertIsNotNone(j["F_ax1_last_window_mean_N"])
        t = run("mbd", "--case", "1", "--t-end", "2", "--sample", "2")
        self.assertIn("peak to peak n/a N", t.stdout)

    def test_run_ledger_of_a_scene_where_no_energy_flows(self):
        with tempfile.TemporaryDirectory() as d:
            scene = write(os.path.join(d, "still.toml"),
                          'name = "still"\nbase = "seed-case1"\n[inputs]\ntau_in = 0.0\ntau_load = 0.0\n')
            r = run("run", "--scene", scene, "--t-end", "0.05", "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            e = json.loads(r.stdout)["energy"]
            self.assertEqual(e["flow_scale_J"], 0.0)
            self.assertIsNone(e["residual_rel"])
            t = run("run", "--scene", scene, "--t-end", "0.05")
            self.assertIn("(n/a of the flows)", t.stdout)

    def test_rom_accuracy_of_a_candidate_that_faulted(self):
        r = run("rom-accuracy", "--scene", "seed-case1", "--t-end", "0.2", "--candidates", "euler:1,ros2:1", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        euler, ros2 = json.loads(r.stdout)["rows"]
        self.assertNotEqual(euler["fault"], "none")
        for k in ("err_omega1_rel", "err_omega2_rel", "err_F_ax_rel", "err_xd1_rel"):
            self.assertIsNone(euler[k], k)
            self.assertIsNotNone(ros2[k], k)
        t = run("rom-accuracy", "--scene", "seed-case1", "--t-end", "0.2", "--candidates", "euler:1")
        row = next(l for l in t.stdout.splitlines() if l.startswith("euler"))
        self.assertEqual(row.split().count("n/a"), 4, row)
        self.assertNotIn("inf", row)

    def test_oscillator_period_of_a_run_that_does_not_oscillate(self):
        r = run("oscillator", "--t-end", "0.1", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["behaviour"], "moving")
        self.assertIsNone(j["period_s"])


class BadInput(Case):
    """Class 7: every bad value is refused, with the flag."""

    def test_empty_paths(self):
        self.refused(["mbd", "--case", "1", "--t-end", "0.01", "--csv", ""], "--csv: empty file name")
        self.refused(["mbd", "--case", "1", "--t-end", "0.01", "--links-csv", ""], "--links-csv: empty file name")
        self.refused(["run", "--scene", "seed-case1", "--csv", ""], "--csv: empty file name")
        self.refused(["oscillator", "--t-end", "1", "--csv", ""], "--csv: empty file name")

    def test_picture_t_negative(self):
        for v in ("-1", "-0.5"):
            self.refused(["mbd", "figures", "--out-dir", "/tmp/never", "--picture-t", v], "--picture-t",
                         sub="mbd figures")

    def test_empty_params_table(self):
        with tempfile.TemporaryDirectory() as d:
            for text, needle in (("[params]\n", "the [params] table is empty"), ("", "no [params] table"),
                                 ("# only a comment\n", "no [params] table")):
                p = write(os.path.join(d, "p.toml"), text)
                self.refused(["validate", "--scene", "seed-case1", "--params", p, "--out-dir", d], needle)
                self.refused(["calibrate", "--scene", "seed-case1", "--start", p, "--out-dir", d], needle)

    def test_extra_cells_refused_like_short_ones(self):
        with tempfile.TemporaryDirectory() as d:
            good = "".join(f"{i * 1e-3},{(i * 37) % 11}\n" for i in range(400))
            f = write(os.path.join(d, "x.csv"), "t_s,y\n" + good[:40] + "0.5,1,99\n" + good[40:])
            self.refused(["analyze", "ripple", "--csv", f, "--column", "y", "--windows", "0:0.3"],
                         "row has 3 cells, the header has 2", sub="analyze ripple")
            self.refused(["analyze", "test01", "--csv", f, "--column", "y"], "row has 3 cells, the header has 2",
                         sub="analyze test01")


class InputReading(Case):
    """Class 8: inputs read once (pipes work), a byte-order mark, nothing printed before a refusal."""

    def ripple_csv(self):
        import math
        return "t_s,y\n" + "".join(f"{i * 1e-3},{math.sin(2 * math.pi * 50 * i * 1e-3)}\n" for i in range(2000))

    def test_ripple_reads_a_pipe(self):
        text = self.ripple_csv()
        with tempfile.TemporaryDirectory() as d:
            f = write(os.path.join(d, "y.csv"), text)
            from_file = run("analyze", "ripple", "--csv", f, "--column", "y", "--windows", "0:1,1:2", "--json")
            self.assertEqual(from_file.returncode, 0, from_file.stderr)
        from_pipe = subprocess.run(
            ["bash", "-c", f'{CLI} analyze ripple --csv <(cat) --column y --windows 0:1,1:2 --json'], input=text,
            capture_output=True, text=True, timeout=120)
        self.assertEqual(from_pipe.returncode, 0, from_pipe.stderr)
        self.assertEqual(json.loads(from_pipe.stdout), json.loads(from_file.stdout))

    def test_byte_order_mark(self):
        with tempfile.TemporaryDirectory() as d:
            f = write(os.path.join(d, "y.csv"), ("\ufeff" + self.ripple_csv()).encode("utf-8"), "wb")
            r = run("analyze", "ripple", "--csv", f, "--column", "y", "--windows", "0:1", "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertEqual(json.loads(r.stdout)["time_column"], "t_s")

    def test_text_mode_refusal_prints_no_table(self):
        with tempfile.TemporaryDirectory() as d:
            f = write(os.path.join(d, "y.csv"), self.ripple_csv())
            # The second window has no samples: refused before the table.
            self.refused(["analyze", "ripple", "--csv", f, "--column", "y", "--windows", "0:1,5:6"], "",
                         sub="analyze ripple")


class Messages(Case):
    """Class 9: the flag given, the value as given, one range from a flag or a file."""

    def test_refused_values_are_not_rounded_into_range(self):
        line = self.refused(["mbd", "--case", "1", "--sheaves", "clamped", "--clamp-N", "99.99999"],
                            "--clamp-N: 99.99999 is outside [100, 100000] N")
        self.assertNotIn(" 100 is outside", line)

    def test_errors_name_the_flag_given(self):
        self.refused(["run", "--scene", "seed-case1", "--t-end", "0.05", "--dt", "0.1"],
                     "--dt: 0.1 s is above --t-end 0.05 s")
        self.refused(["run", "--scene", "seed-case1", "--t-end", "0.0005"],
                     "--t-end: 0.0005 s is below the scene's frame_s 0.001 s")

    def test_help_range_is_the_range_checked(self):
        h = run("mbd", "--help").stdout
        self.assertIn("--t-end FLOAT:in [1e-06, 3600]", h)
        self.refused(["mbd", "--case", "1", "--t-end", "1e-7"], "--t-end: '1e-7' is outside [1e-06, 3600]")
        self.assertIn("--picture-t FLOAT:in [0, 3600]", run("mbd", "figures", "--help").stdout)


if __name__ == "__main__":
    unittest.main(verbosity=2)
