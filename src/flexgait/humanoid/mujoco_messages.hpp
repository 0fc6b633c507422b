#pragma once
/// \file mujoco_messages.hpp
/// MuJoCo reports warnings and errors through two process-wide hooks (mju_user_warning,
/// mju_user_error). Left unset, it prints warnings on stdout (breaking `--json`) and appends
/// them to MUJOCO_LOG.TXT in the working directory, and on an error waits for Enter and exits.
/// A library must not take those hooks from its application, so nothing in flexgait's libraries
/// calls this; the applications (the command-line program, the Python module) call it once at start.
///
/// Warnings are counted per mjData in mjData::warning as well; the walk experiment reads that
/// count and ends a walk with a named failure at the first warning (walk_experiment.cpp).
#include <mujoco/mujoco.h>

#include <string>

namespace flexgait::humanoid {

/// Routes MuJoCo's warnings to stderr as one line "warning: MuJoCo: <text>" and its errors to
/// stderr as "error: MuJoCo: <text>" followed by exit status 1 (MuJoCo cannot continue after an
/// error: its caller's state is undefined). Nothing is written to MUJOCO_LOG.TXT. Idempotent.
void route_mujoco_messages_to_stderr();

/// The number of warnings counted in `d` so far (all kinds).
int mujoco_warning_count(const mjData* d);

/// The warnings counted in `d` so far, as one line ("" if none), e.g. "Nan, Inf or huge value
/// in QACC at DOF 0. The simulation is unstable. (3 times)"; kinds joined by "; ".
std::string mujoco_warnings_text(const mjData* d);

}  // namespace flexgait::humanoid
