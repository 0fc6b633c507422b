"""flexgait's analyses from Python against the command line and against identities of the maths:
continuation, basin, orbit diagram, gait vs friction, stagnation, campaign, compensation study
and export. Each case is small (the rigid wheel where the wheel's model does not matter).

Run by ctest (python_analyses) with /usr/bin/python3; the environment gives PYTHONPATH (the
package), FLEXGAIT_EXE (the command line) and FLEXGAIT_SOURCE (the tree).
"""
import csv
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

import flexgait

EXE = os.environ["FLEXGAIT_EXE"]
SOURCE = os.environ["FLEXGAIT_SOURCE"]
RIGID = {"sim": {"model": "rigid"}}


def cli(*args):
    """Runs the command line in a fresh directory; returns that directory's run folder 'out'."""
    work = tempfile.mkdtemp(prefix="flexgait-py-")
    out = os.path.join(work, "out")
    subprocess.run([EXE, *args, "--out", out, "--no-plot"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.PIPE)
    return out


def read_text(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def read_csv(path):
    """{column: list of str} of a CSV file."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return {name: [r[i] for r in rows[1:]] for i, name in enumerate(rows[0])}


def assert_column_equals_text(test, values, cells, name):
    """A typed column (float array, bool array or list of str) holds exactly the CSV file's cells:
    numbers to the last bit (the file's shortest round-trip text), empty cells as NaN."""
    if isinstance(values, np.ndarray) and values.dtype == np.float64:
        expected = np.array([float(c) if c else np.nan for c in cells])
        np.testing.assert_array_equal(values, expected, err_msg=name)
    elif isinstance(values, np.ndarray) and values.dtype == np.bool_:
        test.assertEqual(list(values), [c == "true" for c in cells], name)
    else:
        test.assertEqual(list(values), cells, name)


class Continuation(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.branch = flexgait.rimless.continuation("rimless.slope", 0.05, 0.15, config=RIGID)
        cls.cli_dir = cli("rimless", "continuation", "--model", "rigid", "--param", "rimless.slope", "--from", "0.05",
                          "--to", "0.15")

    def test_the_branch_equals_the_command_lines_branch_csv(self):
        b, f = self.branch, read_csv(os.path.join(self.cli_dir, "branch.csv"))
        assert_column_equals_text(self, b["parameter"], f["parameter"], "parameter")
        for i, name in enumerate(b["state_names"]):
            assert_column_equals_text(self, b["state"][:, i], f[name], name)
        # |lambda| and arg(lambda) of the complex multipliers are the file's columns (to round-off of abs/arg: exact,
        # the file's are computed by the same std::abs and std::arg from the same complex numbers).
        self.assertEqual(b["multipliers"].dtype, np.complex128)
        np.testing.assert_array_equal(np.abs(b["multipliers"][:, 0]), [float(c) for c in f["abs_lambda_1"]])
        assert_column_equals_text(self, b["stable"], f["stable"], "stable")
        self.assertTrue(b["summary"]["reached_end"])
        self.assertGreater(b["summary"]["points"], 2)
        self.assertEqual(b["summary"]["param"], "rimless.slope")
        # The summary's events are the rows that carry one (the record `rimless continuation --json` prints).
        events = [(e["parameter"], e["event"], e["gait"]) for e in b["summary"]["events"]]
        self.assertEqual(events, [(float(p), e, g) for p, e, g in zip(b["parameter"], b["event"], b["gait"]) if e])
        self.assertIsNone(b["summary"]["failure"])

    def test_stable_means_every_multiplier_inside_the_unit_circle(self):
        b = self.branch
        np.testing.assert_array_equal(b["stable"], np.all(np.abs(b["multipliers"]) < 1, axis=1))

    def test_a_branch_point_is_the_fixed_point_newton_finds_at_its_slope(self):
        # Two algorithms on one map: the continuation's corrector and `rimless fixed-point`'s Newton both solve
        # P(z) = z to a residual of ~1e-12 (sim tolerances 1e-12), so the points agree to 1e-10.
        b = self.branch
        i = len(b["parameter"]) // 2
        slope = float(b["parameter"][i])
        fp_dir = cli("rimless", "fixed-point", "--model", "rigid", "--set", f"rimless.slope={slope!r}")
        fp = json.loads(read_text(os.path.join(fp_dir, "fixed_point.json")))
        self.assertTrue(fp["converged"])
        np.testing.assert_allclose(b["state"][i, :len(fp["state"])], fp["state"], rtol=0, atol=1e-10)

    def test_a_start_without_a_fixed_point_raises(self):
        with self.assertRaises(RuntimeError):  # the wheel rolls back: no gait at the start
            flexgait.rimless.continuation("rimless.slope", 0.05, 0.1, config={**RIGID, "initial.omega": -1})


class Basin(unittest.TestCase):
    def test_the_basin_equals_the_command_lines_and_converged_cells_reach_the_reference(self):
        b = flexgait.rimless.basin("initial.omega", (0.5, 2.0, 3), "initial.beta", "-0.3:-0.1:2", config=RIGID)
        f = read_csv(os.path.join(cli("rimless", "analysis", "basin", "--set", "sim.model=rigid", "--x",
                                      "initial.omega", "--y", "initial.beta", "--x-range", "0.5:2:3", "--y-range",
                                      "-0.3:-0.1:2"), "basin.csv"))
        for name in ("x", "y", "outcome", "gait", "steps", "distance", "failure"):
            assert_column_equals_text(self, b[name], f[name], name)
        self.assertEqual(b["converged"].shape, (2, 3))
        self.assertEqual(int(b["converged"].sum()), b["summary"]["outcomes"]["converged"])
        # A cell labelled converged: Newton started from its initial state finds the reference gait.
        cells = [i for i, o in enumerate(b["outcome"]) if o == "converged"]
        self.assertTrue(cells, b["outcome"])
        i = cells[0]
        fp = flexgait.rimless.fixed_point({**RIGID, "initial.omega": b["x"][i], "initial.beta": b["y"][i]})
        # tolerance: both are Newton's fixed point of the same map (residual ~1e-12)
        np.testing.assert_allclose(fp["state"], list(b["summary"]["reference"]["state"].values()), rtol=0, atol=1e-9)


class OrbitDiagram(unittest.TestCase):
    def test_the_orbit_diagram_equals_the_command_lines_and_settles_on_the_fixed_point(self):
        config = {**RIGID, "analysis.orbit.transient": 100, "analysis.orbit.record": 4}
        o = flexgait.rimless.orbit_diagram("rimless.slope", 0.06, 0.1, 2, config=config)
        f = read_csv(os.path.join(cli("rimless", "analysis", "orbit-diagram", "--set", "sim.model=rigid", "--param",
                                      "rimless.slope", "--from", "0.06", "--to", "0.1", "--count", "2",
                                      "--transient", "100", "--record", "4"), "orbit.csv"))
        for name in ("parameter", "step", "thetad", "gait", "failure"):
            assert_column_equals_text(self, o["crossings"][name], f[name], name)
        self.assertEqual(o["thetad"].shape, (2, 4))
        np.testing.assert_array_equal(o["thetad"].ravel(), o["crossings"]["thetad"])
        # The rigid wheel's gait is a stable period-1 orbit here: after 100 steps the crossings sit on
        # the fixed point (its multiplier, at most 0.73, shrinks the start's error 0.73^100 ~ 2e-14 times).
        for k, slope in enumerate(o["parameter"]):
            self.assertEqual(o["summary"]["values"][k]["distinct"], 1)
            fp = flexgait.rimless.fixed_point({**RIGID, "rimless.slope": slope})
            np.testing.assert_allclose(o["thetad"][k], fp["state"][0], rtol=0, atol=1e-9)


class GaitVsFriction(unittest.TestCase):
    def test_the_gaits_equal_the_command_lines_and_the_sweep_is_flexgait_rimless_sweep(self):
        # Two values of mu on either side of the rigid wheel's threshold between slip-stick and stick
        # (mu ~ 0.327), bisected to 1e-3 (the default 1e-8 takes seconds).
        config = {**RIGID, "analysis": {"friction": {"threshold_tol": 1e-3}}}
        given = json.dumps(config)
        g = flexgait.rimless.gait_vs_friction(0.3, 0.9, 2, config=config)
        self.assertEqual(json.dumps(config), given)  # the caller's dict is not changed
        d = cli("rimless", "analysis", "gait-vs-friction", "--set", "sim.model=rigid", "--set",
                "analysis.friction.threshold_tol=1e-3", "--from", "0.3", "--to", "0.9", "--count", "2")
        for table in ("gaits", "thresholds"):
            f = read_csv(os.path.join(d, table + ".csv"))
            for name, cells in f.items():
                assert_column_equals_text(self, g[table][name], cells, f"{table}.{name}")
        self.assertEqual(len(g["thresholds"]["threshold"]), 1)
        low, high = g["thresholds"]["mu_low"][0], g["thresholds"]["mu_high"][0]
        self.assertLessEqual(high - low, 1e-3)
        sweep = flexgait.rimless.sweep("rimless.mu", 0.3, 0.9, 2, config=RIGID)
        np.testing.assert_array_equal(g["sweep"]["speed"], sweep["speed"])
        np.testing.assert_array_equal(g["sweep"]["multipliers"], sweep["multipliers"])
        self.assertEqual(g["sweep"]["converged"].dtype, np.bool_)

    def test_a_failed_sweep_point_is_nan_not_text(self):
        s = flexgait.rimless.sweep("rimless.slope", 0.0, 0.08, 2, config={**RIGID, "initial.omega": 0.1})
        failed = ~s["converged"]
        self.assertTrue(failed.any(), s["failure"])
        self.assertTrue(np.isnan(s["speed"][failed]).all())
        self.assertTrue(np.isnan(s["state"][failed]).all())
        self.assertTrue(np.isnan(s["multipliers"][failed]).all())


class Stagnation(unittest.TestCase):
    def test_the_scan_equals_the_command_lines(self):
        config_file = os.path.join(SOURCE, "configs", "rimless-stagnation.yaml")
        keys = {"stagnation.count": 4, "stagnation.omega_from": 0.5, "stagnation.omega_to": 0.56,
                "stagnation.offset_min": 1e-3, "stagnation.per_decade": 1}
        s = flexgait.rimless.stagnation(keys, config_file=config_file)
        d = cli("rimless", "analysis", "stagnation", "--config", config_file, "--count", "4", "--from", "0.5", "--to",
                "0.56", "--set", "stagnation.offset_min=1e-3", "--set", "stagnation.per_decade=1")
        self.assertEqual(s["summary"], json.loads(read_text(os.path.join(d, "stagnation.json"))))
        self.assertTrue(s["summary"]["critical_found"])
        for name, cells in read_csv(os.path.join(d, "stagnation.csv")).items():
            assert_column_equals_text(self, s["stages"][name], cells, name)


class Campaign(unittest.TestCase):
    def test_the_points_equal_the_command_lines_campaign_csv(self):
        c = flexgait.campaign("rimless-fixed-point", {"rimless.mu": "0.3:0.9:2", "rimless.slope": [0.02, 0.1]},
                              config=RIGID)
        d = cli("campaign", "rimless-fixed-point", "--set", "sim.model=rigid", "--grid", "rimless.mu=0.3:0.9:2",
                "--grid", "rimless.slope=0.02,0.1")
        f = read_csv(os.path.join(d, "campaign.csv"))
        self.assertEqual(set(c["points"]), set(f))
        for name, cells in f.items():
            assert_column_equals_text(self, c["points"][name], cells, name)
        self.assertEqual(c["summary"]["points"], 4)
        # The slope 0.02 rolls back (no gait): NaN speed, converged False -- as bool, not text.
        self.assertEqual(c["points"]["converged"].dtype, np.bool_)
        self.assertTrue(np.isnan(c["points"]["speed"][~c["points"]["converged"]]).all())

    def test_a_bad_grid_key_is_a_value_error_naming_it(self):
        with self.assertRaisesRegex(ValueError, "rimless.nothing"):
            flexgait.campaign("rimless-fixed-point", {"rimless.nothing": [1, 2]})


class Humanoid(unittest.TestCase):
    def test_a_study_case_is_the_walk_of_its_configuration(self):
        config = {"walk.steps": 1, "walk.step_time": 0.6}
        study = flexgait.humanoid.compensation(config)
        self.assertEqual(set(study["runs"]), {row["case"] for row in study["summary"]["table"]})
        # The study's "off" case is `walk` with compensation off: the same numbers, to the bit.
        off = flexgait.humanoid.walk(config, compensation="off")["summary"]
        self.assertEqual(study["runs"]["off"], off)
        self.assertEqual(study["summary"]["pelvis_roll_error_max_off"], off["pelvis_roll_error_max"])

    def test_export_equals_the_command_lines_files(self):
        for fmt, name in (("mjcf", "robot.xml"), ("urdf", "robot.urdf")):
            e = flexgait.humanoid.export(fmt, file_name=name)
            work = tempfile.mkdtemp(prefix="flexgait-py-")
            out = os.path.join(work, name)
            subprocess.run([EXE, "humanoid", "export", "--format", fmt, "--out", out], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            self.assertEqual(e["text"], read_text(out), fmt)
            reload_yaml = read_text(os.path.splitext(out)[0] + ".yaml")
            self.assertEqual(reload_yaml.split("\n", 1)[1], e["config_yaml"])  # after its header comment
            self.assertEqual(e["config"]["robot.description"], name)

    def test_export_refuses_an_unknown_format(self):
        with self.assertRaisesRegex(ValueError, "sdf"):
            flexgait.humanoid.export("sdf")


if __name__ == "__main__":
    unittest.main()
