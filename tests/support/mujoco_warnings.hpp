#pragma once
// Fails every test in which MuJoCo raised a warning (tests only).
//
// MuJoCo reports a warning (mj_warning: unstable simulation, NaN in qacc, too many contacts, ...)
// by counting it in mjData::warning and, the first time each kind occurs in an mjData, by calling
// mju_warning, which hands the message to the hook mju_user_warning (by default it prints and
// appends to MUJOCO_LOG.TXT in the working directory). Test code cannot reach every mjData the
// code under test creates, so the check installs that hook: a plain global function pointer,
// process-wide state in MuJoCo. That is acceptable here, and only here: a test program is one
// process that owns its main(), nothing in src/ sets the hook (the library must not: it would
// take it from the application), and the listener fails any test after which the hook is no
// longer ours. The records are guarded by a mutex, so warnings raised on worker threads count too.
#include <string>
#include <vector>

namespace flexgait::test_support {

/// Installs the hook (idempotent), registers the global Environment (a warning outside any test
/// fails the program at tear-down) and the listener (a warning during a test fails that test).
/// Call once from main(), after InitGoogleTest.
void install_mujoco_warning_check();

/// The warnings recorded since the last call, and forgets them.
std::vector<std::string> take_mujoco_warnings();

/// Adds a non-fatal failure to the current test for the warnings recorded since the last check
/// (and forgets them), or if the hook is no longer installed. The listener calls it at the end of
/// every test; a test may call it directly.
void check_no_mujoco_warnings();

}  // namespace flexgait::test_support
