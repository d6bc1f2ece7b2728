#include "core/Signal.hpp"

#include <pthread.h>

#include <cstdio>
#include <ctime>
#include <initializer_list>

namespace gf::signal {

namespace {
volatile std::sig_atomic_t g_signal = 0;
// When the first one came (CLOCK_MONOTONIC). Written and read by the handler only, which never
// runs nested (both signals are in its sa_mask).
timespec g_first{};

// A second stop within this window is the first one delivered twice, not a user insisting:
// under mpirun a rank gets the terminal's Ctrl-C and mpirun's forward of it, and SLURM at its
// limit (without --signal) sends SIGTERM to every process, mpirun included, which forwards it
// again. Killing the rank on that copy lost the stop's checkpoint (seen: case B at 768 x 256 on
// 2 ranks, SIGTERM to mpirun and both ranks: no message, checkpoint.tmp left half-written).
constexpr double kRepeatWindowSeconds = 2.0;

extern "C" void on_stop(int sig) {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe (POSIX)
  if (g_signal == 0) {
    g_first = now;
    g_signal = sig;
    return;
  }
  const double since = static_cast<double>(now.tv_sec - g_first.tv_sec) +
                       1e-9 * static_cast<double>(now.tv_nsec - g_first.tv_nsec);
  if (since < kRepeatWindowSeconds) return;
  // A second stop later than that: the default action at once (a second Ctrl-C kills).
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
}  // namespace

void install_stop_handlers() {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction sa {};
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    sa.sa_flags = SA_RESTART;  // system calls (file writes, MPI progress) resume after it
    sigaction(sig, &sa, nullptr);
  }
}

int stop_signal() { return g_signal; }

const char* name(int sig) {
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  static char buf[24];
  std::snprintf(buf, sizeof buf, "signal %d", sig);
  return buf;
}

void unblock() {
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGINT);
  sigaddset(&s, SIGTERM);
  pthread_sigmask(SIG_UNBLOCK, &s, nullptr);
}

Blocked::Blocked() {
  sigset_t s;
  sigemptyset(&s);
  sigaddset(&s, SIGINT);
  sigaddset(&s, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &s, &old_);
}

Blocked::~Blocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

}  // namespace gf::signal
