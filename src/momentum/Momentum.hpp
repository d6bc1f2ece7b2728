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
#include <vector>

#include <memory>

#include "boundary/Boundary.hpp"
#include "boundary/Coulomb.hpp"
#include "boundary/Gate.hpp"
#include "boundary/SideWalls.hpp"
#include "grid/Grid.hpp"
#include "linsolve/Krylov.hpp"

namespace gf::momentum {

struct TimeCoeffs {
  double a0 = 1, a1 = -1, a2 = 0, b0 = 1, b1 = 0;
  // first = true: BDF1 and explicit Euler (no u^{n-1} yet).
  static TimeCoeffs make(double dt, double dt_old, bool first);
  // The momentum transported with the mass fluxes (transport() below): rho^{n+1} (u~ - u*) / dt
  // with u* the transported velocity, i.e. BDF1 with the convection already in u* (b0 = 0).
  static TimeCoeffs transported() { return {1, -1, 0, 0, 0}; }
};

// What one direction-split volume-of-fluid step did (vof::Advector), for the momentum
// transport that goes with it: the granular volume fluxes of its sweeps (dm_vel: .u of the x
// sweep, .v of the y sweep, cell volumes), the volume fraction before and after the step and
// Weymouth & Yue's c_c (dm_cell), and the two densities.
struct MassSweeps {
  Vec flux = nullptr, c_start = nullptr, c_end = nullptr, cc = nullptr;
  double rho_air = 0, rho_gran = 0;  // kg/m^3
};

class Predictor {
 public:
  Predictor(const Grid& g, const Boundaries& bc, double rtol,
            const boundary::SideWallParams& side = {});
  ~Predictor();
  Predictor(const Predictor&) = delete;
  Predictor& operator=(const Predictor&) = delete;

  // Assembles (a0/dt) rho_face - div(2 eta D(.)) + wall terms for the current properties.
  // rho, eta: cell-centred global Vecs; eta_node: global dm_cell Vec holding eta at the
  // interior nodes (i hx, j hy), 1 <= i < nx (0 <= i < nx with periodic x), 1 <= j < ny,
  // stored at (i, j).
  void assemble(Vec rho, Vec eta, Vec eta_node, double a0_over_dt);
  // A linear drag d u on the faces (Pa s/m^2; dm_cell Vec, a face takes the mean of its two
  // cells), implicit in the operator from the next assemble() on: the air's Navier slip on the
  // side walls of a channel (boundary/SideWalls.hpp). Null: none.
  void set_drag(Vec drag) { drag_ = drag; }
  // The gate (boundary/Gate.hpp; not owned, null: none): the covered u-faces are pinned to 0 by
  // a penalty, the covered nodes are walls (Navier slip for the air, moving at the gate's
  // speed; the Coulomb traction for the grains, add_plastic) from the next assemble() on.
  void set_gate(const boundary::Gate* gate) {
    gate_ = gate;
    walls_.set_gate(gate);
  }
  const boundary::Gate* gate() const { return gate_; }

  // The explicit part of the right-hand side: history, convection, -grad p^n, gravity and the
  // moving-wall terms. Result in rhs (global dm_vel Vec).
  void explicit_rhs(Vec vel, Vec vel_old, Vec p, Vec rho, const TimeCoeffs& c, double dt,
                    const std::array<double, 2>& gravity, Vec rhs);

  // The momentum transport consistent with the mass transport (interface.method = "clsvof"):
  // u* from u^n (vel) by ops::momentum_transport with the mass fluxes of m, which the face
  // velocity adv carried (the velocity of the volume-fraction step), so that rho_f^{n+1} u* is
  // the momentum rho_f^n u^n moved by the fluxes that moved rho_f^n to rho_f^{n+1}. explicit_rhs(u*, ..., TimeCoeffs::transported()) then gives the
  // prediction rho^{n+1} (u~ - u*) / dt = ... of eq. 31 without a separate convection term.
  void transport(Vec adv, Vec vel, const MassSweeps& m, double dt, Vec u_star);

  // The power dissipated by the viscous stresses of the assembled operator (eq. 31's
  // div(2 eta D(u)) with its wall terms: Navier slip, no slip) for the velocity vel, W per metre
  // of depth: (u . A u - a0/dt sum rho_face u^2) hx hy, i.e. sum 2 eta D(u):D(u) over the
  // cells and nodes plus the slip walls' eta_b-type terms, exactly as the discrete operator
  // has them. rho: the density A was assembled with. Collective.
  double viscous_power(Vec vel, Vec rho);

  // Solves A u~ = rhs. Returns the KSP iteration count; throws RunError on divergence.
  int solve(Vec rhs, Vec u_tilde);

  // ---- Local solves inside the fixed point (solver.viscous_local_margin) ----
  // After the first solve of a step, the fixed point of eq. 31 changes the right-hand side only
  // where the plastic terms live, and the operator is dominated by its mass term (the diffusion
  // length sqrt(eta dt / rho) is below one cell in case A), so u~ changes only near the
  // granular phase. begin_local() restricts the solves to the rows R (local indices into a
  // dm_vel global Vec, ascending) with the values of u outside R frozen: the Dirichlet
  // sub-problem A_RR u_R = rhs_R - A_RS u_S, assembled by MatCreateSubMatrix from the full
  // matrix, so the same discretisation; its tolerance is the full solve's absolute one,
  // rtol ||B rhs|| (B: the full solve's preconditioner), the test KSPConvergedDefault applies to
  // a warm-started full solve. The sub-problem's rows are dealt out evenly over the ranks.
  // CG moves a residual by one cell per iteration, so while R holds the granular rows widened
  // by more cells than the iterations a solve takes, the local solve takes the same steps as
  // the full one. The caller ends the fixed point with a full solve
  // (solve()), which puts back what the frozen rows missed. Collective; an empty R on every
  // rank leaves the local solves off (local_active() false).
  void begin_local(const std::vector<PetscInt>& rows, Vec rhs, Vec u);
  bool local_active() const { return Aloc_ != nullptr; }
  // Solves the sub-problem for the rows R of u (the others are left as they are) with the
  // current rhs (global dm_vel Vec, all rows). Returns the KSP iteration count.
  int solve_local(Vec rhs, Vec u);
  void end_local();

  // ---- The plastic part of eq. 31 (rheology plugs in here; see Plastic.cpp) ----
  // The Coulomb walls (boundary/Coulomb.hpp): their friction, the phase that says which wall
  // faces are granular (set_phase once per step, before assemble()), their yield stress and
  // projection. A granular face on a frictional wall has the Coulomb traction -kappa_b s_t
  // (add_plastic) instead of its wall condition.
  boundary::CoulombWalls& walls() { return walls_; }
  const boundary::CoulombWalls& walls() const { return walls_; }
  // The side walls of a channel (boundary/SideWalls.hpp): their friction is a body force the
  // fixed point adds with add_force and projects with update.
  const boundary::SideWalls& side_walls() const { return side_; }
  // rhs += div(kappa S) on the faces, plus the Coulomb wall tractions -kappa_b s_t.
  // kappa: cell yield stress (Pa); S: dm_ten (Sxx, Sxy, Syy); kappa_b, s_wall: dm_vel wall
  // storage (boundary/Coulomb.hpp).
  // S_node (dm_node, optional: rheology.plastic_grid = "cell_node"): the node copy of S; then
  // the plastic stress is half the cell copy's plus half the node copy's (the node Sxx, Syy
  // reach the cells as the mean of their four corners; the node Sxy is the shear stress at the
  // node itself, wall nodes included on no-slip walls). kappa at a node: the mean of its cells.
  void add_plastic(Vec kappa, Vec S, Vec kappa_b, Vec s_wall, Vec rhs, Vec S_node = nullptr);
  // Limits add_plastic and the cell part of strain_rate to a rectangle of cells [i0, i1) x
  // [j0, j1) (global indices): the granular region with a margin, where the plastic terms and
  // D(u~) for the projections live (set by the stepper once per step, from the cells with
  // kappa > 0 or phi < 0 widened by 2 cells; the faces outside get no plastic term there).
  // Outside it strain_rate leaves D as it was: callers that read D everywhere call
  // clear_plastic_region() first. Without the node copy only.
  // kUnbounded: no limit in that direction.
  static constexpr PetscInt kUnbounded = 1000000000;
  void set_plastic_region(PetscInt i0, PetscInt i1, PetscInt j0, PetscInt j1) {
    reg_ = {i0, i1, j0, j1};
  }
  void clear_plastic_region() {
    reg_ = {-kUnbounded, kUnbounded, -kUnbounded, kUnbounded};
    walls_.clear_cache();
  }
  // D(u) at the cell centres (dm_ten: Dxx, Dxy, Dyy), with the shear at wall nodes from the
  // wall condition (no slip, Navier: from the wall velocity; free slip, Coulomb: zero).
  // D_node (dm_node, optional): D(u) at the nodes for the node copy of S: Dxy = half the node
  // shear rate (on a wall node: from the no-slip wall velocity; 0 on other walls and at the
  // corners), Dxx, Dyy = the mean over the node's cells of the cell values.
  void strain_rate(Vec vel, Vec eta, Vec D, Vec D_node = nullptr);
  Mat matrix() const { return A_; }

 private:
  struct Region {
    PetscInt i0, i1, j0, j1;
  } reg_{-kUnbounded, kUnbounded, -kUnbounded, kUnbounded};
  const Grid& g_;
  Boundaries bc_;
  Mat A_ = nullptr;
  std::unique_ptr<linsolve::Krylov> ksp_;
  // begin_local(): the rows R, the sub-matrix A_RR, its KSP, and c_R = A_RS u_S.
  VecScatter loc_sct_ = nullptr;  // the rows R of a dm_vel Vec <-> the sub-problem's Vecs
  Mat Aloc_ = nullptr;
  std::unique_ptr<linsolve::Krylov> kloc_;
  Vec bloc_ = nullptr, xloc_ = nullptr, cloc_ = nullptr, work_ = nullptr;
  void gather_local(Vec full, Vec sub) const;
  Vec wall_rhs_ = nullptr;  // moving-wall contributions c U / h, depend on eta
  double a0dt_ = 0;         // a0/dt of the assembled matrix, 1/s
  Vec lrho_ = nullptr, leta_ = nullptr, letan_ = nullptr, lvel_ = nullptr, lvel_old_ = nullptr,
      lp_ = nullptr;
  Vec conv_ = nullptr, conv_old_ = nullptr;
  // transport(): the ghosted advecting velocity, fluxes and fractions.
  Vec ladv_ = nullptr, lflux_ = nullptr, lca_ = nullptr, lcb_ = nullptr, lcc_ = nullptr;
  boundary::CoulombWalls walls_;
  boundary::SideWalls side_;
  Vec drag_ = nullptr, ldrag_ = nullptr;  // set_drag (not owned) and its ghosted copy
  const boundary::Gate* gate_ = nullptr;  // set_gate
  bool gate_node(PetscInt i, PetscInt j) const { return gate_ && gate_->node_blocked(i, j); }
};

}  // namespace gf::momentum
