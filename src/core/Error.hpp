#pragma once
// Errors and exit codes. Every failure that reaches the user carries a message saying what,
// where and what to try; the exit code tells scripts which kind of failure it was.
#include <stdexcept>
#include <string>

namespace gf {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,        // bad command line
  kExitInput = 3,        // bad case file (unknown key, wrong type, out of range, geometry)
  kExitRunFailure = 4,   // NaN, dt collapse, solver divergence during a run
  kExitIo = 5,           // cannot read or write a file (also a corrupt checkpoint)
  kExitInterrupted = 6,  // stopped by SIGINT/SIGTERM after writing a checkpoint: restartable
  kExitInternal = 70,
};

// An error in the user's input, found before any computation.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that went wrong (NaN, CFL blow-up, solver divergence).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run stopped on request (SIGINT/SIGTERM) after it wrote its checkpoint and diagnostics:
// not a failure, but the results are incomplete, so the exit code (kExitInterrupted) differs.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gf

// Check a PETSc error code inside a C++ function that returns void or a value: throws.
#define GF_PETSC(call)                                                                    \
  do {                                                                                    \
    PetscErrorCode gf_ierr_ = (call);                                                     \
    if (gf_ierr_) throw std::runtime_error(std::string("PETSc error ") +                  \
                                           std::to_string(static_cast<int>(gf_ierr_)) +   \
                                           " in " #call " at " __FILE__ ":" +             \
                                           std::to_string(__LINE__));                     \
  } while (0)
