#pragma once
// A polite stop on SIGINT (Ctrl-C) and SIGTERM (the batch system's "your time is up"): the
// handler only records the signal (async-signal-safe: one sig_atomic_t store) and puts the
// default action back, so a second signal kills the process at once. The time loop polls
// stop_signal() after each step, agrees on it across ranks, writes a checkpoint and the
// diagnostics, and exits with kExitInterrupted (core/Error.hpp).
//
// install_stop_handlers() must run after PetscInitialize, which installs PETSc's own handler
// for SIGTERM (an abort with a stack trace) that this one replaces.

namespace gf::signal {

void install_stop_handlers();
// The signal number received (SIGINT or SIGTERM), 0 if none. This rank only.
int stop_signal();
// "SIGINT", "SIGTERM" or "signal N".
const char* name(int sig);

}  // namespace gf::signal
