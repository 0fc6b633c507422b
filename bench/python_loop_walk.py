#!/usr/bin/env python3
"""A 10-step walk stepped one control period at a time from Python with the builtin controller.

Timed as a whole process against `flexgait humanoid walk` (the same walk in C++, with its files)
by farm-bench:
    farm-bench -n 5 --vs 'build/release/src/cli/flexgait humanoid walk --no-plot --out /tmp/w' -- \
        env PYTHONPATH=build/release/src/bindings/python python3 bench/python_loop_walk.py
"""
import flexgait

loop = flexgait.HumanoidLoop({"walk": {"steps": 10}})
end = loop.duration - 0.5 * loop.period
while loop.time < end:
    loop.step()
truth = loop.truth()
print(f"t = {truth.t:.3f} s, pelvis at ({truth.pelvis_pos[0]:.3f}, {truth.pelvis_pos[1]:.3f}, {truth.pelvis_pos[2]:.3f}) m")
