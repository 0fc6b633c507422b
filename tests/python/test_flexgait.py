"""The flexgait Python module against the command line and its own promises.

Run by ctest (the README's test command) with /usr/bin/python3; the environment gives
PYTHONPATH (the built module), FLEXGAIT_EXE (the command line) and FLEXGAIT_SOURCE (the tree).
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
import _thread
import unittest

import numpy as np

import flexgait

EXE = os.environ["FLEXGAIT_EXE"]
SOURCE = os.environ["FLEXGAIT_SOURCE"]
RIMLESS_YAML = os.path.join(SOURCE, "configs", "rimless.yaml")


class SimulateAgainstTheCommandLine(unittest.TestCase):
    def test_energy_balance_and_log_match_the_command_line_to_the_last_digit(self):
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([EXE, "rimless", "simulate", "--config", RIMLESS_YAML, "--set", "sim.steps=8",
                            "--out", out, "--no-plot"], check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(out, "summary.json")) as f:
                cli = json.load(f)
            with open(os.path.join(out, "log.csv")) as f:
                rows = list(csv.DictReader(f))
        run = flexgait.rimless.simulate({"sim.steps": 8}, config_file=RIMLESS_YAML)
        log, summary = run["log"], run["summary"]
        self.assertIsInstance(log["t"], np.ndarray)
        self.assertEqual(log["t"].dtype, np.float64)
        # The summary is the command line's, bit for bit (== on floats, no tolerance).
        self.assertEqual(summary, cli)
        self.assertEqual(summary["energy_balance_error"], cli["energy_balance_error"])
        # The arrays are the columns of log.csv, bit for bit, and the last row's energy ledger closes
        # as summary.json says.
        self.assertEqual(len(log["t"]), len(rows))
        self.assertEqual(list(log.keys()), list(rows[0].keys()))  # every column, in the file's order
        for name, values in log.items():  # numbers bit for bit, text as written
            if isinstance(values, np.ndarray):
                self.assertTrue(np.array_equal(values, np.array([float(r[name]) for r in rows])), name)
            else:
                self.assertEqual(values, [r[name] for r in rows], name)
        ledger = log["E_total"][-1] + log["W_damp"][-1] + log["W_fric"][-1]
        self.assertEqual(log["balance"][-1], float(rows[-1]["balance"]))
        self.assertLess(abs(ledger - cli["energy_initial"]) / cli["energy_initial"], 1e-8)

    def test_fixed_point_maps_to_itself(self):
        fp = flexgait.rimless.fixed_point({"rimless.mu_s": 0.6, "rimless.mu_k": 0.6})
        self.assertTrue(fp["converged"])
        self.assertEqual(fp["z"].shape, fp["jacobian"].shape[:1])
        step = flexgait.rimless.poincare_map({"rimless.mu_s": 0.6, "rimless.mu_k": 0.6}, z=fp["z"])
        self.assertIsNone(step["failure"])
        self.assertLess(np.max(np.abs(step["next"] - fp["z"])), 1e-9)


    def test_failed_fixed_point_is_named_and_has_no_numbers(self):
        # No starting point for Newton (the wheel rolls back; such a call segfaulted):
        # converged False, the failure named, None where a fixed point's numbers would be.
        fp = flexgait.rimless.fixed_point({"initial.omega": -1})
        self.assertFalse(fp["converged"])
        self.assertIn("no initial guess", fp["failure"])
        for key in ("z", "jacobian", "state", "multipliers", "gait", "period"):
            self.assertIsNone(fp[key], key)


class BadConfigFile(unittest.TestCase):
    """A configuration file read with limits; every refusal a ValueError naming the file."""

    def refused(self, text, needle):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "c.yaml")
            with open(path, "w") as f:
                f.write(text)
            with self.assertRaises(ValueError) as e:
                flexgait.rimless.simulate(config_file=path)
        self.assertIn(needle, str(e.exception))

    def test_recursive_alias(self):  # overflowed the stack
        self.refused("a: &a\n  b: *a\n", "c.yaml:2: a recursive alias")

    def test_duplicate_keys_and_extra_documents(self):
        self.refused("rimless:\n  K: 1\n  K: 2\n", "c.yaml:3: key 'K' given twice")
        self.refused("rimless:\n  K: 1\n---\nx: 1\n", "c.yaml:3: a second YAML document")

    def test_complex_key_is_a_value_error(self):  # was RuntimeError
        self.refused("? [a, b]\n: 1\n", "c.yaml:1: a key must be a plain name")

    def test_directory_and_fifo(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaises(ValueError) as e:  # was RuntimeError
                flexgait.rimless.simulate(config_file=d)
            self.assertIn("is a directory", str(e.exception))
            fifo = os.path.join(d, "fifo.yaml")
            os.mkfifo(fifo)
            with self.assertRaises(ValueError) as e:  # blocked forever
                flexgait.rimless.simulate(config_file=fifo)
            self.assertIn("not a regular file", str(e.exception))


class BadInput(unittest.TestCase):
    def test_unknown_key_raises_value_error_naming_it(self):
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"rimless.KK": 5})
        self.assertIn("rimless.KK", str(e.exception))

    def test_bad_value_raises_value_error_naming_the_key_and_domain(self):
        with self.assertRaises(ValueError) as e:
            flexgait.humanoid.walk({"control.compensation": "sometimes"})
        self.assertIn("control.compensation", str(e.exception))
        self.assertIn("off, input, output, both", str(e.exception))
        with self.assertRaises(ValueError) as e:
            flexgait.humanoid.walk(compensation="sometimes")
        self.assertIn("control.compensation", str(e.exception))
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.sweep("rimless.nope", 0.1, 0.2, 2)
        self.assertIn("rimless.nope", str(e.exception))

    def test_wrong_types_raise(self):
        with self.assertRaises(TypeError):
            flexgait.rimless.simulate(["rimless.K", 5])
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"rimless.K": [1, 2]})
        self.assertIn("rimless.K", str(e.exception))

    def test_numpy_scalars_are_numbers(self):  # numpy.int64 was once rejected
        run = flexgait.rimless.simulate({"sim.steps": np.int64(2), "rimless.mu_s": np.float32(0.5),
                                         "rimless.mu_k": np.float64(0.5)})
        self.assertEqual(run["config"]["sim.steps"], 2)
        self.assertEqual(run["config"]["rimless.mu_s"], float(np.float32(0.5)))

    def test_a_key_holding_an_equals_sign_is_a_key(self):  # was split at '=' and misread
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"rimless.K=5": 1000})
        self.assertIn("unknown key 'rimless.K=5'", str(e.exception))

    def test_none_and_nan_are_refused_naming_where(self):  # [None, 1, 2] became NaN, blamed "I = 0"
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.poincare_map(z=[None, 1.0, 2.0])
        self.assertIn("z:", str(e.exception))
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"rimless.K": float("nan")})
        self.assertIn("rimless.K", str(e.exception))
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"rimless.K": None})
        self.assertIn("rimless.K", str(e.exception))


class Humanoid(unittest.TestCase):
    def test_walk_returns_arrays_and_metrics_with_and_without_compensation(self):
        runs = {mode: flexgait.humanoid.walk({"walk.steps": 2, "walk.step_time": 3.0}, compensation=mode)
                for mode in ("off", "both")}
        for mode, run in runs.items():
            self.assertFalse(run["summary"]["fell"])
            self.assertEqual(run["summary"]["compensation"], mode)
            self.assertEqual(len(run["log"]["t"]), len(run["joints"]["l_hip_roll_link"]))
        self.assertLess(runs["both"]["summary"]["pelvis_roll_error_max"],
                        0.3 * runs["off"]["summary"]["pelvis_roll_error_max"])

    def test_walk_arrays_are_the_command_lines_files_to_the_last_digit(self):
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([EXE, "humanoid", "walk", "--set", "walk.steps=1", "--out", out, "--no-plot"], check=True,
                           stdout=subprocess.DEVNULL)
            files = {}
            for name in ("log", "joints"):
                with open(os.path.join(out, name + ".csv")) as f:
                    files[name] = list(csv.DictReader(f))
        run = flexgait.humanoid.walk({"walk.steps": 1})
        for name, rows in files.items():
            self.assertEqual(list(run[name].keys()), list(rows[0].keys()), name)  # every column, in order
            for column, values in run[name].items():
                self.assertTrue(np.array_equal(values, np.array([float(r[column]) for r in rows])), column)

    def test_bench_fits_the_stiffness(self):
        b = flexgait.humanoid.bench({"bench.poses": 7})
        self.assertLess(abs(b["summary"]["k_fit"] / b["summary"]["k_true"] - 1), 0.01)
        self.assertEqual(len(b["samples"]["encoder"]), 14)


class Caps(unittest.TestCase):
    """The command line's caps hold here too."""

    def test_sweep_count_is_capped_as_on_the_command_line(self):  # `rimless sweep --count` allows 1..10^6
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.sweep("rimless.mu", 0.3, 0.6, 1000001)
        self.assertIn("count: 1000001 is not in [1, 1000000]", str(e.exception))

    def test_the_logs_projected_size_is_capped(self):  # 1e-6 s over 120 s: ~5e10 bytes of log in memory
        with self.assertRaises(ValueError) as e:
            flexgait.rimless.simulate({"sim.sample_dt": 1e-6})
        self.assertIn("sim.max_log_bytes", str(e.exception))


class Interrupt(unittest.TestCase):
    """Ctrl-C stops a long call with KeyboardInterrupt. _thread.interrupt_main() trips the flag a
    SIGINT trips; the call, running C++ with the GIL released, sees it at its next check."""

    def interrupted(self, call):
        timer = threading.Timer(0.3, _thread.interrupt_main)
        timer.start()
        try:
            with self.assertRaises(KeyboardInterrupt):
                call()  # each runs for many seconds uninterrupted
        finally:
            timer.cancel()

    def test_sweep(self):
        self.interrupted(lambda: flexgait.rimless.sweep("rimless.mu", 0.3, 0.6, 100000))

    def test_simulate(self):
        self.interrupted(lambda: flexgait.rimless.simulate(
            {"sim.model": "rigid", "sim.steps": 100000, "sim.max_time": 1e5, "sim.sample_dt": 10}))

    def test_walk(self):
        self.interrupted(lambda: flexgait.humanoid.walk({"walk.steps": 400}))

    # 100,000 transient steps (with the simulated-time limit lifted) before Newton: minutes.
    long_transient = {"analysis.transient_steps": 100000, "sim.max_time": 1e6}

    def test_fixed_point(self):
        self.interrupted(lambda: flexgait.rimless.fixed_point(self.long_transient))

    def test_fixed_point_of_the_rigid_wheel(self):  # many short runs: each one checks at its start
        self.interrupted(lambda: flexgait.rimless.fixed_point(dict(self.long_transient, **{"sim.model": "rigid"})))

    def test_poincare_map(self):
        self.interrupted(lambda: flexgait.rimless.poincare_map(self.long_transient))

    def test_within_one_sweep_point(self):
        self.interrupted(lambda: flexgait.rimless.sweep("rimless.mu", 0.5, 0.5, 1, self.long_transient))

    def test_bench(self):
        self.interrupted(lambda: flexgait.humanoid.bench({"bench.poses": 10000, "bench.settle_time": 100}))


class Threads(unittest.TestCase):
    def test_the_gil_is_released_during_a_sweep(self):
        # While a sweep runs in a worker thread, this thread keeps running Python.
        window = {}

        def work():
            window["start"] = time.perf_counter()
            flexgait.rimless.sweep("rimless.mu", 0.3, 0.6, 24)  # long enough (> 0.2 s) with dop853
            window["end"] = time.perf_counter()

        worker = threading.Thread(target=work)
        ticks = []
        worker.start()
        while worker.is_alive():
            ticks.append(time.perf_counter())
            time.sleep(0.001)
        worker.join()
        inside = [t for t in ticks if window["start"] + 0.05 < t < window["end"] - 0.05]
        self.assertGreater(window["end"] - window["start"], 0.2)
        self.assertGreater(len(inside), 10)


class Documentation(unittest.TestCase):
    def test_every_function_has_a_docstring(self):
        for module in (flexgait, flexgait.rimless, flexgait.humanoid):
            self.assertTrue(module.__doc__)
            for name in dir(module):
                obj = getattr(module, name)
                if callable(obj) and not name.startswith("_"):
                    self.assertTrue(obj.__doc__ and len(obj.__doc__) > 60, f"{module.__name__}.{name}")

    def test_defaults_and_describe_cover_the_schema(self):
        d = flexgait.defaults("walk")
        self.assertEqual(d["control.compensation"], "both")
        self.assertEqual(d["plant.k_joint"], 1000.0)
        self.assertEqual(set(flexgait.describe("walk")), set(d))


class Examples(unittest.TestCase):
    def run_example(self, script, png, *args):
        with tempfile.TemporaryDirectory() as out:
            subprocess.run([sys.executable, os.path.join(SOURCE, "examples", script), out, *args], check=True,
                           stdout=subprocess.DEVNULL, env=dict(os.environ))
            path = os.path.join(out, png)
            self.assertTrue(os.path.getsize(path) > 10000)
            with open(path, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_rimless_gait_vs_friction(self):
        self.run_example("rimless_gait_vs_friction.py", "rimless_gait_vs_friction.png", "8")

    def test_pelvis_error_compensation(self):
        self.run_example("pelvis_error_compensation.py", "pelvis_error_compensation.png", "1")


if __name__ == "__main__":
    unittest.main()
