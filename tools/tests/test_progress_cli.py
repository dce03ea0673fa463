#!/usr/bin/env python3
"""Progress bars of the long commands (docs/cli.md#progress): drawn on a
terminal, absent when stderr is piped and when CI is set. The terminal is a
pseudo-terminal opened here; the bar is the one helper's line
("<label> [###...] NN%  ...  wall ...  left ...")."""
import os
import pty
import re
import select
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
BAR = re.compile(r"\r(?P<label>[^\r\[]+) \[[#.]{24}\] +(?P<pct>\d+)%.*?wall [^ ]+ s?.*?left ")

# Each long command on a short job: (arguments, the bar's label).
COMMANDS = [
    (["run", "--scene", "seed-case1", "--t-end", "3"], "run seed-case1"),
    (["lyapunov", "--scene", "lorenz", "--t-end", "200", "--t-transient", "10"], "lyapunov lorenz"),
    (["analyze", "sweep", "--scene", "lorenz", "--axis", "rho=20:30:3", "--t-end", "20", "--t-transient", "5",
      "--t-peaks", "5", "--jobs", "1"], "sweep lorenz"),
    (["rom-accuracy", "--scene", "seed-case1", "--t-end", "0.5", "--candidates", "ros2:1",
      "--ref-substeps", "20"], "rom-accuracy seed-case1"),
    (["oscillator", "--friction", "stribeck", "--x0", "0,3,0,6", "--t-end", "100", "--dt", "1e-4",
      "--integrator", "rk4"], "oscillator"),
]


def env(ci=None):
    e = {k: v for k, v in os.environ.items() if k != "CI"}
    if ci is not None:
        e["CI"] = ci
    return e


def under_pty(args, ci=None):
    """Runs the command with stderr on a pseudo-terminal (stdout piped);
    returns (exit code, stdout, what the terminal received)."""
    master, slave = pty.openpty()
    p = subprocess.Popen([CLI, *args], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=slave,
                         env=env(ci))
    os.close(slave)
    tty = b""
    while True:
        r, _, _ = select.select([master], [], [], 600)
        if not r:
            p.kill()
            break
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the child closed its side
            break
        if not chunk:
            break
        tty += chunk
    out = p.stdout.read()
    p.wait(timeout=60)
    os.close(master)
    return p.returncode, out.decode(), tty.decode(errors="replace")


class Progress(unittest.TestCase):
    def test_bar_on_a_terminal(self):
        for args, label in COMMANDS:
            with self.subTest(args[0]):
                code, out, tty = under_pty(args)
                self.assertEqual(code, 0, tty)
                bars = [m for m in BAR.finditer(tty)]
                self.assertTrue(bars, "no bar on the terminal: " + repr(tty[:400]))
                self.assertEqual(bars[0].group("label"), label)
                # The line is cleared at the end: the last thing drawn is the erase.
                self.assertTrue(tty.endswith("\r\x1b[K"), repr(tty[-80:]))
                # The data stay on stdout, untouched by the bar.
                self.assertNotIn("\r", out)
                self.assertTrue(out.strip())

    def test_bar_on_the_trajectory_commands(self):
        # Their data go to files; the bar is drawn while the model or the
        # plant runs and cleared before anything else is printed.
        with tempfile.TemporaryDirectory() as d:
            for args, label in (
                    (["analyze", "trajectory", "--scene", "lorenz", "--t-end", "2000", "--out", d + "/t.csv"],
                     "trajectory lorenz"),
                    (["analyze", "figures", "--scene", "seed-case1", "--t-end", "10", "--out-dir", d + "/f"],
                     "figures seed-case1"),
                    (["analyze", "figures", "--scene", "lorenz", "--t-end", "200", "--out-dir", d + "/g"],
                     "figures lorenz")):
                with self.subTest(label):
                    code, _, tty = under_pty(args)
                    self.assertEqual(code, 0, tty)
                    bars = [m for m in BAR.finditer(tty)]
                    self.assertTrue(bars, "no bar on the terminal: " + repr(tty[:400]))
                    self.assertEqual(bars[0].group("label"), label)
                    self.assertIn("\r\x1b[K", tty)
                    r = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600, env=env())
                    self.assertEqual(r.returncode, 0, r.stderr)
                    self.assertEqual(r.stderr, "")

    def test_nothing_when_piped(self):
        for args, _ in COMMANDS:
            with self.subTest(args[0]):
                r = subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600, env=env())
                self.assertEqual(r.returncode, 0, r.stderr)
                self.assertEqual(r.stderr, "")

    def test_nothing_on_a_terminal_in_ci(self):
        args, _ = COMMANDS[0]
        code, _, tty = under_pty(args, ci="true")
        self.assertEqual(code, 0, tty)
        self.assertEqual(tty, "")
        # CI=0 means not CI: the bar is back.
        code, _, tty = under_pty(args, ci="0")
        self.assertTrue(BAR.search(tty), repr(tty[:200]))


if __name__ == "__main__":
    unittest.main()
