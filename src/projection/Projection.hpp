#pragma once
// The incremental projection of eq. 32:
//   rho^{n+1} a0 (u^{n+1} - u~) / dt + grad(p^{n+1} - p^n) = 0,   div u^{n+1} = 0,
// i.e. with psi = p^{n+1} - p^n the variable-density Poisson problem
//   -div( (1/rho) grad psi ) = -(a0/dt) div u~    (homogeneous Neumann on every wall;
//   periodic in x with boundary.periodic_x, the null space is still the constants)
// followed by u^{n+1} = u~ - (dt/a0) (1/rho_face) grad psi and p^{n+1} = p^n + psi.
// a0 = 3/2 for the constant-step BDF2 of the paper (momentum/Momentum.hpp).
//
// The operator is symmetric positive semi-definite with the constants as null space; it is
// solved with CG, options prefix -pres_ (any PETSc KSP/PC can be chosen at run time). The
// pressure level is fixed by making the mean pressure on the top boundary (extrapolated from the
// last two rows of cells) zero: the yield stress of the Drucker-Prager model (eq. 19) needs the
// absolute pressure, and the top of the domain is in the air at the reference (atmospheric)
// pressure.
//
// Preconditioner: hypre PFMG (structured-grid multigrid) by default, because the pressure solve
// was ~25 % of the wall time of case A and PFMG's setup is 3-4x and its solve 1.5x cheaper than
// BoomerAMG's on this operator (stand-alone, 1 rank, CG to 1e-8, setup/solve seconds:
// BoomerAMG .007/.007, .024/.038, .106/.20 and PFMG .002/.006, .007/.024, .032/.134 at
// 256x64, 512x128, 1024x256; 14-15 CG iterations with PFMG against 7-8). In case A at n = 64,
// t <= 0.2 s, time_Pressure_s went 2.75 -> 1.36 s with the same answers (2e-9 relative with a
// converged fixed point). PETSc 3.18 offers PFMG only with a MATHYPRESTRUCT matrix on a 3D
// DMDA: the Projector builds an nx x ny x 1 one with the cell DM's decomposition, so cell Vecs
// are used by the solver as they are.
// BoomerAMG back: -pres_pc_type hypre (any pc_type other than pfmg takes the AIJ matrix of
// dm_pres). Periodic x (boundary.periodic_x) always uses AIJ + BoomerAMG: PETSc 3.18's
// MATHYPRESTRUCT rejects periodic DMDAs.
#include <petscksp.h>

#include <memory>

#include "boundary/Gate.hpp"
#include "grid/Grid.hpp"
#include "linsolve/Krylov.hpp"

namespace gf::projection {

class Projector {
 public:
  Projector(const Grid& g, double rtol);
  ~Projector();
  Projector(const Projector&) = delete;
  Projector& operator=(const Projector&) = delete;

  // Assembles the Poisson matrix for the current density (cell-centred global Vec).
  void assemble(Vec rho);
  // The gate (boundary/Gate.hpp; not owned, null: none): the coefficients of the u-faces it
  // covers, and their velocity corrections, are scaled by the faces' open part (0: no flux),
  // from the next assemble() on.
  void set_gate(const boundary::Gate* gate) { gate_ = gate; }
  // Projects u_tilde (in place -> u^{n+1}) and updates p (p^n -> p^{n+1}). Returns KSP iterations.
  int project(Vec vel, Vec p, Vec rho, double a0, double dt);
  // p^{n+1} = p^n + psi with the level of project() (the mean pressure on the top boundary is
  // zero): for a psi solved elsewhere (the exact plastic step with the pressure,
  // momentum/ExactPlasticStep.hpp). Collective.
  void add_increment(Vec psi, Vec p) const;
  // Whether the last project() had to solve again with GMRES after CG broke down.
  bool fell_back() const { return fell_back_; }
  // Whether the preconditioner is hypre PFMG on a MATHYPRESTRUCT matrix (the default).
  bool pfmg() const { return pfmg_; }

 private:
  const Grid& g_;
  bool pfmg_ = false;
  DM dm_struct_ = nullptr;  // PFMG only: the nx x ny x 1 DMDA of the MATHYPRESTRUCT matrix
  Mat M_ = nullptr;
  std::unique_ptr<linsolve::Krylov> ksp_;
  MatNullSpace null_ = nullptr;
  const boundary::Gate* gate_ = nullptr;
  double aperture(PetscInt i, PetscInt j) const { return gate_ ? gate_->aperture(i, j) : 1.0; }
  bool fell_back_ = false;
  Vec rhs_ = nullptr, psi_ = nullptr, lpsi_ = nullptr, lvel_ = nullptr, lrho_ = nullptr;
};

}  // namespace gf::projection
