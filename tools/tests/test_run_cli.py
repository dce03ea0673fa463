#!/usr/bin/env python3
"""`cvtplant run` / `cvtplant scenes` as a user drives them (docs/rom.md)."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

CLI = sys.argv.pop(1) if len(sys.argv) > 1 else "cvtplant"
HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "..", "tools", "scenes")
# The seed case under its clamping actuator: the built-in seed-case1 runs the
# tension plant on fixed sheaves, which the adaptive solver does not have.
CLAMPED = os.path.join(SCENES, "seed-case1-clamped.toml")
BUILTIN = ["oscillator-coulomb", "oscillator-stribeck", "seed-case1", "seed-case2", "clamp-step", "tip-in",
           "gross-slip", "ratio-control"]


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=600)


def significant(text):
    """The significant digits of a decimal number's text."""
    return text.lower().split("e")[0].replace("-", "").replace(".", "").strip("0")


def write(d, name, text):
    path = os.path.join(d, name)
    with open(path, "w") as f:
        f.write(text)
    return path


class Scenes(unittest.TestCase):
    def test_one_line_per_builtin(self):
        r = run("scenes")
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.strip().splitlines()
        self.assertEqual([l.split()[0] for l in lines], BUILTIN)

    def test_json(self):
        r = run("scenes", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual([s["scene"] for s in j], BUILTIN)
        self.assertTrue(all(s["integrator"] == "ros2" and s["frame_s"] == 1e-3 for s in j))


class Run(unittest.TestCase):
    def test_csv_and_json(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "out.csv")
            r = run("run", "--scene", "tip-in", "--t-end", "2", "--csv", path, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            with open(path) as f:
                rows = list(csv.reader(f))
        self.assertEqual(rows[0][:5], ["t", "omega1", "omega2", "F_ax", "slip"])
        self.assertEqual(len(rows), 1 + 2001)
        self.assertEqual(j["fault"], "none")
        self.assertEqual(j["frames"], 2000)
        self.assertEqual(j["features"], "axial,road_load")
        self.assertLess(abs(j["energy"]["residual_rel"]), 1e-4)
        self.assertGreater(j["ns_per_frame"], 0)
        # The axial force follows the 4 kN command.
        self.assertAlmostEqual(j["final"]["F_ax_N"], 4000.0, delta=1.0)

    def test_csv_numbers_read_back_to_the_run_doubles(self):
        # Every number in the CSV is the shortest text of its double
        # (docs/cli.md#csv-numbers): the last row, parsed, equals bit for bit
        # what the JSON summary (an independent formatter) reports for the
        # final frame, and the energy columns close the balance exactly as
        # the summary's do.
        with tempfile.TemporaryDirectory() as d:
            # The ratio-shift example (wedging: every output moves) with every log.
            with open(os.path.join(SCENES, "ratio-shift.toml")) as f:
                text = f.read().replace('t_end_s = 5.0', 't_end_s = 1.5')
            text = "\n".join('log = ["torques", "friction", "ratios", "energy", "states"]' if l.startswith("log =")
                             else l for l in text.splitlines())
            self.assertIn("states", text)
            scene = write(d, "all-logs.toml", text)
            path = os.path.join(d, "out.csv")
            r = run("run", "--scene", scene, "--csv", path, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            with open(path) as f:
                rows = list(csv.DictReader(f))
        self.assertEqual(len(rows), 1 + 1500)
        last = rows[-1]
        for col, key in (("omega1", "omega1_rad_s"), ("omega2", "omega2_rad_s"), ("F_ax", "F_ax_N"),
                         ("slip", "slip"), ("torque_transmitted", "torque_transmitted_Nm")):
            self.assertEqual(float(last[col]), j["final"][key], col)
        for col, key in (("E_stored", "stored_final_J"), ("W_in", "input_J"), ("W_load", "load_J"),
                         ("W_friction", "friction_loss_J"), ("E_residual", "residual_J")):
            self.assertEqual(float(last[col]), j["energy"][key], col)
        for row in rows:
            for col, text in row.items():
                if col == "fault":
                    self.assertEqual(text, "none")
                    continue
                v = float(text)
                # Shortest round-trip: as many significant digits as Python's
                # repr() (itself the shortest text that reads back) needs.
                self.assertEqual(significant(text), significant(repr(v)), (col, text))
        # Time stamps are the frames' own: frame i at i * 1 ms to the last bit.
        self.assertEqual(float(rows[1000]["t"]), 1000 * 1e-3)

    def test_summary_separates_plant_and_output_cost(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "out.csv")
            with_csv = json.loads(run("run", "--scene", "seed-case1", "--t-end", "2", "--csv", path, "--json").stdout)
            text = run("run", "--scene", "seed-case1", "--t-end", "2", "--csv", path).stdout
        bare = json.loads(run("run", "--scene", "seed-case1", "--t-end", "2", "--json").stdout)
        self.assertEqual(bare["output_ns_per_frame"], 0)
        self.assertEqual(bare["plant_ns_per_frame"], bare["ns_per_frame"])
        self.assertGreater(with_csv["output_ns_per_frame"], 0)
        self.assertAlmostEqual(with_csv["plant_ns_per_frame"] + with_csv["output_ns_per_frame"],
                               with_csv["ns_per_frame"], delta=1e-6 * with_csv["ns_per_frame"])
        self.assertRegex(text, r"plant \d+ ns/frame, CSV output \d+ ns/frame")

    def test_every_builtin_runs_without_fault(self):
        for name in BUILTIN:
            r = run("run", "--scene", name, "--t-end", "3", "--json")
            self.assertEqual(r.returncode, 0, name + r.stderr)
            self.assertEqual(json.loads(r.stdout)["fault"], "none", name)

    def test_scalars(self):
        for scalar in ("double", "float"):
            r = run("run", "--scene", "seed-case1", "--t-end", "2", "--scalar", scalar, "--json")
            self.assertEqual(r.returncode, 0, scalar + r.stderr)
            self.assertEqual(json.loads(r.stdout)["scalar"], scalar)

    def test_unstable_integrator_is_a_fault_exit_1(self):
        r = run("run", "--scene", "seed-case2", "--integrator", "rk4", "--substeps", "1", "--json")
        self.assertEqual(r.returncode, 1)
        self.assertIn(json.loads(r.stdout)["fault"], ("energy-growth", "state-non-finite"))

    def test_example_scene_files(self):
        for name in sorted(os.listdir(SCENES)):
            r = run("run", "--scene", os.path.join(SCENES, name), "--t-end", "2", "--json")
            self.assertEqual(r.returncode, 0, name + r.stderr)


    def test_without_energy_ledger(self):
        # The scene's choice (docs/rom.md#watchdog): same trajectory, no
        # energy object and no energy columns; the default log drops them.
        with tempfile.TemporaryDirectory() as d:
            p = write(d, "s.toml", 'base = "seed-case1"\nt_end_s = 1.0\nenergy_ledger = false\n')
            out_off, out_on = os.path.join(d, "off.csv"), os.path.join(d, "on.csv")
            r = run("run", "--scene", p, "--csv", out_off, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            self.assertFalse(j["energy_ledger"])
            self.assertNotIn("energy", j)
            self.assertEqual(j["fault"], "none")
            r = run("run", "--scene", "seed-case1", "--t-end", "1", "--csv", out_on, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertTrue(json.loads(r.stdout)["energy_ledger"])
            with open(out_off) as f:
                off = list(csv.reader(f))
            with open(out_on) as f:
                on = list(csv.reader(f))
        self.assertNotIn("E_residual", off[0])
        self.assertIn("E_residual", on[0])
        self.assertEqual(len(off), len(on))
        for a, b in zip(off[1:], on[1:]):
            self.assertEqual(a[:5], b[:5])

    def test_wedging_scene_shifts_the_ratio(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "shift.csv")
            r = run("run", "--scene", os.path.join(SCENES, "ratio-shift.toml"), "--csv", out, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            summary = json.loads(r.stdout)
            self.assertEqual(summary["fault"], "none")
            self.assertIn("wedging", summary["features"])
            with open(out) as f:
                rows = list(csv.DictReader(f))
            first, last = rows[0], rows[-1]
            # Upshift: the driver radius grows, the driven one shrinks, r2/r1
            # falls (1.5 -> 1.448 in the 1 s after the step).
            self.assertGreater(float(last["r1"]), float(first["r1"]) + 0.001)
            self.assertLess(float(last["r2"]), float(first["r2"]) - 0.001)
            self.assertLess(float(last["geometric_ratio"]), 0.98 * float(first["geometric_ratio"]))
            self.assertAlmostEqual(float(first["geometric_ratio"]), 0.1143 / 0.0762, places=9)

    def test_tension_scene_logs_the_chain_tension(self):
        # docs/rom.md#tension: the built-in seed-case1 (the seed case on fixed
        # sheaves) with the tension log group; the JSON's final.tension.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "t.csv")
            p = write(d, "t.toml", 'base = "seed-case1"\nlog = ["torques", "ratios", "tension"]\n')
            r = run("run", "--scene", p, "--t-end", "3", "--csv", out, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            j = json.loads(r.stdout)
            with open(out) as f:
                rows = list(csv.DictReader(f))
        self.assertEqual(j["features"], "tension")
        t = j["final"]["tension"]
        self.assertTrue(t["sheave_on_stop"])
        last = rows[-1]
        self.assertAlmostEqual(float(last["T_tight"]), t["T_tight_N"], places=6)
        self.assertAlmostEqual(float(last["T_slack"]), t["T_slack_N"], places=6)
        # The creep strain is dT / (kL + T_s), kL = 2700 N, and the chain runs
        # faster than r2/r1 makes it by about that much.
        dT = t["T_tight_N"] - t["T_slack_N"]
        self.assertAlmostEqual(t["creep_strain"], dT / (2700.0 + t["T_slack_N"]), places=9)
        ratio = float(last["speed_ratio"])
        self.assertGreater(ratio, 1.5 * (1.0 + 0.8 * t["creep_strain"]))
        self.assertLess(abs(j["energy"]["residual_rel"]), 1e-4)
        for h in ("T_tight", "T_slack", "T_centrifugal", "creep_strain", "sheave_on_stop"):
            self.assertIn(h, rows[0])


class Adaptive(unittest.TestCase):
    """`run --solver adaptive` (docs/numerics.md#adaptive)."""

    def run_csv(self, d, name, *args):
        path = os.path.join(d, name)
        r = run("run", "--csv", path, "--json", *args)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(path, "rb") as f:
            return json.loads(r.stdout), f.read()

    def test_same_rows_as_the_frame_stepper_and_close_to_a_fine_one(self):
        with tempfile.TemporaryDirectory() as d:
            common = ("--scene", "tip-in", "--t-end", "1.5")
            ja, a = self.run_csv(d, "a.csv", *common, "--solver", "adaptive", "--rtol", "1e-8")
            jf, f = self.run_csv(d, "f.csv", *common, "--substeps", "64")
        ra = list(csv.DictReader(a.decode().splitlines()))
        rf = list(csv.DictReader(f.decode().splitlines()))
        self.assertEqual(ja["solver"], "adaptive")
        self.assertEqual(ja["integrator"], "rodas4")
        self.assertEqual(ja["fault"], "none")
        self.assertEqual([r["t"] for r in ra], [r["t"] for r in rf])
        self.assertEqual(list(ra[0].keys()), list(rf[0].keys()))
        # The ramp of tip-in (1.0 .. 1.2 s) is held per frame in both: the
        # 64-substep frame stepper is an independent reference to ~1e-6 here.
        worst = max(abs(float(x["omega1"]) - float(y["omega1"])) for x, y in zip(ra, rf))
        self.assertLess(worst, 1e-3)
        self.assertLess(abs(ja["energy"]["residual_rel"]), 1e-4)

    def test_steps_over_frames_where_the_inputs_hold(self):
        r = run("run", "--scene", CLAMPED, "--t-end", "5", "--solver", "adaptive", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        j = json.loads(r.stdout)
        self.assertEqual(j["frames"], 5000)
        self.assertLess(j["work"]["steps"], j["frames"] / 4)
        self.assertEqual(j["work"]["jacobians"], j["work"]["steps"])

    def test_bit_for_bit_run_to_run(self):
        with tempfile.TemporaryDirectory() as d:
            args = ("--scene", "seed-case2", "--t-end", "2", "--solver", "adaptive", "--rtol", "1e-7")
            _, a = self.run_csv(d, "a.csv", *args)
            _, b = self.run_csv(d, "b.csv", *args)
        self.assertGreater(len(a), 100000)
        self.assertEqual(a, b)

    def test_step_cap_is_a_run_error(self):
        r = run("run", "--scene", CLAMPED, "--t-end", "2", "--solver", "adaptive", "--max-steps", "20")
        self.assertEqual(r.returncode, 1)
        self.assertIn("--max-steps", r.stderr)
        # No summary of a final frame the run never reached.
        self.assertNotIn("final", r.stdout)

    def test_refusals(self):
        cases = [
            (("--scene", "ratio-control", "--solver", "adaptive"), "wedging"),
            (("--scene", CLAMPED, "--solver", "adaptive", "--scalar", "float"), "double"),
            (("--scene", CLAMPED, "--solver", "adaptive", "--substeps", "4"), "--substeps"),
            (("--scene", CLAMPED, "--solver", "adaptive", "--integrator", "rk4"), "--integrator"),
            (("--scene", CLAMPED, "--rtol", "1e-6"), "--solver adaptive"),
            (("--scene", CLAMPED, "--solver", "adaptive", "--rtol", "nan"), "--rtol"),
            (("--scene", CLAMPED, "--solver", "adaptive", "--atol", "0"), "--atol"),
            (("--scene", CLAMPED, "--solver", "implicit"), "--solver"),
        ]
        for args, part in cases:
            r = run("run", *args)
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(part, r.stderr, args)
            self.assertEqual(r.stdout, "", args)


class BadInput(unittest.TestCase):
    def assert_usage(self, r, *parts):
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertTrue(r.stderr.startswith("cvtplant run: error: "), r.stderr)
        for p in parts:
            self.assertIn(p, r.stderr)

    def test_unknown_scene(self):
        self.assert_usage(run("run", "--scene", "no-such-scene"), "no-such-scene")

    def test_bad_flags(self):
        self.assertEqual(run("run", "--scene", "tip-in", "--integrator", "nope").returncode, 2)
        self.assertEqual(run("run", "--scene", "tip-in", "--dt", "-1").returncode, 2)
        self.assertEqual(run("run", "--scene", "tip-in", "--substeps", "0").returncode, 2)

    def assert_scenes_refused(self, cases):
        """Each (scene file text, extra flags, parts) refused with one line holding the parts; a part
        ":N:" is the file's line N, named after the file's path."""
        with tempfile.TemporaryDirectory() as d:
            for i, (text, flags, parts) in enumerate(cases):
                p = write(d, "s%d.toml" % i, text)
                self.assert_usage(run("run", "--scene", p, *flags), *[p + x if x.startswith(":") else x for x in parts])

    def test_syntax_error_names_file_and_line(self):
        self.assert_scenes_refused([('base = "tip-in"\n\nt_end_s = = 3\n', (), (":3:", "syntax"))])

    def test_unknown_field_names_file_line_field(self):
        self.assert_scenes_refused([('base = "tip-in"\n[params]\nr1_m = 0.07\nJ3_kgm2 = 1.0\n', (),
                                     (":4:", "params.J3_kgm2", "unknown field"))])

    def test_out_of_range_names_file_line_field(self):
        self.assert_scenes_refused([
            ('base = "tip-in"\n[params]\nr1_m = 0.07\nJ1_kgm2 = -1.0\n', (), (":4:", "params.J1_kgm2", "> 0")),
            ('base = "tip-in"\n[friction]\nmu0 = 5.0\n', (), (":3:", "friction.mu0")),
            ('base = "tip-in"\n[inputs]\n\nclamp = -3.0\n', (), (":4:", "clamp", ">= 0"))])

    def test_wrong_type_and_unknown_names(self):
        self.assert_scenes_refused([
            ('base = "tip-in"\nt_end_s = "long"\n', (), (":2:", "t_end_s", "number")),
            ('features = ["axial", "warp_drive"]\n', (), (":1:", "features", "warp_drive")),
            ('base = "tip-in"\n[inputs]\ntau_in = { kind = "square", value = 1 }\n', (), (":3:", "kind"))])

    def test_energy_ledger_key(self):
        self.assert_scenes_refused([
            ('base = "seed-case1"\nenergy_ledger = "off"\n', (), (":2:", "energy_ledger", "true or false")),
            ('base = "seed-case1"\nenergy_ledger = false\nlog = ["torques", "energy"]\n', (), ("log", "energy_ledger"))])

    def test_wedging_needs_axial_and_floating_point(self):
        shift = os.path.join(SCENES, "ratio-shift.toml")
        self.assert_usage(run("run", "--scene", shift, "--scalar", "fixed"), "scalar", "double or float")
        self.assert_scenes_refused([
            ('base = "tip-in"\nfeatures = ["wedging"]\n', (), (":2:", "features", "axial")),
            ('base = "tip-in"\nfeatures = ["axial", "wedging"]\n[params]\nbeta0_deg = 76\n', (),
             (":4:", "beta0_deg", "self-locking"))])

    def test_tension_keys_and_refusals(self):
        # (file text, extra flags, the parts the one-line error names)
        tension = 'base = "seed-case1"\nfeatures = ["tension"]\n[params]\n'
        cases = [
            (tension + "creep_gain = -1\n", (), (":4:", "params.creep_gain", "[0, 10]")),
            (tension + "chain_mass_kg_m = nan\n", (), (":4:", "params.chain_mass_kg_m", "finite")),
            (tension + "wrap_excess_share = 0.7\n", (), (":4:", "params.wrap_excess_share")),
            (tension + 'fixed_sheaves = "yes"\n', (), (":4:", "params.fixed_sheaves", "true or false")),
            ('base = "seed-case1"\nfeatures = ["axial", "tension"]\n[params]\nfixed_sheaves = true\n', (),
             (":4:", "params.fixed_sheaves", "axial")),
            ('base = "seed-case1"\nfeatures = ["axial", "wedging", "tension"]\n[params]\nfixed_sheaves = true\n', (),
             (":4:", "params.fixed_sheaves", "axial")),
            ('base = "seed-case1"\nfeatures = ["axial"]\nlog = ["torques", "tension"]\n', (), (":3:", "log", "tension feature")),
            (tension + "chain_stiffness_N = 4e7\n", ("--scalar", "fixed"), ("chain_stiffness_N", "fixed-point range")),
        ]
        self.assert_scenes_refused(cases)
        self.assert_usage(run("run", "--scene", "seed-case1", "--solver", "adaptive"), "--solver adaptive", "tension")

    def test_rom_accuracy_refuses_a_plant_the_scalar_lacks(self):
        # The fixed-point plants have no wedging: the candidates are refused
        # before anything runs, never run without the feature.
        shift = os.path.join(SCENES, "ratio-shift.toml")
        r = run("rom-accuracy", "--scene", shift, "--scalar", "fixed", "--t-end", "0.01")
        self.assertEqual(r.returncode, 2, r.stdout + r.stderr)
        self.assertEqual(r.stdout, "")
        self.assertEqual(r.stderr.strip(), "cvtplant rom-accuracy: error: --scalar fixed: features: wedging runs in "
                         "double or float only: there is no fixed-point plant with it")
        r = run("rom-accuracy", "--scene", shift, "--scalar", "float", "--t-end", "0.05", "--ref-substeps", "4",
                "--candidates", "ros2:1", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.loads(r.stdout)["rows"][0]["fault"], "none")


if __name__ == "__main__":
    unittest.main()
