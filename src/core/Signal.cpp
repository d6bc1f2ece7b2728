#include "core/Signal.hpp"

#include <pthread.h>

#include <cstdio>
#include <initializer_list>

namespace gf::signal {

namespace {
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop(int sig) {
  g_signal = sig;
  std::signal(sig, SIG_DFL);  // a second Ctrl-C stops at once
}
}  // namespace

void install_stop_handlers() {
  for (int sig : {SIGINT, SIGTERM}) {
    // Already received (before PetscInitialize): the second one takes the default action.
    if (g_signal == sig) {
      std::signal(sig, SIG_DFL);
      continue;
    }
    struct sigaction sa {};
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
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
