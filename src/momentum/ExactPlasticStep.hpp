#pragma once
// One step's plastic problem solved exactly (issue 19): eq. 31 with theta = 0 and kappa frozen,
//
//   A u - C Pi (kappa S) = b,    S = P(S + c E u)   in every cell with kappa > 0,
//
// A the assembled prediction operator (Predictor::assemble), b the rest of its right-hand side,
// C and B the plastic matrices (PlasticMatrices.hpp), E u = L (B u + d0) the deviatoric strain
// rate (Dxx - Dyy)/2, Dxy that the projection of eq. 29 acts on, Pi (sxx, sxy) = (sxx, sxy,
// -sxx) the traceless tensor and P the projection on the unit ball of the paper's norm
// |S|^2 = Sxx^2 + Sxy^2. Its solution does not depend on c > 0: in a rigid cell E u = 0 and
// |S| <= 1, in a yielded one S = E u / |E u|; the rigid zones are rigid, not elastic as with
// theta > 0 (the unit test RelaxedProjectionFixedPointDependsOnROverTheta).
//
// Method of multipliers (augmented Lagrangian): for a multiplier lambda, the inner problem
//   F(u) = A u - C Pi kappa P(lambda + c E u) - b = 0
// is the gradient of a convex C^1 function with a semismooth gradient (the Moreau envelope of
// the yield dissipation, on the walls where C = -B^T W), solved by Newton's method (PETSc SNES,
// line search, the generalised Jacobian A - C Pi kappa c P'(q) L B, P'(q) = I inside the ball
// and (I - n n^T) / |q| outside; options prefix -exact_, default a direct solve), then
// lambda <- P(lambda + c E u). It stops when the multiplier changes by less than tol in every
// cell (|lambda_new - lambda| = |P(q) - lambda|: in a rigid cell c |E u|, in a yielded one the
// misalignment of lambda with E u), after a converged inner solve.
//
// Measured (test_exact_plastic_step_mpi.cpp, steady Bingham channel, direct solves): the plug
// below its threshold stays at rest (|u| 1.5e-10 and 1.8e-11 m/s at c factor 1 and 3, 33 and 18
// multiplier updates of one Newton iteration each); the Bingham Poiseuille profile with error
// 1.1e-2 and 2.7e-3 at 16 and 32 cells across (second order), independent of c to 3e-11; but
// the outer loop is slow where the flow yields (52 and 130 updates at c factor 10; at 64 cells
// not converged in 200 updates and 4084 Newton iterations, error 6.8e-4), and at c factor 100
// the Newton line search on |F| fails on the held plug. Not robust enough for the stepper: the
// primal-dual Newton step of docs/RHEOLOGY.md (item 3) is the next candidate for the inner solve.
//
// The pressure is not in this problem (the projection of eq. 32 follows it), so a zone held
// rigid here can still be deformed by the pressure correction (docs/RHEOLOGY.md, the Coulomb
// block's first step). Not yet used by the stepper: a component, verified by
// tests/unit/momentum/test_exact_plastic_step_mpi.cpp, of the coupled exact step issue 19 asks
// for.
#include <petscsnes.h>

#include "grid/Grid.hpp"
#include "momentum/PlasticMatrices.hpp"

namespace gf::momentum {

struct ExactStepOptions {
  double tol = 1e-10;   // largest change of the multiplier in a cell, dimensionless
  int max_outer = 200;  // multiplier updates
  double inner_rtol = 1e-12;  // Newton: relative reduction of |F|
};

struct ExactStepStats {
  int outer = 0;          // multiplier updates
  int newton = 0;         // Newton iterations, all inner solves
  double change = 0;      // the last multiplier change (max over cells)
  bool converged = false;
};

class ExactPlasticStep {
 public:
  explicit ExactPlasticStep(const Grid& g);
  ~ExactPlasticStep();
  ExactPlasticStep(const ExactPlasticStep&) = delete;
  ExactPlasticStep& operator=(const ExactPlasticStep&) = delete;

  // Solves the problem above. A: the prediction operator (dm_vel layout); b: dm_vel; kappa:
  // dm_cell yield stress (Pa); c: dm_cell augmentation (s; the answer does not depend on it,
  // the iteration count does); u: dm_vel, in: the start, out: the solution; S: dm_ten, in: the
  // start multiplier, out: the plastic tensor (0 where kappa <= 0). Collective.
  ExactStepStats solve(Mat A, Vec b, const PlasticMatrices& m, Vec kappa, Vec c, Vec u, Vec S,
                       const ExactStepOptions& opt = {});

 private:
  const Grid& g_;
  SNES snes_ = nullptr;
  // Per solve: what the SNES callbacks read.
  Mat A_ = nullptr, J_ = nullptr, CMB_ = nullptr, M_ = nullptr;
  const PlasticMatrices* m_ = nullptr;
  Vec b_ = nullptr, kappa_ = nullptr, c_ = nullptr, lambda_ = nullptr, D_ = nullptr,
      T_ = nullptr, CT_ = nullptr;  // CT_: C T of the residual (dm_vel)
  void plastic_stress(Vec u, Vec T, bool jacobian);
  static PetscErrorCode residual(SNES, Vec u, Vec F, void* ctx);
  static PetscErrorCode jacobian(SNES, Vec u, Mat J, Mat P, void* ctx);
};

}  // namespace gf::momentum
