#!/usr/bin/env python3
"""Bad input and failed runs at the front door (docs/cli.md#conventions, #ranges).

Every bad option, file argument or oversized run gets exit 2, one line on
stderr that starts `cvtplant <sub>: error:` and names the option, and nothing
on stdout; a run that fails gets exit 1 and `cvtplant <sub>: failed:`; data
goes to stdout or the file only, and a failed write fails the run.
"""
import csv
import io
import os
import re
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
DOCS = os.path.join(ROOT, "docs", "cli.md")


def run(*args, **kw):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600, **kw)


class Case(unittest.TestCase):
    def usage_error(self, args, pattern, sub=None):
        """Exit 2, nothing on stdout, one stderr line `cvtplant SUB: error: ...` matching pattern."""
        r = run(*args)
        self.assertEqual(r.returncode, 2, f"{args}: exit {r.returncode}, stderr {r.stderr!r}")
        self.assertEqual(r.stdout, "", f"{args}: stdout not empty")
        lines = r.stderr.splitlines()
        self.assertEqual(len(lines), 1, f"{args}: stderr {r.stderr!r}")
        sub = sub or args[0]
        self.assertTrue(lines[0].startswith(f"cvtplant {sub}: error: "), lines[0])
        self.assertRegex(lines[0], pattern)
        return lines[0]

    def refused_values(self, command, patterns):
        """`command` with each "option value" of `patterns` added: a usage error matching its pattern."""
        for option_value, pattern in patterns.items():
            self.usage_error(command + option_value.split(), pattern)

    def run_failure(self, args, pattern, sub=None, **kw):
        """Exit 1 and a `cvtplant SUB: failed: ...` line on stderr matching pattern."""
        r = run(*args, **kw)
        self.assertEqual(r.returncode, 1, f"{args}: exit {r.returncode}, stderr {r.stderr!r}")
        sub = sub or args[0]
        fails = [l for l in r.stderr.splitlines() if l.startswith(f"cvtplant {sub}: failed: ")]
        self.assertEqual(len(fails), 1, r.stderr)
        self.assertRegex(fails[0], pattern)
        return r


def write(d, name, text):
    path = os.path.join(d, name)
    with open(path, "w") as f:
        f.write(text)
    return path


class NumericOptions(Case):
    """Every numeric option: finite, in its documented range."""

    def test_nan_and_inf_refused_everywhere(self):
        for args in (["run", "--scene", "seed-case1", "--t-end"], ["oscillator", "--t-end"],
                     ["rom-accuracy", "--scene", "seed-case1", "--dt"], ["lyapunov", "--scene", "lorenz", "--t-end"],
                     ["lyapunov", "--scene", "lorenz", "--dt"]):
            for bad in ("nan", "inf", "-inf", "1e400"):
                self.usage_error(args + [bad], r"--(t-end|dt).*(not a finite number|outside the range of a double)")

    def test_rom_accuracy_t_end_inf(self):
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--t-end", "inf"], r"--t-end: 'inf' is not a finite")

    def test_rom_accuracy_dt_tiny(self):
        # Was a bad_alloc: 1e13 frames reserved.
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--dt", "1e-12"], r"--dt: '1e-12' is outside \[1e-07, 1\]")

    def test_rom_accuracy_dt_above_t_end(self):
        # Was exit 0 with nothing compared.
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--t-end", "0.5", "--dt", "0.8"],
                         r"--dt: must be <= --t-end")

    def test_rom_accuracy_reference_substeps_capped(self):
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--ref-substeps", "1000000"],
                         r"--ref-substeps: '1000000' is outside 1\.\.100000")
        line = self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--t-end", "1000", "--ref-substeps", "100000"],
                                r"needs 1e\+11 integrator steps .*cap of 1e\+09; raise it with --max-steps")
        self.assertIn("1000000 frames", line)
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--candidates", "ros2:1e3"],
                         r"--candidates: substeps '1e3' is not an integer")

    def test_rom_accuracy_memory_capped(self):
        self.usage_error(["rom-accuracy", "--scene", "gross-slip", "--t-end", "1e5", "--dt", "1e-4", "--ref-substeps", "1",
                          "--candidates", "ros2:1", "--max-steps", "1e15"],
                         r"needs about 61036 MB .*cap of 1024 MB; raise it with --max-memory-mb")

    def test_lyapunov_nan_negative(self):
        self.refused_values(["lyapunov", "--scene", "lorenz"], {
            "--t-end nan": r"--t-end: 'nan' is not a finite number", "--t-end -5": r"--t-end: '-5' is outside \(0, 1e\+09\]",
            "--dt -0.01": r"--dt: '-0.01' is outside", "--t-transient -1": r"--t-transient: '-1' is outside",
            "--batches 1": r"--batches: '1' is outside 2\.\.1000"})

    def test_lyapunov_dt_1e_300(self):
        # Was a signed overflow of the step count (UBSan) before any check.
        self.usage_error(["lyapunov", "--scene", "lorenz", "--dt", "1e-300"], r"--dt: '1e-300' is outside \[1e-09, 1\]")

    def test_lyapunov_run_length_capped(self):
        self.usage_error(["lyapunov", "--scene", "lorenz", "--dt", "1e-9", "--t-end", "1000"],
                         r"needs 1\.\d+e\+12 integrator steps .*raise it with --max-steps")
        self.usage_error(["lyapunov", "--scene", "lorenz", "--dt", "0.01", "--t-end", "2000", "--max-steps", "1000"],
                         r"needs 2\.06e\+05 integrator steps .*cap of 1000; raise it with --max-steps")
        # A plant scene shortens dt for its stiffness inside the library: the
        # same cap holds there.
        self.usage_error(["lyapunov", "--scene", "seed-case1", "--t-end", "1", "--t-transient", "0",
                          "--t-warmup", "0", "--dt", "0.01", "--max-steps", "500"],
                         r"needs .* steps .*above the cap of 500; raise it with --max-steps")

    def test_integer_options_strict(self):
        self.refused_values(["run", "--scene", "seed-case1"], {
            "--substeps 2.5": r"--substeps: '2.5' is not an integer", "--substeps 0": r"--substeps: '0' is outside 1\.\.10000",
            "--every -3": r"--every: '-3' is outside"})
        self.usage_error(["oscillator", "--t-end", "1", "--every", "1e3"], r"--every: '1e3' is not an integer")

    def test_run_and_oscillator_ranges(self):
        self.usage_error(["run", "--scene", "seed-case1", "--dt", "1e-9"], r"--dt: '1e-09' is outside|--dt: '1e-9' is outside")
        self.usage_error(["run", "--scene", "seed-case1", "--t-end", "2e5"], r"--t-end: '2e5' is outside \(0, 100000\]")
        self.usage_error(["oscillator", "--t-end", "1", "--dt", "2"], r"--dt: '2' is outside|--dt: must be <= --t-end")
        self.usage_error(["oscillator", "--t-end", "1e6", "--dt", "1e-4"],
                         r"needs 1e\+10 integrator steps \(--t-end / --dt\).*--max-steps")
        self.usage_error(["run", "--scene", "seed-case1", "--t-end", "1e5", "--substeps", "100"],
                         r"needs 1e\+10 integrator steps \(1e\+08 frames x 100 substeps\).*--max-steps")

    def test_cap_options_ranged(self):
        self.usage_error(["run", "--scene", "seed-case1", "--max-steps", "0"], r"--max-steps: '0' is outside \[1, 1e\+15\]")
        self.usage_error(["rom-accuracy", "--scene", "seed-case1", "--max-memory-mb", "nan"], r"--max-memory-mb: 'nan'")

    def test_raised_cap_runs(self):
        # The cap is a guard, not a limit: raised, the same run goes ahead.
        self.usage_error(["run", "--scene", "seed-case1", "--t-end", "0.2", "--max-steps", "100"],
                         r"needs 200 integrator steps")
        r = run("run", "--scene", "seed-case1", "--t-end", "0.2", "--max-steps", "200", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)


class AnalyzeOptions(Case):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.sine = os.path.join(cls.tmp.name, "sine.csv")
        with open(cls.sine, "w") as f:
            f.write("t,s\n")
            for i in range(2000):
                f.write(f"{i},{__import__('math').sin(i * 0.17):.10f}\n")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def series(self, tool, *extra):
        return ["analyze", tool, "--csv", self.sine, "--column", "s", *extra]

    def test_fnn_rtol_negative(self):
        self.usage_error(self.series("fnn", "--rtol", "-1"), r"--rtol: '-1' is outside \(0, 1e\+06\]", "analyze fnn")

    def test_rqa_eps_inf(self):
        self.usage_error(self.series("rqa", "--eps", "inf"), r"--eps: 'inf' is not a finite number", "analyze rqa")
        self.usage_error(self.series("rqa", "--rr", "1"), r"--rr: '1' is outside \(0, 1\)", "analyze rqa")

    def test_test01_n_c_1e8(self):
        self.usage_error(self.series("test01", "--n-c", "1e8"), r"--n-c: '1e8' is not an integer", "analyze test01")
        self.usage_error(self.series("test01", "--n-c", "100000000"), r"--n-c: '100000000' is outside 1\.\.10000",
                         "analyze test01")

    def test_series_options(self):
        self.usage_error(self.series("ami", "--dt", "0"), r"--dt: '0' is outside \(0, 1e\+06\]", "analyze ami")
        self.usage_error(self.series("lle", "--m", "31"), r"--m: '31' is outside 1\.\.30", "analyze lle")
        self.usage_error(self.series("cao", "--discard", "-1"), r"--discard: '-1' is outside", "analyze cao")
        self.usage_error(self.series("classify", "--tau", "0"), r"--tau: '0' is outside 1\.\.100000", "analyze classify")

    def test_seed_section4_t_end_1e5_memory(self):
        # Was 790 MB and growing before any check.
        with tempfile.TemporaryDirectory() as d:
            self.usage_error(["analyze", "seed-section4", "--scene", "seed-case1", "--t-end", "1e5", "--out-dir", d],
                             r"needs about \d+ MB \(1e\+08 samples of 2 signal\(s\).*raise it with --max-memory-mb",
                             "analyze seed-section4")
            self.assertEqual(os.listdir(d), [])

    def test_trajectory_and_sweep_capped(self):
        self.usage_error(["analyze", "trajectory", "--scene", "lorenz", "--t-end", "1e9", "--sample-dt", "1e9"],
                         r"needs 2e\+11 integrator steps .*--max-steps", "analyze trajectory")
        self.usage_error(["analyze", "trajectory", "--scene", "lorenz", "--t-end", "1e4", "--sample-dt", "1e-4",
                          "--dt", "1e-4", "--max-steps", "1e15"],
                         r"needs about 2289 MB .*--max-memory-mb", "analyze trajectory")
        self.usage_error(["analyze", "sweep", "--scene", "lorenz", "--axis", "rho=20:30:100000", "--t-end", "100"],
                         r"needs \S+ integrator steps \(100000 points x .*--max-steps", "analyze sweep")
        self.usage_error(["analyze", "sweep", "--scene", "logistic", "--axis", "r=3:4:5", "--state", "3"],
                         r"--state: 3 is not a state index of logistic \(0\.\.0\)", "analyze sweep")
        self.usage_error(["analyze", "sweep", "--scene", "logistic", "--axis", "r=3:4:5", "--shard", "2/2"],
                         r"--shard '2/2': '2' is outside 0\.\.1", "analyze sweep")

    def test_sweep_every_point_failed_exits_1(self):
        # The logistic map leaves [0, 1] for r > 4 and diverges at every point.
        r = self.run_failure(["analyze", "sweep", "--scene", "logistic", "--axis", "r=5:6:3", "--t-end", "100",
                              "--t-transient", "10", "--jobs", "1"], r"every point \(3\) failed; first error: '.*diverged",
                             "analyze sweep")
        # The CSV still says which points failed.
        rows = [l for l in r.stdout.splitlines() if l and not l.startswith("#")]
        self.assertEqual(len(rows), 1 + 3)


class SceneFiles(Case):
    def runs_until(self, d, inputs, flags, pattern):
        """A 0.1 s seed-case1 scene with `inputs` under [inputs]: it runs, and `flags` make it a
        usage error matching `pattern`. Returns the scene's path."""
        p = write(d, "ok.toml", 'base = "seed-case1"\nt_end_s = 0.1\n[inputs]\n' + inputs)
        self.assertEqual(run("run", "--scene", p, "--json").returncode, 0)
        self.usage_error(["run", "--scene", p] + flags, pattern)
        return p

    def test_table_negative_time(self):
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "neg.toml", 'base = "seed-case1"\n[inputs]\n'
                      'tau_in = { kind = "table", t_s = [-1.0, 2.0], value = [100.0, 120.0] }\n')
            self.usage_error(["run", "--scene", p], re.escape(p) + r":3: inputs.tau_in: profile times must be >= 0")

    def test_sine_frequency_1e300(self):
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "f.toml", 'base = "seed-case1"\n[inputs]\n'
                      'tau_in = { kind = "sine", offset = 100.0, amplitude = 5.0, freq_hz = 1e300 }\n')
            self.usage_error(["run", "--scene", p], r":3: inputs.tau_in: sine frequency must be at most half the frame rate")
            # Half the frame rate is the limit: 500 Hz at 1 ms is accepted, 501 Hz is not.
            self.runs_until(d, 'tau_in = { kind = "sine", offset = 100.0, amplitude = 5.0, freq_hz = 500.0 }\n',
                            ["--dt", "2e-3"], r"tau_in: sine frequency must be at most half")

    def test_fixed_point_clamp_beyond_q16(self):
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "c.toml", 'base = "seed-case1"\nscalar = "fixed"\n[inputs]\n'
                      'clamp = { kind = "ramp", from = 32768.0, to = 40000.0, t0_s = 0.0, t1_s = 1.0 }\n')
            self.usage_error(["run", "--scene", p], r"clamp: the profile goes beyond the fixed-point range")
            # The same scene is fine in double, and refused when --scalar chooses fixed.
            dbl = self.runs_until(d, 'clamp = { kind = "ramp", from = 32768.0, to = 40000.0, t0_s = 0.0, t1_s = 1.0 }\n',
                                  ["--scalar", "fixed"], r"clamp: the profile goes beyond the fixed-point")
            self.usage_error(["rom-accuracy", "--scene", dbl, "--scalar", "fixed"],
                             r"--scalar fixed: clamp: the profile goes beyond the fixed-point range")
            # 32767 N fits.
            fits = write(d, "e.toml", 'base = "seed-case1"\nt_end_s = 0.05\nscalar = "fixed"\n[inputs]\nclamp = 32767.0\n')
            r = run("run", "--scene", fits, "--json")
            self.assertNotEqual(r.returncode, 2, r.stderr)

    def test_scene_directory_devnull_devzero(self):
        with tempfile.TemporaryDirectory() as d:
            self.usage_error(["run", "--scene", d], r"--scene: '.*' is a directory, not a file")
            self.usage_error(["lyapunov", "--scene", d], r"--scene: '.*' is a directory, not a file")
        self.usage_error(["run", "--scene", "/dev/null"], r"--scene: '/dev/null' is not a regular file or a pipe")
        self.usage_error(["run", "--scene", "/dev/zero"], r"--scene: '/dev/zero' is not a regular file or a pipe")

    def test_scene_pipe_bounded(self):
        # A pipe is read, but only up to the 1 MiB cap: an endless one stops.
        r = subprocess.run(["bash", "-c", f'"{CLI}" run --scene <(cat /dev/zero)'], capture_output=True, text=True,
                           timeout=120)
        self.assertEqual(r.returncode, 2, r.stderr)
        self.assertRegex(r.stderr, r"^cvtplant run: error: --scene: '/dev/fd/\d+' is larger than 1048576 bytes\n$")
        r = subprocess.run(["bash", "-c", f'"{CLI}" run --scene <(printf "base = \\"seed-case1\\"\\nt_end_s = 0.1\\n") --json'],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)

    def test_empty_scene_file(self):
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "empty.toml", "# nothing\n")
            self.usage_error(["run", "--scene", p], r"has no keys: not a scene file")

    def test_non_ascii_scene_file(self):
        # The TOML parser has undefined behaviour on some non-ASCII characters
        # where it looks for whitespace (the scene-file fuzzer found U+00A0..
        # U+0499 there): any non-ASCII byte is refused with its line.
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "u.toml", 'base = "seed-case1"\nt_end_s = 0.1\u00e9 \n')
            self.usage_error(["run", "--scene", p], r"u\.toml:2: not ASCII")
            p = write(d, "c.toml", '# \u00b5 in a comment\nbase = "seed-case1"\n')
            self.usage_error(["run", "--scene", p], r"c\.toml:1: not ASCII")

    def test_csv_over_the_scene_file(self):
        with tempfile.TemporaryDirectory() as d:
            text = 'base = "seed-case1"\nt_end_s = 0.1\n'
            p = write(d, "s.toml", text)
            os.symlink(p, os.path.join(d, "link.csv"))
            os.link(p, os.path.join(d, "hard.csv"))
            for out in (p, os.path.join(d, "link.csv"), os.path.join(d, "hard.csv"), os.path.join(d, ".", "s.toml")):
                self.usage_error(["run", "--scene", p, "--csv", out], r"--csv: '.*' is the input of --scene \('.*'\); writing it would destroy that input")
            with open(p) as f:
                self.assertEqual(f.read(), text)
            self.usage_error(["run", "--scene", "seed-case1", "--csv", d], r"--csv: '.*' is a directory")

    def test_merge_out_over_a_shard(self):
        with tempfile.TemporaryDirectory() as d:
            shard = write(d, "s0.csv", "# placeholder\n")
            self.usage_error(["analyze", "merge", shard, "--out", shard], r"--out: '.*' is the input of the shards", "analyze merge")
            with open(shard) as f:
                self.assertEqual(f.read(), "# placeholder\n")

    def test_unknown_scene_file_reason_kept(self):
        # A file that exists but is not a scene says why, for the model tools too.
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "bad.toml", "name = [\n")
            self.usage_error(["lyapunov", "--scene", p, "--t-end", "1"], re.escape(p) + r":\d+: syntax:")


class FailureIsVisible(Case):
    def test_divergence_prints_failed(self):
        r = self.run_failure(["run", "--scene", "seed-case2", "--integrator", "rk4", "--substeps", "1", "--json"],
                             r"the plant faulted: (energy-growth|state-non-finite) at t = \S+ s \(frame \d+\)")
        self.assertIn('"fault"', r.stdout)  # the summary is still written
        # RK4 at a 1 s step on the 2 Hz oscillator grows without bound.
        self.run_failure(["oscillator", "--x0", "0,30,0,60", "--t-end", "400", "--dt", "1"],
                         r"the state became non-finite at step \d+ \(t = \d+ s\): the step is too large")

    def test_unknown_subcommand(self):
        r = run("rum", "--scene", "x")
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stdout, "")
        self.assertRegex(r.stderr, r"^cvtplant: error: unknown subcommand 'rum' \(did you mean 'run'\?\); "
                                   r"subcommands: .*oscillator.*\n$")
        r = run("analyze", "clasify", "--csv", "x")
        self.assertEqual(r.returncode, 2)
        self.assertRegex(r.stderr, r"^cvtplant analyze: error: unknown subcommand 'clasify' \(did you mean 'classify'\?\);"
                                   r" subcommands: ami, fnn, .*\n$")
        r = run("xyzzy")
        self.assertRegex(r.stderr, r"^cvtplant: error: unknown subcommand 'xyzzy'; subcommands: ")

    def test_long_cells_truncated(self):
        with tempfile.TemporaryDirectory() as d:
            p = os.path.join(d, "long.csv")
            with open(p, "w") as f:
                f.write("t,s\n0,1\n1," + "x" * 50_000_000 + "\n")
            line = self.usage_error(["analyze", "ami", "--csv", p, "--column", "s"],
                                    r":3: column 's': 'xxxx\S*\.\.\.' \(50000000 characters\) is not a number", "analyze ami")
            self.assertLess(len(line), 300)
            line = self.usage_error(["run", "--scene", "y" * 100000], r"--scene: 'yyy\S*\.\.\.' \(100000 characters\) is neither")
            self.assertLess(len(line), 400)
            line = self.usage_error(["run", "--scene", "seed-case1", "--dt", "1" * 100000], r"--dt: '111\S*\.\.\.' \(100000 characters\)")
            self.assertLess(len(line), 300)
            s = write(d, "s.toml", 'base = "seed-case1"\nintegrator = "' + "z" * 500000 + '"\n')
            line = self.usage_error(["run", "--scene", s], r":2: integrator: unknown method 'zzz\S*\.\.\.' \(500000 characters\)")
            self.assertLess(len(line), 400)

    def test_csv_to_stdout_holds_data_only(self):
        r = run("run", "--scene", "tip-in", "--t-end", "0.5", "--csv", "-")
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = list(csv.reader(io.StringIO(r.stdout)))
        self.assertEqual(rows[0][:5], ["t", "omega1", "omega2", "F_ax", "slip"])
        self.assertEqual(len(rows), 1 + 501)
        self.assertTrue(all(len(row) == len(rows[0]) for row in rows))
        for row in rows[1:]:
            float(row[0])
        self.assertIn("Scene tip-in", r.stderr)  # the summary went to stderr
        r = run("oscillator", "--t-end", "0.01", "--csv", "-")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stdout.splitlines()[0], "t,x1,v1,x2,v2,F1,F2")
        self.assertIn("Stick-slip oscillator", r.stderr)
        self.usage_error(["run", "--scene", "tip-in", "--csv", "-", "--json"], r"--json and --csv - both write to stdout")

    def test_closed_pipe_fails_the_run(self):
        # `cvtplant run --csv - | head -1`: the reader goes away after one line.
        for args in (["run", "--scene", "seed-case1", "--t-end", "100", "--csv", "-"],
                     ["oscillator", "--t-end", "100", "--csv", "-"],
                     ["analyze", "trajectory", "--scene", "lorenz", "--t-end", "1000", "--sample-dt", "0.01"]):
            p = subprocess.Popen([CLI, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            first = p.stdout.readline()
            self.assertTrue(first)
            p.stdout.close()
            err = p.stderr.read().decode()
            p.stderr.close()
            code = p.wait(timeout=600)
            sub = " ".join(args[:2]) if args[0] == "analyze" else args[0]
            self.assertEqual(code, 1, f"{args}: {err!r}")
            self.assertRegex(err, rf"cvtplant {sub}: failed: writing (to stdout|the output) failed: Broken pipe")

    def test_full_disk_fails_the_run(self):
        if not os.path.exists("/dev/full"):
            self.skipTest("no /dev/full")
        self.run_failure(["run", "--scene", "seed-case1", "--t-end", "0.5", "--csv", "/dev/full"],
                         r"writing the output failed: No space left on device")
        self.run_failure(["oscillator", "--t-end", "0.1", "--csv", "/dev/full"], r"No space left on device")
        with open("/dev/full", "w") as full:
            for args, sub in ((["scenes"], "scenes"), (["run", "--scene", "seed-case1", "--t-end", "0.1", "--json"], "run"),
                              (["run", "--scene", "seed-case1", "--t-end", "0.1", "--csv", "-"], "run"),
                              (["lyapunov", "--list"], "lyapunov")):
                r = subprocess.run([CLI, *args], stdout=full, stderr=subprocess.PIPE, text=True, timeout=600)
                self.assertEqual(r.returncode, 1, f"{args}: {r.stderr!r}")
                self.assertRegex(r.stderr, rf"cvtplant {sub}: failed: writing to stdout failed: No space left on device")
        with tempfile.TemporaryDirectory() as d:
            r = run("analyze", "seed-section4", "--scene", "seed-case1", "--t-end", "0.1", "--out-dir", "/dev/full/x")
            self.assertNotEqual(r.returncode, 0)


class RangesDocumented(unittest.TestCase):
    """The ranges in --help are the ones docs/cli.md#ranges lists (one place in the code, one table in the docs)."""

    SUBS = ["oscillator", "run", "rom-accuracy", "lyapunov"] + ["analyze " + t for t in (
        "ami", "fnn", "cao", "lle", "rqa", "recurrence", "test01", "classify", "trajectory", "sweep", "figures",
        "seed-section4", "ripple")]

    def help_ranges(self, sub):
        r = run(*sub.split(), "--help")
        self.assertEqual(r.returncode, 0, r.stderr)
        out = {}
        for line in r.stdout.splitlines():
            m = re.match(r"\s+(--[a-z0-9-]+) (FLOAT|INT|UINT)(?::in ([\[(][^\])]*[\])]|-?\d+\.\.\d+))?", line)
            if m:
                out[m.group(1)] = m.group(3)
        return out

    def test_every_numeric_option_has_a_documented_range(self):
        with open(DOCS) as f:
            docs = f.read()
        table = {}
        for m in re.finditer(r"^\| `([a-z0-9 <>*-]+)` \| `(--[a-z0-9-]+)` \| `([^`]+)` \|", docs, re.M):
            table[(m.group(1), m.group(2))] = m.group(3)
        series = {"analyze " + t for t in ("ami", "fnn", "cao", "lle", "rqa", "recurrence", "test01", "classify")}
        seen = 0
        used = set()
        for sub in self.SUBS:
            for opt, rng in self.help_ranges(sub).items():
                seen += 1
                self.assertIsNotNone(rng, f"{sub} {opt}: numeric option without a range")
                # A row for the subcommand, else the row shared by the series tools, else by every subcommand.
                keys = [(sub, opt)] + ([("analyze <series>", opt)] if sub in series else []) + [("*", opt)]
                key = next((k for k in keys if k in table), None)
                self.assertIsNotNone(key, f"{sub} {opt} {rng}: not in docs/cli.md#ranges")
                self.assertEqual(table[key], rng, f"{sub} {opt}")
                used.add(key)
        self.assertGreater(seen, 100)
        self.assertEqual(set(table) - used, set(), "rows of docs/cli.md#ranges that no --help shows")


if __name__ == "__main__":
    unittest.main(verbosity=2)
