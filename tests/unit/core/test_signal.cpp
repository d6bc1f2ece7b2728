// The polite stop on SIGINT/SIGTERM (core/Signal.hpp). Each check runs in a forked child, so that
// the process-wide handler state starts fresh and a kill is seen as the child's death, not
// this test's.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "core/Signal.hpp"

namespace {

int child_status(void (*body)()) {
  const pid_t pid = fork();
  if (pid == 0) {
    body();
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

}  // namespace

// Under mpirun a rank gets the stop twice at once (SLURM's SIGTERM to every process and mpirun's
// forward of it; the terminal's Ctrl-C and mpirun's): one stop, the rank lives on to checkpoint.
TEST(Signal, StopDeliveredTwiceAtOnceIsOneStop) {
  const int st = child_status([] {
    gf::signal::install_stop_handlers();
    std::raise(SIGTERM);
    std::raise(SIGTERM);
    std::raise(SIGINT);
    _exit(gf::signal::stop_signal() == SIGTERM ? 0 : 1);
  });
  ASSERT_TRUE(WIFEXITED(st)) << "the child was killed by signal " << WTERMSIG(st);
  EXPECT_EQ(WEXITSTATUS(st), 0) << "stop_signal() is not the first signal";
}

// A second stop well after the first is a user insisting: the default action, at once.
TEST(Signal, SecondStopAfterTwoSecondsKills) {
  const int st = child_status([] {
    gf::signal::install_stop_handlers();
    std::raise(SIGINT);
    std::this_thread::sleep_for(std::chrono::milliseconds(2200));
    std::raise(SIGINT);
    _exit(0);
  });
  ASSERT_TRUE(WIFSIGNALED(st)) << "the child lived through the second SIGINT";
  EXPECT_EQ(WTERMSIG(st), SIGINT);
}
