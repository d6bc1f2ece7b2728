#include "core/Signal.hpp"

#include <csignal>
#include <initializer_list>
#include <cstdio>

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

}  // namespace gf::signal
