#pragma once
// The prediction u~ of eq. 31 with a yield stress or Coulomb walls, solved exactly with
// theta = 0 (rheology.solver = "newton", issue 19): the step's plastic problem
//   A u~ = rhs0 + div(kappa S) - kappa_b s_t,   S = P(S + c E u~),   s_t = P_b(s_t + c_b u_t)
// with kappa and the operator A frozen for the step and kappa_b = tan(alpha_b) (-T_n)^+ (eq. 22)
// from the step's start (p^n, S^n, u^n), frozen too: the step is then a convex problem with a
// unique velocity (rheology.newton_wall_load = "step_start"). With "iterate" kappa_b is
// refreshed from the current D(u~) and S (as the fixed point does; ExactStepOptions::
// refresh_kappa_b). Solved by the primal-dual semismooth Newton method of
// ExactPlasticStep::solve_newton (one direct solve per iteration). The plastic matrices B, C
// are assembled once per step (the phase on the Coulomb walls changes). c = r kappa and c_b = r_b kappa_b are the fixed point's augmentations
// (rheology.r_factor); the converged step does not depend on them (theta = 0: the rigid zones
// are rigid, not elastic). With the side walls of a channel (boundary/SideWalls.hpp) their
// friction is solved in the same Newton iteration (NewtonSide), its bound k frozen for the
// step like kappa. Not with the node copy of S or the gate. With
// solver.viscous_local_margin > 0 the Newton systems after the first of a step are solved on the
// granular rows widened by that margin (ExactStepOptions::local_margin).
#include <petscvec.h>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "momentum/ExactPlasticStep.hpp"
#include "momentum/FixedPoint.hpp"
#include "momentum/Momentum.hpp"
#include "momentum/PlasticMatrices.hpp"
#include "rheology/Rheology.hpp"

namespace gf::momentum {

class NewtonPlastic {
 public:
  // opt: the solver's options; tol and max_outer from rheology.newton_tol and
  // rheology.newton_max_iter. coupled (rheology.newton_pressure = "coupled"): the pressure in
  // the same Newton system (NewtonPressure): u~ is then u^{n+1}, divergence-free, and psi()
  // p^{n+1} - p^n, which replace the projection of eq. 32.
  NewtonPlastic(const Grid& g, Predictor& pred, const rheology::Params& rheo,
                const ExactStepOptions& opt, bool coupled);
  ~NewtonPlastic();
  NewtonPlastic(const NewtonPlastic&) = delete;
  NewtonPlastic& operator=(const NewtonPlastic&) = delete;

  // Solves the step's problem for u~ (in: the initial guess; out: the prediction) and s.S,
  // s.s_wall (in: S^n, s_t^n as the start; out: the step's); in.kappa_b is refreshed with
  // ExactStepOptions::refresh_kappa_b, used as it is otherwise.
  // rhs0: Predictor::explicit_rhs; A: the assembled operator of pred; a0dt = a0/dt (1/s).
  // Stats as the fixed point's: iters = the Newton iterations, change = the last residual.
  // Collective.
  // With the pressure and refresh_kappa_b, the Coulomb walls' kappa_b is refreshed from
  // p^n + psi (the step's pressure), not p^n.
  FixedPointStats solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde, double a0dt);
  bool coupled() const { return pres_.psi != nullptr; }
  // The last solve's p^{n+1} - p^n up to a constant (dm_cell, Pa); null unless coupled.
  Vec psi() const { return pres_.psi; }

 private:
  const Grid& g_;
  Predictor& pred_;
  rheology::Params rheo_;
  ExactStepOptions opt_;
  ExactPlasticStep step_;
  PlasticMatrices m_;
  Vec c_ = nullptr;      // dm_cell, s: c = r kappa
  Vec c_rigid_ = nullptr;  // dm_cell, s: the rigid cells' step, from the cell's own rho, eta
  Vec c_num_ = nullptr;  // dm_vel wall storage, Pa s/m: c_b kappa_b
  Vec c_side_ = nullptr;  // dm_cell, s/m: the side walls' augmentation c_s (NewtonSide)
  NewtonPressure pres_;  // coupled: the saddle point's fixed blocks and psi
  Vec p_step_ = nullptr;  // coupled with walls: p^n + psi for kappa_b (dm_cell, Pa)
};

}  // namespace gf::momentum
