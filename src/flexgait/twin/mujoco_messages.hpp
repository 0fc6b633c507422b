#pragma once
/// \file mujoco_messages.hpp
/// MuJoCo reports warnings and errors through two process-wide hooks (mju_user_warning,
/// mju_user_error). Left unset, it prints warnings on stdout (breaking `--json`) and appends
/// them to MUJOCO_LOG.TXT in the working directory, and on an error waits for Enter and exits.
/// A library must not take those hooks from its application, so nothing in flexgait's libraries
/// calls this; the applications (the command-line program, the Python module) call it once at start.
///
/// Warnings are counted per mjData in mjData::warning as well; the plant reports that count and
/// its text (GroundTruth::warnings, HumanoidPlant::warnings_text), and the walk experiment ends a
/// walk with a named failure at the first warning (walk_experiment.cpp).

namespace flexgait::twin {

/// Routes MuJoCo's warnings to stderr as one line "warning: MuJoCo: <text>" and its errors to
/// stderr as "error: MuJoCo: <text>" followed by exit status 1 (MuJoCo cannot continue after an
/// error: its caller's state is undefined). Nothing is written to MUJOCO_LOG.TXT. Idempotent.
void route_mujoco_messages_to_stderr();

/// Whether MuJoCo's message hooks are set (by route_mujoco_messages_to_stderr or by anyone else,
/// e.g. MuJoCo's own Python bindings in the same process).
bool mujoco_messages_hooked();

}  // namespace flexgait::twin
