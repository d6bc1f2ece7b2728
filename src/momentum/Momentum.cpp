#include "momentum/Momentum.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/Error.hpp"
#include "operators/Operators.hpp"

namespace gf::momentum {

TimeCoeffs TimeCoeffs::make(double dt, double dt_old, bool first) {
  TimeCoeffs c;
  if (first || dt_old <= 0) return c;
  const double w = dt / dt_old;
  c.a0 = (1 + 2 * w) / (1 + w);
  c.a1 = -(1 + w);
  c.a2 = w * w / (1 + w);
  c.b0 = 1 + w;
  c.b1 = -w;
  return c;
}

Predictor::Predictor(const Grid& g, const Boundaries& bc, double rtol,
                     const boundary::SideWallParams& side)
    : g_(g), bc_(bc), walls_(g, bc), side_(g, side) {
  // Preallocate only: the box stencil of dm_visc reserves 18 slots per row but a row has 9
  // entries; explicit zeros in the pattern would make BoomerAMG's coarse operators needlessly
  // dense (measured: 4x slower V-cycles). The first assembly fixes the true pattern.
  GF_PETSC(DMSetMatrixPreallocateOnly(g.dm_visc(), PETSC_TRUE));
  GF_PETSC(DMCreateMatrix(g.dm_visc(), &A_));
  GF_PETSC(MatSetOption(A_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  GF_PETSC(MatSetOption(A_, MAT_SYMMETRIC, PETSC_TRUE));
  // Default CG + Jacobi: with the mass term rho a0/dt on the diagonal, and eta/h^2 of order
  // rho/dt at the paper's viscosities, the operator is well conditioned after diagonal
  // scaling (measured: 29 iterations at 6 ms per solve on the 128^2 cavity, against 21 ms with
  // BoomerAMG on the vector system). Large viscosity contrasts (mu(I)) need
  // -visc_pc_type hypre (SOLVER_NOTES.md: Jacobi takes 650 iterations at eta = 5000).
  ksp_ = std::make_unique<linsolve::Krylov>(
      g.comm(), linsolve::KrylovSetup{"visc_", KSPCG, PCJACOBI, rtol, true, false,
                                      "viscous solve (prefix -visc_)",
                                      "try a smaller time step or -visc_pc_type hypre"});
  // The local solves (begin_local) read the same -visc_ options; their tolerance is set there.
  kloc_ = std::make_unique<linsolve::Krylov>(
      g.comm(), linsolve::KrylovSetup{"visc_", KSPCG, PCJACOBI, std::nullopt, true, false,
                                      "local viscous solve (prefix -visc_, "
                                      "solver.viscous_local_margin)",
                                      "try solver.viscous_local_margin = 0"});
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &wall_rhs_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &conv_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &conv_old_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lrho_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &leta_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &letan_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lp_));
  GF_PETSC(DMCreateLocalVector(g.dm_vel(), &lvel_));
  GF_PETSC(DMCreateLocalVector(g.dm_vel(), &lvel_old_));
}

Predictor::~Predictor() {
  for (Vec* v : {&wall_rhs_, &conv_, &conv_old_, &lrho_, &leta_, &letan_, &lp_, &lvel_,
                 &lvel_old_, &ladv_, &lflux_, &lca_, &lcb_, &lcc_, &ldrag_})
    VecDestroy(v);
  end_local();
  VecDestroy(&work_);
  MatDestroy(&A_);
}

void Predictor::assemble(Vec rho, Vec eta, Vec eta_node, double a0dt) {
  const Box& b = g_.box();
  a0dt_ = a0dt;
  to_local(g_.dm_cell(), rho, lrho_);
  to_local(g_.dm_cell(), eta, leta_);
  to_local(g_.dm_cell(), eta_node, letan_);
  const PetscScalar **r, **ec, **en;
  Vel** wr;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), leta_, &ec));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), letan_, &en));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), wall_rhs_, &wr));
  const PetscScalar** dr = nullptr;  // set_drag
  if (drag_) {
    if (!ldrag_) GF_PETSC(DMCreateLocalVector(g_.dm_cell(), &ldrag_));
    to_local(g_.dm_cell(), drag_, ldrag_);
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), ldrag_, &dr));
  }
  const boundary::CoulombWalls::Phase phase(walls_);
  const PetscScalar* const* ph = phase.array();
  // A granular face on a frictional wall has the Coulomb traction instead (add_plastic).
  auto cw = [&](const WallBC& w, double e, double d, int side, PetscInt i, PetscInt j) {
    return walls_.coulomb_face(ph, side, i, j) ? 0.0 : wall_coefficient(w, e, d);
  };
  // The gate (boundary/Gate.hpp): its covered nodes carry no viscous shear across (eta = 0
  // there) and are walls for the v-faces on either side (gate_wall); its covered u-faces are
  // pinned to 0 by a penalty 1e8 times their mass term.
  auto eta_nd = [&](PetscInt i, PetscInt j) { return gate_node(i, j) ? 0.0 : en[j][i]; };
  const WallBC gate_bc{WallType::Navier, gate_ ? gate_->params().eta_b : 0.0,
                       gate_ ? gate_->velocity() : 0.0};
  auto gate_wall = [&](PetscInt i, PetscInt j, double& diag, double& rhs) {
    const double e = 0.5 * (ec[j - 1][i] + ec[j][i]);
    const double c = walls_.gate_face(ph, i, j) ? 0.0 : wall_coefficient(gate_bc, e, 0.5 * b.hx);
    diag += c / b.hx;
    rhs += c * gate_bc.velocity / b.hx;
  };
  constexpr double kGatePenalty = 1e8;
  GF_PETSC(MatZeroEntries(A_));

  const double hx = b.hx, hy = b.hy, hx2 = hx * hx, hy2 = hy * hy, hxy = hx * hy;
  MatStencil row, col[12];
  PetscScalar val[12];
  int n = 0;  // entries of the current row
  auto add = [&](PetscInt ii, PetscInt jj, PetscInt cc, double v) {
    col[n].i = ii; col[n].j = jj; col[n].k = 0; col[n].c = cc; val[n] = v; ++n;
  };
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      // ---- x-momentum, unknown u on the left face of cell (i, j) ----
      row.i = i; row.j = j; row.k = 0; row.c = 0;
      wr[j][i].u = 0.0;
      if (b.wall_u(i)) {  // wall face: u = 0 (eq. 20); a scaled identity row keeps A SPD
        col[0] = row;
        val[0] = a0dt * r[j][i];
        GF_PETSC(MatSetValuesStencil(A_, 1, &row, 1, col, val, INSERT_VALUES));
      } else {
        n = 0;
        double diag = a0dt * ops::rho_xface(r, i, j);
        if (dr) diag += 0.5 * (dr[j][i - 1] + dr[j][i]);
        if (gate_ && gate_->aperture(i, j) < 1.0) diag += kGatePenalty * a0dt * ops::rho_xface(r, i, j);
        // normal stress 2 eta du/dx at the centres of cells i-1 and i (periodic x: the
        // columns -1 / nx wrap in MatSetValuesStencil, cell i-1 = -1 is a ghost)
        diag += 2 * (ec[j][i] + ec[j][i - 1]) / hx2;
        if (!b.wall_u(i + 1)) add(i + 1, j, 0, -2 * ec[j][i] / hx2);
        if (!b.wall_u(i - 1)) add(i - 1, j, 0, -2 * ec[j][i - 1] / hx2);
        // shear stress eta (du/dy + dv/dx) at the top node (i, j+1)
        if (j + 1 < b.ny) {
          const double e = eta_nd(i, j + 1);
          diag += e / hy2;
          add(i, j + 1, 0, -e / hy2);
          add(i, j + 1, 1, -e / hxy);
          add(i - 1, j + 1, 1, e / hxy);
        } else {  // top wall
          const double e = 0.5 * (ec[j][i - 1] + ec[j][i]);
          const double c = cw(bc_.top, e, 0.5 * hy, 3, i, j);
          diag += c / hy;
          wr[j][i].u += c * bc_.top.velocity / hy;
        }
        // ... and at the bottom node (i, j)
        if (j >= 1) {
          const double e = eta_nd(i, j);
          diag += e / hy2;
          add(i, j - 1, 0, -e / hy2);
          add(i, j, 1, e / hxy);
          add(i - 1, j, 1, -e / hxy);
        } else {  // bottom wall
          const double e = 0.5 * (ec[j][i - 1] + ec[j][i]);
          const double c = cw(bc_.bottom, e, 0.5 * hy, 2, i, j);
          diag += c / hy;
          wr[j][i].u += c * bc_.bottom.velocity / hy;
        }
        add(i, j, 0, diag);
        GF_PETSC(MatSetValuesStencil(A_, 1, &row, n, col, val, INSERT_VALUES));
      }
      // ---- y-momentum, unknown v on the bottom face of cell (i, j) ----
      row.c = 1;
      wr[j][i].v = 0.0;
      if (j == 0) {
        col[0] = row;
        val[0] = a0dt * r[j][i];
        GF_PETSC(MatSetValuesStencil(A_, 1, &row, 1, col, val, INSERT_VALUES));
      } else {
        n = 0;
        double diag = a0dt * ops::rho_yface(r, i, j);
        if (dr) diag += 0.5 * (dr[j - 1][i] + dr[j][i]);
        diag += 2 * (ec[j][i] + ec[j - 1][i]) / hy2;
        if (j + 1 < b.ny) add(i, j + 1, 1, -2 * ec[j][i] / hy2);
        if (j - 1 >= 1) add(i, j - 1, 1, -2 * ec[j - 1][i] / hy2);
        // shear stress at the right node (i+1, j) (periodic x: node nx is node 0)
        if (!b.wall_u(i + 1)) {
          const double e = eta_nd(i + 1, j);
          diag += e / hx2;
          add(i + 1, j, 1, -e / hx2);
          add(i + 1, j, 0, -e / hxy);
          add(i + 1, j - 1, 0, e / hxy);
          if (gate_node(i + 1, j)) gate_wall(i, j, diag, wr[j][i].v);
        } else {  // right wall
          const double e = 0.5 * (ec[j - 1][i] + ec[j][i]);
          const double c = cw(bc_.right, e, 0.5 * hx, 1, i, j);
          diag += c / hx;
          wr[j][i].v += c * bc_.right.velocity / hx;
        }
        // ... and at the left node (i, j)
        if (!b.wall_u(i)) {
          const double e = eta_nd(i, j);
          diag += e / hx2;
          add(i - 1, j, 1, -e / hx2);
          add(i, j, 0, e / hxy);
          add(i, j - 1, 0, -e / hxy);
          if (gate_node(i, j)) gate_wall(i, j, diag, wr[j][i].v);
        } else {  // left wall
          const double e = 0.5 * (ec[j - 1][i] + ec[j][i]);
          const double c = cw(bc_.left, e, 0.5 * hx, 0, i, j);
          diag += c / hx;
          wr[j][i].v += c * bc_.left.velocity / hx;
        }
        add(i, j, 1, diag);
        GF_PETSC(MatSetValuesStencil(A_, 1, &row, n, col, val, INSERT_VALUES));
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), wall_rhs_, &wr));
  if (dr) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), ldrag_, &dr));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), letan_, &en));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), leta_, &ec));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
  ksp_->set_operator(A_);
}

void Predictor::explicit_rhs(Vec vel, Vec vel_old, Vec p, Vec rho, const TimeCoeffs& c,
                             double dt, const std::array<double, 2>& grav, Vec rhs) {
  const Box& b = g_.box();
  to_local(g_.dm_vel(), vel, lvel_);
  to_local(g_.dm_vel(), vel_old, lvel_old_);
  to_local(g_.dm_cell(), p, lp_);
  to_local(g_.dm_cell(), rho, lrho_);
  Vel **lv, **lvo, **cv, **cvo, **out;
  const Vel **wr;
  const PetscScalar **pp, **r;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &lv));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_old_, &lvo));
  fill_velocity_ghosts(g_, lv);
  fill_velocity_ghosts(g_, lvo);
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), conv_, &cv));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), conv_old_, &cvo));
  // b0 = 0: the convection is already in vel (transport()).
  if (c.b0 != 0.0) ops::convection(b, lv, cv);
  if (c.b1 != 0.0) ops::convection(b, lvo, cvo);
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lp_, &pp));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), wall_rhs_, &wr));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), rhs, &out));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (b.wall_u(i)) {
        out[j][i].u = 0.0;
      } else {
        const double rf = ops::rho_xface(r, i, j);
        const double hist = -(c.a1 * lv[j][i].u + c.a2 * lvo[j][i].u) / dt;
        const double conv = (c.b0 != 0.0 ? c.b0 * cv[j][i].u : 0.0) +
                            (c.b1 != 0.0 ? c.b1 * cvo[j][i].u : 0.0);
        out[j][i].u = rf * (hist - conv) - (pp[j][i] - pp[j][i - 1]) / b.hx + rf * grav[0] +
                      wr[j][i].u;
      }
      if (j == 0) {
        out[j][i].v = 0.0;
      } else {
        const double rf = ops::rho_yface(r, i, j);
        const double hist = -(c.a1 * lv[j][i].v + c.a2 * lvo[j][i].v) / dt;
        const double conv = (c.b0 != 0.0 ? c.b0 * cv[j][i].v : 0.0) +
                            (c.b1 != 0.0 ? c.b1 * cvo[j][i].v : 0.0);
        out[j][i].v = rf * (hist - conv) - (pp[j][i] - pp[j - 1][i]) / b.hy + rf * grav[1] +
                      wr[j][i].v;
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), rhs, &out));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), wall_rhs_, &wr));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lp_, &pp));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), conv_old_, &cvo));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), conv_, &cv));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_old_, &lvo));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &lv));
}

void Predictor::transport(Vec adv, Vec vel, const MassSweeps& m, double dt, Vec u_star) {
  const Box& b = g_.box();
  if (!lflux_) {
    GF_PETSC(DMCreateLocalVector(g_.dm_vel(), &lflux_));
    GF_PETSC(DMCreateLocalVector(g_.dm_vel(), &ladv_));
    for (Vec* v : {&lca_, &lcb_, &lcc_}) GF_PETSC(DMCreateLocalVector(g_.dm_cell(), v));
  }
  to_local(g_.dm_vel(), adv, ladv_);
  to_local(g_.dm_vel(), vel, lvel_);
  to_local(g_.dm_vel(), m.flux, lflux_);
  to_local(g_.dm_cell(), m.c_start, lca_);
  to_local(g_.dm_cell(), m.c_end, lcb_);
  to_local(g_.dm_cell(), m.cc, lcc_);
  Vel **lv, **la, **out;
  const Vel** F;
  const PetscScalar **a, **bb, **cc;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &lv));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), ladv_, &la));
  fill_velocity_ghosts(g_, lv);
  fill_velocity_ghosts(g_, la);
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), lflux_, &F));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lca_, &a));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lcb_, &bb));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lcc_, &cc));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), u_star, &out));
  ops::momentum_transport(b, dt, m.rho_air, m.rho_gran, la, a, bb, cc, F, lv, out);
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), u_star, &out));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lcc_, &cc));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lcb_, &bb));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lca_, &a));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), lflux_, &F));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), ladv_, &la));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &lv));
}

double Predictor::viscous_power(Vec vel, Vec rho) {
  const Box& b = g_.box();
  if (!work_) GF_PETSC(VecDuplicate(vel, &work_));
  GF_PETSC(MatMult(A_, vel, work_));
  PetscScalar uAu;
  GF_PETSC(VecDot(vel, work_, &uAu));
  // The mass term a0/dt rho_face u^2 of the same rows (wall rows carry u = 0).
  to_local(g_.dm_cell(), rho, lrho_);
  const PetscScalar** r;
  const Vel** u;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), vel, &u));
  double mass = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (!b.wall_u(i)) mass += ops::rho_xface(r, i, j) * u[j][i].u * u[j][i].u;
      if (j > 0) mass += ops::rho_yface(r, i, j) * u[j][i].v * u[j][i].v;
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), vel, &u));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  return (uAu - a0dt_ * g_.sum(mass)) * b.hx * b.hy;
}

int Predictor::solve(Vec rhs, Vec u_tilde) {
  return ksp_->solve(rhs, u_tilde);
}

void Predictor::gather_local(Vec full, Vec sub) const {
  GF_PETSC(VecScatterBegin(loc_sct_, full, sub, INSERT_VALUES, SCATTER_FORWARD));
  GF_PETSC(VecScatterEnd(loc_sct_, full, sub, INSERT_VALUES, SCATTER_FORWARD));
}

void Predictor::begin_local(const std::vector<PetscInt>& rows, Vec rhs, Vec u) {
  end_local();
  const PetscInt n_loc = static_cast<PetscInt>(rows.size());
  PetscInt n_glob = 0;
  MPI_Allreduce(&n_loc, &n_glob, 1, MPIU_INT, MPI_SUM, g_.comm());
  if (n_glob == 0) return;
  // R is where the granular phase is, which in case A lies on one rank of two: the sub-problem
  // is dealt out in equal parts of its global row list (ascending) instead, rank r taking the
  // r-th. Every rank holds the whole list (all-gather, O(|R|) integers).
  PetscInt rstart;
  GF_PETSC(MatGetOwnershipRange(A_, &rstart, nullptr));
  std::vector<PetscInt> mine(rows.size());
  for (std::size_t q = 0; q < rows.size(); ++q) mine[q] = rstart + rows[q];
  PetscMPIInt size, rank;
  MPI_Comm_size(g_.comm(), &size);
  MPI_Comm_rank(g_.comm(), &rank);
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  const PetscMPIInt n_mine = static_cast<PetscMPIInt>(n_loc);
  MPI_Allgather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, g_.comm());
  for (PetscMPIInt r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<PetscInt> all(static_cast<std::size_t>(n_glob));
  MPI_Allgatherv(mine.data(), n_mine, MPIU_INT, all.data(), counts.data(), displs.data(),
                 MPIU_INT, g_.comm());
  const PetscInt lo = n_glob * rank / size, hi = n_glob * (rank + 1) / size;
  IS is;
  GF_PETSC(ISCreateGeneral(g_.comm(), hi - lo, all.data() + lo, PETSC_COPY_VALUES, &is));
  GF_PETSC(MatCreateSubMatrix(A_, is, is, MAT_INITIAL_MATRIX, &Aloc_));
  GF_PETSC(MatSetOption(Aloc_, MAT_SYMMETRIC, PETSC_TRUE));
  GF_PETSC(MatCreateVecs(Aloc_, &xloc_, &bloc_));
  GF_PETSC(VecDuplicate(bloc_, &cloc_));
  GF_PETSC(VecScatterCreate(u, is, xloc_, nullptr, &loc_sct_));
  GF_PETSC(ISDestroy(&is));
  if (!work_) GF_PETSC(VecDuplicate(u, &work_));
  // c_R = (A u)_R - A_RR u_R: what the frozen rows outside R put into the rows of R.
  GF_PETSC(MatMult(A_, u, work_));
  gather_local(work_, cloc_);
  gather_local(u, xloc_);
  GF_PETSC(MatMult(Aloc_, xloc_, bloc_));
  GF_PETSC(VecAXPY(cloc_, -1.0, bloc_));
  // The full solve's stopping test: ||B r|| < max(rtol ||B rhs||, atol) (KSPConvergedDefault
  // with a nonzero initial guess). The preconditioned residual of R is the full one while the
  // residual lives in R (exactly so for Jacobi).
  PetscReal rtol, atol, dtol, bnorm;
  PetscInt maxit;
  GF_PETSC(KSPGetTolerances(ksp_->ksp(), &rtol, &atol, &dtol, &maxit));
  PC pc;
  GF_PETSC(KSPGetPC(ksp_->ksp(), &pc));
  GF_PETSC(PCApply(pc, rhs, work_));
  GF_PETSC(VecNorm(work_, NORM_2, &bnorm));
  kloc_->set_operator(Aloc_);
  GF_PETSC(KSPSetTolerances(kloc_->ksp(), 0.0, std::max(rtol * bnorm, atol), dtol, maxit));
}

int Predictor::solve_local(Vec rhs, Vec u) {
  gather_local(rhs, bloc_);
  GF_PETSC(VecAXPY(bloc_, -1.0, cloc_));
  gather_local(u, xloc_);
  const int its = kloc_->solve(bloc_, xloc_);
  GF_PETSC(VecScatterBegin(loc_sct_, xloc_, u, INSERT_VALUES, SCATTER_REVERSE));
  GF_PETSC(VecScatterEnd(loc_sct_, xloc_, u, INSERT_VALUES, SCATTER_REVERSE));
  return its;
}

void Predictor::end_local() {
  // The next R has other sizes: the KSP and its preconditioner drop the old operator.
  if (kloc_) KSPReset(kloc_->ksp());
  for (Vec* v : {&bloc_, &xloc_, &cloc_}) VecDestroy(v);
  MatDestroy(&Aloc_);
  VecScatterDestroy(&loc_sct_);
}

}  // namespace gf::momentum
