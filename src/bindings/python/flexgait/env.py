"""A Gymnasium-style environment over flexgait.HumanoidLoop.

Debian packages no gymnasium, so this adapter does not import it; it keeps Gymnasium's method
names and return values (reset -> (observation, info); step -> (observation, reward,
terminated, truncated, info)), so that code written for a gymnasium.Env runs on it and a thin
gymnasium.Env subclass can wrap it where gymnasium is installed.

    env = flexgait.env.HumanoidEnv({"walk.steps": 2})
    obs, info = env.reset(seed=1)
    obs, reward, terminated, truncated, info = env.step(env.initial_pose)   # or step(None): builtin
"""
from typing import Any, Callable, Mapping, Optional

import numpy as np

from . import HumanoidLoop

# The observation: what a controller reads (SensorReadings), flattened in this order.
OBSERVATION = (("encoder", 13), ("ft_force", 6), ("ft_torque", 6), ("imu_quat", 4), ("gyro", 3), ("accel", 3))


def observation(sensors) -> np.ndarray:
    """The sensors' readings as one float64 vector (OBSERVATION's order)."""
    return np.concatenate([np.ravel(getattr(sensors, name)) for name, _ in OBSERVATION])


def upright_reward(truth, period: float) -> float:
    """The default reward: the period's length [s] while only the soles touch the floor (time alive), else 0."""
    return 0.0 if truth.non_sole_contact else period


class HumanoidEnv:
    """The humanoid's closed loop as an environment: one control period per step.

    `action`: 13 joint commands [rad] (HumanoidLoop.joint_names order), or None for the builtin
    walking controller. terminated: a body other than a sole touches the floor (a fall), or the
    simulation failed (info["failure"] says why; reset() starts again). truncated: `max_time` [s]
    reached (default: the builtin plan's length). `reward(truth, period)` sees the ground truth.
    """

    def __init__(self, config: Optional[Mapping[str, Any]] = None, config_file: Optional[str] = None,
                 max_time: Optional[float] = None,
                 reward: Callable[[Any, float], float] = upright_reward):
        self.loop = HumanoidLoop(config, config_file)
        self.max_time = self.loop.duration if max_time is None else float(max_time)
        self.reward = reward
        self.observation_size = sum(n for _, n in OBSERVATION)
        self.action_size = len(self.loop.joint_names)

    @property
    def initial_pose(self) -> np.ndarray:
        return self.loop.initial_pose

    def reset(self, seed: Optional[int] = None, options: Optional[Mapping[str, Any]] = None):
        self.loop.reset(seed=seed)
        return observation(self.loop.sensors()), {"t": self.loop.time}

    def step(self, action):
        try:
            self.loop.step(None if action is None else np.asarray(action, dtype=float))
        except RuntimeError as failure:  # the twin failed: the episode ends here
            return observation(self.loop.sensors()), 0.0, True, False, {"t": self.loop.time, "failure": str(failure)}
        truth = self.loop.truth()
        terminated = bool(truth.non_sole_contact)
        truncated = not terminated and self.loop.time >= self.max_time - 0.5 * self.loop.period
        return (observation(self.loop.sensors()), float(self.reward(truth, self.loop.period)), terminated, truncated,
                {"t": self.loop.time})

    def render(self, width: int = 640, height: int = 480) -> np.ndarray:
        return self.loop.render(width, height)

    def close(self) -> None:
        pass
