#include "momentum/NewtonPlastic.hpp"

#include <algorithm>

#include "core/Error.hpp"
#include "core/Profile.hpp"
#include "operators/Operators.hpp"

namespace gf::momentum {

NewtonPlastic::NewtonPlastic(const Grid& g, Predictor& pred, const rheology::Params& rheo,
                             const ExactStepOptions& opt, bool coupled)
    : g_(g), pred_(pred), rheo_(rheo), opt_(opt), step_(g) {
  // Newton's own tangential stiffness gamma = c / (|q| - 1) down to |q| - 1 = 1e-9. Measured on
  // case A at n = 16 to 0.3 s (the walls' load from the step's start): with the floor 1e-3 the
  // bottom row's cells just past the yield limit (|q| - 1 = 1e-6 to 5e-5) converged linearly
  // and 25 of 300 steps reached the cap; at 1e-9, with full steps where the active sets do not
  // change (ExactPlasticStep::solve_newton), 9. Not with the pressure: there the unit test's
  // channel (test_exact_plastic_step_mpi.cpp) took 200 iterations at 1e-9 instead of 21.
  if (!coupled) opt_.gap_floor = 1e-9;
  {
    // -exactpd_retract false: the linearisation at S_k itself (ExactStepOptions::retract), to
    // compare iteration counts; the converged step is the same.
    PetscBool flag = PETSC_TRUE, set = PETSC_FALSE;
    GF_PETSC(PetscOptionsGetBool(nullptr, nullptr, "-exactpd_retract", &flag, &set));
    if (set) opt_.retract = flag == PETSC_TRUE;
    // -exactpd_rigid_tol_factor f: the rigid cells and sticking faces to f * newton_tol
    // (ExactStepOptions::rigid_tol_factor).
    GF_PETSC(PetscOptionsGetReal(nullptr, nullptr, "-exactpd_rigid_tol_factor",
                                 &opt_.rigid_tol_factor, nullptr));
  }
  if (coupled) {
    saddle_blocks(g, pres_);
    GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &p_step_));
  }
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &c_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &c_rigid_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &c_num_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &c_side_));
}

NewtonPlastic::~NewtonPlastic() {
  VecDestroy(&c_);
  VecDestroy(&c_rigid_);
  VecDestroy(&c_num_);
  VecDestroy(&c_side_);
  VecDestroy(&p_step_);
  VecDestroy(&pres_.psi);
  MatDestroy(&pres_.G);
  MatDestroy(&pres_.Dv);
  MatDestroy(&pres_.Z);
}

FixedPointStats NewtonPlastic::solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde,
                                     double a0dt) {
  const Box& b = g_.box();
  {
    prof::Scope ps(prof::Assemble);
    assemble_plastic_matrices(g_, pred_, s.eta, m_);
  }
  prof::Scope ps(prof::Plastic);
  // c = r kappa per cell (rheology::update_plastic) and c_b kappa_b = r_factor (rho a0 h / dt +
  // 2 eta / h) per wall face (boundary::CoulombWalls::update).
  {
    const PetscScalar **k, **rr, **er, **rho, **eta;
    PetscScalar **c, **cr;
    Vel** cn;
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), c_rigid_, &cr));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), in.kappa, &k));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), in.rho_r, &rr));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), in.eta_r, &er));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.rho, &rho));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.eta, &eta));
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), c_, &c));
    GF_PETSC(DMDAVecGetArray(g_.dm_vel(), c_num_, &cn));
    const double h2 = std::min(b.hx, b.hy) * std::min(b.hx, b.hy);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        c[j][i] = rheology::r_local(rheo_, k[j][i], er[j][i], rr[j][i] * a0dt * h2) *
                  std::max(k[j][i], 0.0);
        // The rigid cells' step: c_R kappa = rigid_factor (2 eta + rho a0 h^2 / dt) with the cell's own
        // rho and eta. The fixed point's r takes the lightest neighbour's (an interface cell's
        // r from the air's: 1000 times smaller), which there would make the rigid cells' update
        // an Uzawa step too short to converge fast (measured on the Coulomb block: a linear tail
        // at a ratio 0.75 per iteration).
        cr[j][i] = k[j][i] > 0 ? opt_.rigid_factor * (2.0 * eta[j][i] + rho[j][i] * a0dt * h2) /
                                     k[j][i]
                               : 0.0;
        cn[j][i].u = rheo_.r_factor *
                     boundary::CoulombWalls::stiffness(rho[j][i], eta[j][i], a0dt, b.hy);
        cn[j][i].v = rheo_.r_factor *
                     boundary::CoulombWalls::stiffness(rho[j][i], eta[j][i], a0dt, b.hx);
      }
    GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), c_num_, &cn));
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), c_, &c));
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), c_rigid_, &cr));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.eta, &eta));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.rho, &rho));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), in.eta_r, &er));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), in.rho_r, &rr));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), in.kappa, &k));
  }
  boundary::CoulombWalls& walls = pred_.walls();
  NewtonWalls w;
  const bool wall = walls.active();
  if (wall) {
    walls.cache_inputs(s.p, in.kappa, s.eta);
    w.kappa_b = in.kappa_b;
    w.c_num = c_num_;
    w.s_wall = s.s_wall;
    if (opt_.refresh_kappa_b) w.refresh = [&](Vec D, Vec S, Vec kb) {
      if (coupled()) {  // the pressure at the current iterate, at the level p^{n+1} will have
        // (psi is pinned at a corner cell: without the level, kappa_b would take a constant
        // as large as the corner's pressure).
        GF_PETSC(VecWAXPY(p_step_, 1.0, pres_.psi, s.p));
        ops::set_pressure_level(g_, p_step_);
        walls.cache_inputs(p_step_, in.kappa, s.eta);
        walls.yield(p_step_, S, in.kappa, D, s.eta, kb);
      } else {
        walls.yield(s.p, S, in.kappa, D, s.eta, kb);
      }
    };
  }
  // The side walls: c_s = r_factor (rho a0/dt + 2 eta/(hx hy)) / k with the cell's own rho and
  // eta, the fixed point's r k (SideWalls::update) over k.
  NewtonSide sd;
  const bool side = pred_.side_walls().active() && in.kappa_side;
  if (side) {
    const PetscScalar **k, **rho, **eta;
    PetscScalar** cs;
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), in.kappa_side, &k));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.rho, &rho));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.eta, &eta));
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), c_side_, &cs));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i)
        cs[j][i] = k[j][i] > 0 ? rheo_.r_factor *
                                     (rho[j][i] * a0dt + 2.0 * eta[j][i] / (b.hx * b.hy)) /
                                     k[j][i]
                               : 0.0;
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), c_side_, &cs));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.eta, &eta));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.rho, &rho));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), in.kappa_side, &k));
    sd = {in.kappa_side, c_side_, s.s_side};
  }
  if (coupled()) GF_PETSC(VecSet(pres_.psi, 0.0));
  std::vector<PetscInt> rows;
  // At least 2 cells: a cell's S reaches, through the node shear stresses, the faces of its
  // neighbours' neighbours, and the rows outside must hold no plastic term.
  if (opt_.local_margin > 0 && !coupled())
    rows = granular_rows(g_, in.granular, std::max(opt_.local_margin, 2));
  ExactStepStats r;
  try {
    r = step_.solve_newton(pred_.matrix(), rhs0, m_, in.kappa, c_, u_tilde, s.S, opt_,
                           wall ? &w : nullptr, c_rigid_, coupled() ? &pres_ : nullptr,
                           opt_.local_margin > 0 && !coupled() ? &rows : nullptr,
                           side ? &sd : nullptr);
  } catch (...) {
    walls.clear_cache();
    throw;
  }
  walls.clear_cache();
  FixedPointStats st;
  st.iters = r.newton;
  st.change = r.change;
  st.converged = r.converged;
  return st;
}

}  // namespace gf::momentum
