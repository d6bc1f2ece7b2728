#pragma once
// A polite stop on SIGINT (Ctrl-C) and SIGTERM (the batch system's "your time is up"): the
// handler only records the signal (async-signal-safe: one sig_atomic_t store and the time). A
// second signal more than 2 s after the first kills the process at once; one within 2 s is
// taken for the same stop delivered twice (under mpirun: the terminal's and mpirun's forward, or
// SLURM's SIGTERM to every process and mpirun's forward) and ignored. The time loop polls
// stop_signal() after each step, agrees on it across ranks, writes a checkpoint and the
// diagnostics, and exits with kExitInterrupted (core/Error.hpp); the start-up of a run polls
// it too, between its stages, so that a signal at any time after main() begins stops the run
// cleanly.
//
// apps/ installs the handlers first thing in main() (the launcher apps/launcher.c holds the
// signals blocked until then, while the libraries load), then holds the two signals blocked
// during PetscInitialize (which installs PETSc's own SIGTERM handler, an abort with a stack
// trace), installs them again and unblocks: a signal that arrived meanwhile is delivered to
// this handler then, not lost and not an abort.
#include <csignal>

namespace gf::signal {

void install_stop_handlers();
// The signal number received (SIGINT or SIGTERM), 0 if none. This rank only.
int stop_signal();
// "SIGINT", "SIGTERM" or "signal N".
const char* name(int sig);

// Unblocks SIGINT and SIGTERM (held blocked by the launcher, apps/launcher.c): a pending one is
// delivered at once. Call after install_stop_handlers().
void unblock();

// While alive, SIGINT and SIGTERM are blocked (held pending) in this thread and the threads
// it starts.
class Blocked {
 public:
  Blocked();
  ~Blocked();
  Blocked(const Blocked&) = delete;
  Blocked& operator=(const Blocked&) = delete;

 private:
  sigset_t old_{};
};

}  // namespace gf::signal
