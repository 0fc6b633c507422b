# flexgait.rimless: the flexible-leg rimless wheel (stubs; see help(flexgait.rimless)).
from typing import Any, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Config = Optional[Mapping[str, Any]]
_Range = Union[str, Sequence[float]]

def simulate(config: _Config = None, config_file: Optional[str] = None) -> dict[str, Any]: ...
def fixed_point(config: _Config = None, config_file: Optional[str] = None, section: str = "touchdown") -> dict[str, Any]: ...
def poincare_map(
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
    z: Optional[npt.NDArray[np.float64]] = None,
) -> dict[str, Any]: ...
def sweep(
    param: str,
    start: float,
    stop: float,
    count: int,
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
) -> dict[str, Any]: ...
def continuation(
    param: str,
    start: float,
    stop: float,
    step: float = 0.0,
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
    period: int = 1,
    switch_at_period_doubling: bool = False,
) -> dict[str, Any]: ...
def basin(
    x: str,
    x_range: _Range,
    y: str,
    y_range: _Range,
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
) -> dict[str, Any]: ...
def orbit_diagram(
    param: str,
    start: float,
    stop: float,
    count: int,
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
) -> dict[str, Any]: ...
def gait_vs_friction(
    start: Optional[float] = None,
    stop: Optional[float] = None,
    count: Optional[int] = None,
    config: _Config = None,
    config_file: Optional[str] = None,
    section: str = "touchdown",
) -> dict[str, Any]: ...
def stagnation(config: _Config = None, config_file: Optional[str] = None) -> dict[str, Any]: ...
