"""The flexgait package: its layout, its type stubs against the compiled module, and the
Gymnasium-style adapter (flexgait.env).

Run by ctest (python_package) with /usr/bin/python3; PYTHONPATH is the folder holding flexgait/.
"""
import ast
import os
import re
import unittest

import numpy as np

import flexgait
import flexgait.env
import flexgait.humanoid
import flexgait.rimless

PACKAGE = os.path.dirname(flexgait.__file__)


def stub_names(path):
    """{name: argument names (functions) or {member: argument names} (classes)} of a .pyi file's public top level."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read())

    def args(f):
        return [a.arg for a in f.args.args + f.args.kwonlyargs if a.arg != "self"]

    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
            out[node.name] = args(node)
        elif isinstance(node, ast.ClassDef):
            members = {}
            for m in node.body:
                if isinstance(m, ast.FunctionDef):
                    members[m.name] = args(m)
                elif isinstance(m, ast.AnnAssign):
                    members[m.target.id] = None
            out[node.name] = members
    return out


def runtime_args(function):
    """The argument names pybind11 wrote in the function's signature line ("name(a: T = d, b: U) -> R")."""
    first = function.__doc__.splitlines()[0]
    inside = first[first.index("(") + 1:first.rindex(") ->")]
    names = [re.match(r"\s*(\w+)", part).group(1) for part in re.split(r",(?![^\[]*\])", inside) if part.strip()]
    return [n for n in names if n != "self"]


class Layout(unittest.TestCase):
    def test_the_package_re_exports_the_compiled_module(self):
        self.assertTrue(flexgait.__file__.endswith("__init__.py"))
        self.assertEqual(os.path.dirname(flexgait._flexgait.__file__), PACKAGE)
        self.assertIs(flexgait.rimless, flexgait._flexgait.rimless)
        self.assertIs(flexgait.HumanoidLoop, flexgait._flexgait.HumanoidLoop)
        self.assertEqual(flexgait.__version__, flexgait._flexgait.__version__)
        from flexgait.rimless import simulate  # a submodule by name
        self.assertIs(simulate, flexgait._flexgait.rimless.simulate)

    def test_pep_561_marker_and_stubs_are_beside_the_module(self):
        for name in ("py.typed", "__init__.pyi", "rimless.pyi", "humanoid.pyi"):
            self.assertTrue(os.path.isfile(os.path.join(PACKAGE, name)), name)


class Stubs(unittest.TestCase):
    """The stubs declare what the module has, with the same argument names: a binding added or
    renamed without its stub fails here."""

    def check(self, stub, module, skip=()):
        declared = stub_names(os.path.join(PACKAGE, stub))
        public = {n for n in dir(module) if not n.startswith("_") and n not in skip}
        self.assertEqual(set(declared), public, stub)
        for name, spec in declared.items():
            thing = getattr(module, name)
            if isinstance(spec, dict):  # a class: its members, each method's arguments
                self.assertEqual(set(spec), {m for m in dir(thing) if not m.startswith("_")} | {"__init__"} & set(spec),
                                 name)
                for member, arguments in spec.items():
                    if (arguments is not None and member != "__init__"
                            and not isinstance(getattr(thing, member), property)):
                        self.assertEqual(runtime_args(getattr(thing, member)), arguments, f"{name}.{member}")
            else:
                self.assertEqual(runtime_args(thing), spec, name)

    def test_top_level(self):
        self.check("__init__.pyi", flexgait._flexgait, skip=("rimless", "humanoid"))

    def test_rimless(self):
        self.check("rimless.pyi", flexgait.rimless)

    def test_humanoid(self):
        self.check("humanoid.pyi", flexgait.humanoid)


class Env(unittest.TestCase):
    """flexgait.env.HumanoidEnv: Gymnasium's reset/step contract over HumanoidLoop."""

    def test_reset_and_step_follow_the_gymnasium_contract(self):
        env = flexgait.env.HumanoidEnv({"walk": {"steps": 2}}, max_time=0.05)
        obs, info = env.reset(seed=1)
        self.assertEqual(obs.shape, (env.observation_size,))
        self.assertEqual(info["t"], 0.0)
        # The observation is the sensors' readings: its first 13 are the encoders.
        np.testing.assert_array_equal(obs[:13], env.loop.sensors().encoder)
        steps, truncated = 0, False
        while not truncated:
            obs, reward, terminated, truncated, info = env.step(env.initial_pose)
            self.assertFalse(terminated)  # standing in the start pose: no fall
            self.assertEqual(reward, env.loop.period)  # the default reward: time alive
            steps += 1
        # truncated at max_time, to the period
        self.assertEqual(steps, round(0.05 / env.loop.period))

    def test_reset_with_a_seed_repeats_the_episode(self):
        env = flexgait.env.HumanoidEnv({"walk.steps": 2, "plant.noise.gyro": 0.01})
        runs = []
        for seed in (5, 5):
            env.reset(seed=seed)
            for _ in range(20):
                obs = env.step(None)[0]  # None: the builtin controller
            runs.append(obs)
        np.testing.assert_array_equal(runs[0], runs[1])

    def test_a_bad_action_raises_value_error(self):
        env = flexgait.env.HumanoidEnv({"walk.steps": 2})
        env.reset()
        with self.assertRaisesRegex(ValueError, "command"):
            env.step(np.zeros(3))


if __name__ == "__main__":
    unittest.main()
