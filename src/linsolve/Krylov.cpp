#include "linsolve/Krylov.hpp"

#include <string>
#include <utility>

#include "core/Error.hpp"

namespace gf::linsolve {

Krylov::Krylov(MPI_Comm comm, KrylovSetup setup) : setup_(std::move(setup)) {
  GF_PETSC(KSPCreate(comm, &ksp_));
  GF_PETSC(KSPSetOptionsPrefix(ksp_, setup_.prefix.c_str()));
  GF_PETSC(KSPSetType(ksp_, setup_.type));
  PC pc;
  GF_PETSC(KSPGetPC(ksp_, &pc));
  GF_PETSC(PCSetType(pc, setup_.pc));
  if (setup_.rtol) GF_PETSC(KSPSetTolerances(ksp_, *setup_.rtol, 1e-50, PETSC_DEFAULT, 1000));
  if (setup_.nonzero_guess) GF_PETSC(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  GF_PETSC(KSPSetFromOptions(ksp_));
}

Krylov::~Krylov() { KSPDestroy(&ksp_); }

void Krylov::set_operator(Mat A) { GF_PETSC(KSPSetOperators(ksp_, A, A)); }

int Krylov::solve(Vec b, Vec x) {
  GF_PETSC(KSPSolve(ksp_, b, x));
  KSPConvergedReason reason;
  PetscInt its;
  GF_PETSC(KSPGetConvergedReason(ksp_, &reason));
  GF_PETSC(KSPGetIterationNumber(ksp_, &its));
  fell_back_ = false;
  if (setup_.gmres_fallback) {
    KSPType type;
    GF_PETSC(KSPGetType(ksp_, &type));
    const bool cg = std::string(type) == KSPCG;
    if (cg && (reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_BREAKDOWN)) {
      GF_PETSC(KSPSetType(ksp_, KSPGMRES));
      GF_PETSC(VecSet(x, 0.0));
      GF_PETSC(KSPSolve(ksp_, b, x));
      PetscInt its2;
      GF_PETSC(KSPGetConvergedReason(ksp_, &reason));
      GF_PETSC(KSPGetIterationNumber(ksp_, &its2));
      GF_PETSC(KSPSetType(ksp_, KSPCG));
      its += its2;
      fell_back_ = true;
    }
  }
  if (reason < 0)
    throw RunError(setup_.what + " did not converge: " + std::string(KSPConvergedReasons[reason]) +
                   " after " + std::to_string(its) + " iterations" +
                   (fell_back_ ? " (CG, then GMRES)" : "") + "; " + setup_.hint);
  return static_cast<int>(its);
}

}  // namespace gf::linsolve
