#pragma once
// The Krylov solvers of granflow (PETSc KSP), built one way: an options prefix (-pres_ for the
// pressure Poisson problem of eq. 32, -visc_ for the viscous operator of eq. 31), a default
// method and preconditioner that any -<prefix>ksp_type / -<prefix>pc_type overrides at run time
// (KSPSetFromOptions is called last), a relative tolerance, and a check of every solve: a solve
// that diverged is a RunError naming the solver, the PETSc reason, the iterations and what to try.
//
// CG needs a symmetric positive definite preconditioner. BoomerAMG on the singular (Neumann)
// pressure operator is one in practice but not always (HP case B at n = 64 met
// DIVERGED_INDEFINITE_PC at t = 1.58 s); with `gmres_fallback` a CG solve that breaks down is
// solved again from zero with GMRES and the same preconditioner (counted: fell_back()), and CG
// stays the method of the next solve.
#include <petscksp.h>

#include <optional>
#include <string>

namespace gf::linsolve {

struct KrylovSetup {
  std::string prefix;          // options prefix, e.g. "pres_"
  KSPType type = KSPCG;        // default method
  PCType pc = PCJACOBI;        // default preconditioner
  std::optional<double> rtol;  // relative tolerance (absolute 1e-50, at most 1000 iterations)
  bool nonzero_guess = false;  // start from the x given to solve()
  bool gmres_fallback = false;
  std::string what;  // "viscous solve (prefix -visc_)": the start of failure messages
  std::string hint;  // what to try when it diverges
};

class Krylov {
 public:
  Krylov(MPI_Comm comm, KrylovSetup setup);
  ~Krylov();
  Krylov(const Krylov&) = delete;
  Krylov& operator=(const Krylov&) = delete;

  KSP ksp() const { return ksp_; }
  // The operator (also the preconditioning matrix); its preconditioner is rebuilt at the next
  // solve.
  void set_operator(Mat A);
  // Solves A x = b (x holds the initial guess with nonzero_guess). Returns the KSP iterations
  // (both solves with a fallback); throws RunError if it diverged.
  int solve(Vec b, Vec x);
  bool fell_back() const { return fell_back_; }

 private:
  KrylovSetup setup_;
  KSP ksp_ = nullptr;
  bool fell_back_ = false;
};

}  // namespace gf::linsolve
