"""flexgait: legged locomotion with compliance, from Python.

The compiled core is flexgait._flexgait (pybind11); this package re-exports it, so that
`flexgait.rimless.simulate(...)`, `flexgait.HumanoidLoop(...)` and `import flexgait.rimless` work,
and ships its type stubs (PEP 561). help(flexgait._flexgait) documents every function.
"""
import sys as _sys

from . import _flexgait
from ._flexgait import *  # noqa: F401,F403  (the module has no private names to hide)
from ._flexgait import __version__, humanoid, rimless  # noqa: F401

__doc__ = _flexgait.__doc__

# The compiled submodules importable by name (`import flexgait.rimless`, `from flexgait.humanoid
# import walk`), as if they were files of the package.
for _name in ("rimless", "humanoid"):
    _sys.modules[__name__ + "." + _name] = getattr(_flexgait, _name)
del _name
