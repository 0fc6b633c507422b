"""flexgait.HumanoidLoop and flexgait.Controller: the humanoid's closed loop stepped from Python.

Run by ctest (python_loop) with /usr/bin/python3; PYTHONPATH gives the built module.
"""
import sys
import threading
import unittest

import numpy as np

import flexgait

TWO_STEPS = {"walk.steps": 2}


def tilt(truth):
    """The pelvis's tilt from vertical [rad]."""
    w, x, y, z = truth.pelvis_quat
    return float(np.arccos(np.clip(1.0 - 2.0 * (x * x + y * y), -1.0, 1.0)))


class AnklePD(flexgait.Controller):
    """A hand-written controller: holds the start pose and rights the pelvis with the ankles (a PD
    on the IMU's roll and pitch)."""

    def __init__(self, pose, names, kp=0.5, kd=0.05):
        super().__init__()
        self.pose = np.array(pose)
        self.kp, self.kd = kp, kd
        self.roll = [names.index(n) for n in names if n.endswith("ankle_roll")]
        self.pitch = [names.index(n) for n in names if n.endswith("ankle_pitch")]

    def update(self, sensors, t):
        w, x, y, z = sensors.imu_quat
        roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1, 1))
        q = self.pose.copy()
        # feet flat: turning an ankle by +d turns the pelvis by -d about the foot
        q[self.roll] += self.kp * roll + self.kd * sensors.gyro[0]
        q[self.pitch] += self.kp * pitch + self.kd * sensors.gyro[1]
        return q


class MoveOneJoint(flexgait.Controller):
    def __init__(self, pose, joint, delta):
        super().__init__()
        self.q = np.array(pose)
        self.q[joint] += delta

    def update(self, sensors, t):
        return self.q


class WrongShape(flexgait.Controller):
    def update(self, sensors, t):
        return np.zeros(3)


class Stepping(unittest.TestCase):
    def test_reset_with_a_seed_is_deterministic(self):
        loop = flexgait.HumanoidLoop({**TWO_STEPS, "plant.noise.gyro": 0.01})
        runs = []
        for seed in (3, 3, 4):
            loop.reset(seed=seed)
            for _ in range(200):
                loop.step()
            runs.append((loop.truth().link_angle, loop.sensors().gyro))
        np.testing.assert_array_equal(runs[0][0], runs[1][0])  # the same seed: the same bits
        np.testing.assert_array_equal(runs[0][1], runs[1][1])
        self.assertFalse(np.array_equal(runs[0][1], runs[2][1]))  # another seed: other sensor noise

    def test_step_by_step_equals_run(self):
        a, b = flexgait.HumanoidLoop(TWO_STEPS), flexgait.HumanoidLoop(TWO_STEPS)
        while a.time < 1.0 - 0.5 * a.period:
            a.step()
        b.run(until=1.0)
        self.assertEqual(a.time, b.time)
        np.testing.assert_array_equal(a.truth().link_angle, b.truth().link_angle)

    def test_the_builtin_controller_walks_two_steps(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS)
        loop.run()
        truth = loop.truth()
        self.assertGreater(truth.pelvis_pos[2], 0.5)
        self.assertLess(tilt(truth), 0.2)
        self.assertTrue(all(truth.sole_contact))

    def test_nested_dicts_are_keys(self):
        nested = flexgait.HumanoidLoop({"walk": {"steps": 2}, "control": {"compensation": "off"}})
        self.assertEqual(nested.config["walk.steps"], 2)
        self.assertEqual(nested.config["control.compensation"], "off")
        self.assertEqual(nested.duration, flexgait.HumanoidLoop(TWO_STEPS).duration)

    def test_records_are_typed(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS)
        self.assertEqual(len(flexgait.HumanoidLoop.joint_names), 13)
        s, g = loop.sensors(), loop.truth()
        self.assertEqual(s.encoder.shape, (13,))
        self.assertEqual(s.ft_force.shape, (2, 3))
        self.assertEqual(g.sole_pos.shape, (2, 3))
        self.assertIsInstance(g.non_sole_contact, bool)
        loop.step()  # (the contacts are found by the first step)
        self.assertEqual(loop.truth().sole_contact, [True, True])


class YourController(unittest.TestCase):
    def test_a_python_pd_keeps_the_twin_standing_ten_seconds(self):
        probe = flexgait.HumanoidLoop(TWO_STEPS)
        controller = AnklePD(probe.initial_pose, flexgait.HumanoidLoop.joint_names)
        loop = flexgait.HumanoidLoop(TWO_STEPS, controller=controller)
        z0 = loop.truth().pelvis_pos[2]
        loop.run(until=10.0)
        truth = loop.truth()
        self.assertAlmostEqual(truth.t, 10.0, delta=1e-9)
        self.assertLess(abs(truth.pelvis_pos[2] - z0), 0.02)  # the gears' sag, not a fall (0.2 m)
        self.assertLess(tilt(truth), 0.05)
        self.assertFalse(truth.non_sole_contact)

    def test_a_python_controllers_commands_reach_the_plant(self):
        probe = flexgait.HumanoidLoop(TWO_STEPS)
        knee = flexgait.HumanoidLoop.joint_names.index("l_knee")
        loop = flexgait.HumanoidLoop({**TWO_STEPS, "control.compensation": "off"},
                                     controller=MoveOneJoint(probe.initial_pose, knee, 0.1))
        loop.run(until=1.0)
        # compensation off: the command passes unchanged; the motor-side encoder follows it
        self.assertEqual(loop.command()[knee], probe.initial_pose[knee] + 0.1)
        self.assertAlmostEqual(loop.sensors().encoder[knee], probe.initial_pose[knee] + 0.1, delta=5e-3)

    def test_a_given_command_reaches_the_plant(self):
        loop = flexgait.HumanoidLoop({**TWO_STEPS, "control.compensation": "off"})
        q = loop.initial_pose.copy()
        knee = flexgait.HumanoidLoop.joint_names.index("r_knee")
        q[knee] += 0.1
        for _ in range(250):
            loop.step(q)
        self.assertAlmostEqual(loop.sensors().encoder[knee], q[knee], delta=5e-3)


class BadUse(unittest.TestCase):
    def test_wrong_shapes_and_nan_raise_value_error_naming_the_argument(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS)
        with self.assertRaisesRegex(ValueError, "command: expected 13"):
            loop.step(np.zeros(12))
        with self.assertRaisesRegex(ValueError, "command: expected 13"):
            loop.step("knees")
        q = loop.initial_pose.copy()
        q[4] = np.nan
        with self.assertRaisesRegex(ValueError, "command: joint 4 .* is nan"):
            loop.step(q)
        self.assertEqual(loop.time, 0.0)  # nothing moved
        with self.assertRaisesRegex(ValueError, "seed"):
            loop.reset(seed=-1)

    def test_a_controller_returning_a_wrong_shape_raises(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS, controller=WrongShape())
        with self.assertRaisesRegex(ValueError, "Controller.update's return: expected 13"):
            loop.step()

    def test_a_controller_without_update_raises(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS, controller=flexgait.Controller())
        with self.assertRaises(Exception):
            loop.step()

    def test_use_after_a_failed_step_raises_until_reset(self):
        # Gears 10^5 times stiffer than THORMANG's, undamped, at the longest physics step: the
        # explicit integration of the gears is unstable and MuJoCo warns in the first period.
        unstable = {**TWO_STEPS, "plant.k_joint": 1e8, "plant.gear_damping": 0, "plant.physics_dt": 0.002}
        loop = flexgait.HumanoidLoop(unstable)
        with self.assertRaisesRegex(RuntimeError, "the simulation failed at t = .*: mujoco_warning"):
            loop.step()
        with self.assertRaisesRegex(RuntimeError, "reset the loop"):
            loop.step()
        loop.reset()  # a new twin: it steps (and fails) again, rather than refusing
        with self.assertRaisesRegex(RuntimeError, "the simulation failed"):
            loop.step()


class Threads(unittest.TestCase):
    def test_two_loops_step_in_parallel_with_the_gil_released(self):
        # With a switch interval far longer than the test, this thread runs only while the workers
        # have released the GIL (a worker that kept it through run() would finish first): it counts
        # to 10^5 while both workers are still stepping.
        loops = [flexgait.HumanoidLoop(TWO_STEPS), flexgait.HumanoidLoop(TWO_STEPS)]
        old = sys.getswitchinterval()
        sys.setswitchinterval(100.0)
        try:
            threads = [threading.Thread(target=loop.run, kwargs={"until": 1.0}) for loop in loops]
            for t in threads:
                t.start()
            count = 0
            while count < 100000 and any(t.is_alive() for t in threads):
                count += 1
            overlapped = all(t.is_alive() for t in threads)
            for t in threads:
                t.join()
        finally:
            sys.setswitchinterval(old)
        self.assertTrue(overlapped, f"the workers ended before this thread counted to {count}")
        self.assertEqual(loops[0].time, loops[1].time)
        np.testing.assert_array_equal(loops[0].truth().link_angle, loops[1].truth().link_angle)


class Render(unittest.TestCase):
    def test_render_is_an_rgb_image_of_the_twin(self):
        loop = flexgait.HumanoidLoop(TWO_STEPS)
        image = loop.render(160, 120)
        self.assertEqual(image.shape, (120, 160, 3))
        self.assertEqual(image.dtype, np.uint8)
        self.assertGreater(image.std(), 5.0)  # a picture, not a blank
        with self.assertRaisesRegex(ValueError, "width and height"):
            loop.render(0, 10)


if __name__ == "__main__":
    unittest.main()
