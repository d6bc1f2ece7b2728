/* granflow: the program a user runs. It only holds SIGINT and SIGTERM blocked and replaces
 * itself (execv) by granflow-core, the program proper, in the same folder.
 *
 * Why: granflow-core loads about a hundred shared libraries (PETSc, MPI, hypre, BLAS...),
 * which takes about 0.1 s before its main() can install the stop handler (core/Signal.hpp);
 * a SIGTERM in that window would kill it with exit 143 and nothing said. A blocked signal
 * stays pending across execv, so it reaches granflow-core's handler as soon as main() has
 * installed it and unblocked the signals: the run then stops cleanly (exit 6, with a message).
 * This launcher links only the C library, statically: it blocks the signals microseconds after
 * its execve.
 * The arguments are passed on unchanged (argv[0] too: the provenance shows the command typed). */
#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int main(int argc, char** argv) {
  (void)argc;
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  sigprocmask(SIG_BLOCK, &stop, NULL);

  char core[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", core, sizeof core - 32);
  if (n <= 0) {
    fprintf(stderr, "granflow: cannot find its own path (/proc/self/exe): %s\n", strerror(errno));
    return 70;
  }
  core[n] = '\0';
  char* slash = strrchr(core, '/');
  strcpy(slash ? slash + 1 : core, "granflow-core");
  execv(core, argv);
  fprintf(stderr, "granflow: cannot start %s: %s (build it with scripts/build.sh)\n", core,
          strerror(errno));
  return 70;
}
