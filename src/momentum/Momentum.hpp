#pragma once
// The prediction step of eq. 31 (without the plastic stress, which rheology/ adds):
//
//   rho^{n+1} ( (a0 u~ + a1 u^n + a2 u^{n-1}) / dt + b0 div(u^n (x) u^n) + b1 div(u^{n-1} (x) u^{n-1}) )
//      + grad p^n = rho^{n+1} g + div(2 eta^{n+1} D(u~)) [+ div(kappa S)]
//
// with the BDF2 coefficients of a variable step (a0, a1, a2) = ((1+2w)/(1+w), -(1+w), w^2/(1+w)),
// w = dt_n / dt_{n-1}, and the extrapolation (b0, b1) = (1+w, -w). For w = 1 these are the
// paper's 3/2, -2, 1/2 and 2, -1. The first step is BDF1 / explicit Euler: (1, -1, 0), (1, 0).
//
// The implicit viscous operator is the full coupled u-v operator  (a0/dt) rho - div(2 eta D(.)),
// assembled once per step (it depends on rho^{n+1}, eta^{n+1}, dt) and solved with a PETSc KSP
// under the option prefix -visc_ (default CG + Jacobi). It is symmetric positive definite (standard MAC
// discretisation), so CG applies. The fixed point of eq. 31 only changes the right-hand side,
// so the matrix and its preconditioner are reused across the fixed-point iterations.
#include <petscksp.h>

#include <array>

#include "boundary/Boundary.hpp"
#include "grid/Grid.hpp"

namespace gf::momentum {

struct TimeCoeffs {
  double a0 = 1, a1 = -1, a2 = 0, b0 = 1, b1 = 0;
  // first = true: BDF1 and explicit Euler (no u^{n-1} yet).
  static TimeCoeffs make(double dt, double dt_old, bool first);
};

class Predictor {
 public:
  Predictor(const Grid& g, const Boundaries& bc, double rtol);
  ~Predictor();
  Predictor(const Predictor&) = delete;
  Predictor& operator=(const Predictor&) = delete;

  // Assembles (a0/dt) rho_face - div(2 eta D(.)) + wall terms for the current properties.
  // rho, eta: cell-centred global Vecs; eta_node: global dm_cell Vec holding eta at the
  // interior nodes (i hx, j hy), 1 <= i < nx, 1 <= j < ny, stored at (i, j).
  void assemble(Vec rho, Vec eta, Vec eta_node, double a0_over_dt);

  // The explicit part of the right-hand side: history, convection, -grad p^n, gravity and the
  // moving-wall terms. Result in rhs (global dm_vel Vec).
  void explicit_rhs(Vec vel, Vec vel_old, Vec p, Vec rho, const TimeCoeffs& c, double dt,
                    const std::array<double, 2>& gravity, Vec rhs);

  // Solves A u~ = rhs. Returns the KSP iteration count; throws RunError on divergence.
  int solve(Vec rhs, Vec u_tilde);

  Mat matrix() const { return A_; }

 private:
  const Grid& g_;
  Boundaries bc_;
  Mat A_ = nullptr;
  KSP ksp_ = nullptr;
  Vec wall_rhs_ = nullptr;  // moving-wall contributions c U / h, depend on eta
  Vec lrho_ = nullptr, leta_ = nullptr, letan_ = nullptr, lvel_ = nullptr, lvel_old_ = nullptr,
      lp_ = nullptr;
  Vec conv_ = nullptr, conv_old_ = nullptr;
  bool preconditioner_built_ = false;
};

}  // namespace gf::momentum
