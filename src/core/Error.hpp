#pragma once
// Errors and exit codes. Every failure that reaches the user carries a message saying what,
// where and what to try; the exit code tells scripts which kind of failure it was.
#include <stdexcept>
#include <string>
#include <vector>

namespace gf {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,        // bad command line
  kExitInput = 3,        // bad case file (unknown key, wrong type, out of range, geometry)
  kExitRunFailure = 4,   // NaN, dt collapse, solver divergence during a run
  kExitIo = 5,           // cannot read or write a file (also a corrupt checkpoint)
  kExitInterrupted = 6,  // stopped by SIGINT/SIGTERM (after writing a checkpoint if it could)
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

// A PETSc call that returned an error code (GF_PETSC). what() is one line: the call, where,
// PETSc's own message of the error (kept by the handler of install_petsc_error_capture, which
// replaces PETSc's multi-line traceback) and its code. A std::runtime_error, so a caller that
// does not care about the kind still catches it.
class PetscFailure : public std::runtime_error {
 public:
  PetscFailure(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }
  // Codes PETSc raises for what a user gave it (an unknown type name, a value that is not a
  // number or is out of range, an unavailable factorization package, "incorrect user
  // input"): with user-given PETSc options, such a failure is an input error, not a bug.
  bool user_input_kind() const;

 private:
  int code_;
};

// Called by GF_PETSC: throws the PetscFailure of `code` for `call` at file:line.
[[noreturn]] void throw_petsc_failure(int code, const char* call, const char* file, int line);

// After PetscInitialize: PETSc errors are no longer printed as a traceback of every level;
// the first level's message is kept for the PetscFailure that GF_PETSC throws. Code that
// pushes its own handler (io/Checkpoint.cpp's QuietPetsc) is unaffected.
void install_petsc_error_capture();

// The PETSc options given (command line, solver.petsc_options, PETSC_OPTIONS) that nothing has
// read so far, as "-name value": after the solvers were set up and used once, a misspelled or
// misplaced option. Options PETSc itself reads only at the end (-log_view...) are left out.
std::vector<std::string> unused_petsc_options();

}  // namespace gf

// Check a PETSc error code inside a C++ function that returns void or a value: throws
// gf::PetscFailure.
#define GF_PETSC(call)                                                         \
  do {                                                                         \
    PetscErrorCode gf_ierr_ = (call);                                          \
    if (gf_ierr_) gf::throw_petsc_failure(static_cast<int>(gf_ierr_), #call,   \
                                          __FILE__, __LINE__);                 \
  } while (0)
