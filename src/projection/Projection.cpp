#include "projection/Projection.hpp"

#include <string>

#include "core/Error.hpp"
#include "linsolve/Krylov.hpp"
#include "operators/Operators.hpp"

namespace gf::projection {

Projector::Projector(const Grid& g, double rtol) : g_(g) {
  // The preconditioner is chosen before the matrix because PFMG needs its own matrix type. Only
  // -pres_pc_type is looked at here; the rest of the -pres_ options reach the KSP below.
  char pc_type[64] = "";
  PetscBool pc_set = PETSC_FALSE;
  GF_PETSC(PetscOptionsGetString(nullptr, "pres_", "-pc_type", pc_type, sizeof pc_type, &pc_set));
  const bool want_pfmg = !pc_set || std::string(pc_type) == PCPFMG;
  // PETSc 3.18's MATHYPRESTRUCT refuses any DMDA boundary type but DM_BOUNDARY_NONE ("Ask us
  // to add periodic support by calling HYPRE_StructGridSetPeriodic()"), so a periodic grid keeps
  // the AIJ matrix and BoomerAMG.
  if (want_pfmg && g.periodic_x() && pc_set)
    throw InputError("-pres_pc_type pfmg: PFMG (MATHYPRESTRUCT) has no periodic support in PETSc "
                     "3.18 (boundary.periodic_x = true); use -pres_pc_type hypre");
  pfmg_ = want_pfmg && !g.periodic_x();

  if (pfmg_) {
    // MATHYPRESTRUCT exists only for a 3D DMDA: nx x ny x 1 cells, star stencil of width 1,
    // with the processor grid and ownership ranges of the cell DM. Its global vectors then have
    // the local layout of dm_cell's (i fastest, then j; k = 0 only), so the Vecs of dm_cell
    // (rhs_, psi_) go to KSPSolve as they are: MatMult and PCApply of hypre copy the local
    // array with HYPRE_StructVector{Set,Get}BoxValues over the owned box. No scatter, no copy.
    // The boundary is DM_BOUNDARY_NONE (MATHYPRESTRUCT rejects GHOSTED): no ghost rows exist
    // beyond the walls and the wall stencil entries stay zero.
    PetscInt px, py;
    const PetscInt *lx, *ly;
    GF_PETSC(DMDAGetInfo(g.dm_cell(), nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr,
                         nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
    GF_PETSC(DMDAGetOwnershipRanges(g.dm_cell(), &lx, &ly, nullptr));
    const PetscInt lz[1] = {1};
    GF_PETSC(DMDACreate3d(g.comm(), DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE,
                          DMDA_STENCIL_STAR, g.nx(), g.ny(), 1, px, py, 1, 1, 1, lx, ly, lz,
                          &dm_struct_));
    GF_PETSC(DMSetMatType(dm_struct_, MATHYPRESTRUCT));
    GF_PETSC(DMSetUp(dm_struct_));
    PetscInt xs, ys, zs, xm, ym, zm;
    GF_PETSC(DMDAGetCorners(dm_struct_, &xs, &ys, &zs, &xm, &ym, &zm));
    const Box& b = g.box();
    if (xs != b.xs || ys != b.ys || xm != b.xm || ym != b.ym || zs != 0 || zm != 1)
      throw RunError("projection: the PFMG DMDA does not have the layout of the cell DM");
    GF_PETSC(DMCreateMatrix(dm_struct_, &M_));
  } else {
    GF_PETSC(DMCreateMatrix(g.dm_pres(), &M_));
    GF_PETSC(MatSetOption(M_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  }
  GF_PETSC(MatSetOption(M_, MAT_SYMMETRIC, PETSC_TRUE));
  // The constants span the null space for both matrix types (MatSetNullSpace is generic; KSP
  // projects them out of the preconditioned residual). The rhs is made consistent by hand in
  // project(); the constant part of psi does not matter, the level is set afterwards.
  GF_PETSC(MatNullSpaceCreate(g.comm(), PETSC_TRUE, 0, nullptr, &null_));
  GF_PETSC(MatSetNullSpace(M_, null_));
  ksp_ = std::make_unique<linsolve::Krylov>(
      g.comm(),
      linsolve::KrylovSetup{"pres_", KSPCG, pfmg_ ? PCPFMG : PCHYPRE, rtol, false, true,
                            "pressure solve (prefix -pres_)",
                            "try another preconditioner (e.g. -pres_pc_type hypre for BoomerAMG, "
                            "or gamg) or a smaller time step (time.cfl, time.dt_max)"});
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &rhs_));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &psi_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lpsi_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lrho_));
  GF_PETSC(DMCreateLocalVector(g.dm_vel(), &lvel_));
}

Projector::~Projector() {
  for (Vec* v : {&rhs_, &psi_, &lpsi_, &lrho_, &lvel_}) VecDestroy(v);
  MatNullSpaceDestroy(&null_);
  MatDestroy(&M_);
  DMDestroy(&dm_struct_);
}

void Projector::assemble(Vec rho) {
  const Box& b = g_.box();
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), rho, INSERT_VALUES, lrho_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), rho, INSERT_VALUES, lrho_));
  const PetscScalar** r;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(MatZeroEntries(M_));
  const double ihx2 = 1.0 / (b.hx * b.hx), ihy2 = 1.0 / (b.hy * b.hy);
  MatStencil row, col[5];
  PetscScalar val[5];
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      row.i = i; row.j = j; row.k = 0; row.c = 0;
      int n = 0;
      double diag = 0;
      auto add = [&](PetscInt ii, PetscInt jj, double beta) {  // beta = (1/rho_face)/h^2
        col[n].i = ii; col[n].j = jj; col[n].k = 0; col[n].c = 0; val[n] = -beta; ++n;
        diag += beta;
      };
      // Wall faces carry no flux (u.n = 0, eq. 20 and (u^{n+1} - u~).n = 0 in eq. 32). With
      // periodic x, cell 0 couples to cell nx-1 (the column -1 / nx wraps; rho from the ghosts).
      // The same (i, j, k = 0) stencils fill the AIJ matrix of dm_pres and the MATHYPRESTRUCT
      // one of the 3D DMDA (PFMG); the z entries of the latter stay zero.
      // The gate's faces: times their open part (boundary/Gate.hpp).
      if (!b.wall_u(i)) add(i - 1, j, aperture(i, j) * ihx2 / ops::rho_xface(r, i, j));
      if (!b.wall_u(i + 1)) add(i + 1, j, aperture(i + 1, j) * ihx2 / ops::rho_xface(r, i + 1, j));
      if (j > 0) add(i, j - 1, ihy2 / ops::rho_yface(r, i, j));
      if (j + 1 < b.ny) add(i, j + 1, ihy2 / ops::rho_yface(r, i, j + 1));
      col[n] = row;
      val[n] = diag;
      ++n;
      GF_PETSC(MatSetValuesStencil(M_, 1, &row, n, col, val, INSERT_VALUES));
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(MatAssemblyBegin(M_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(M_, MAT_FINAL_ASSEMBLY));
  ksp_->set_operator(M_);
}

int Projector::project(Vec vel, Vec p, Vec rho, double a0, double dt) {
  const Box& b = g_.box();
  // Right-hand side -(a0/dt) div u~, made consistent with the null space.
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_vel(), vel, INSERT_VALUES, lvel_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_vel(), vel, INSERT_VALUES, lvel_));
  {
    Vel** lv;
    PetscScalar** f;
    GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &lv));
    fill_velocity_ghosts(g_, lv);
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), rhs_, &f));
    ops::divergence(b, lv, f);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) f[j][i] *= -a0 / dt;
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), rhs_, &f));
    GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &lv));
  }
  GF_PETSC(MatNullSpaceRemove(null_, rhs_));
  GF_PETSC(VecSet(psi_, 0.0));
  // CG that breaks down is solved again with GMRES (linsolve/Krylov.hpp; counted in summary.json).
  const int its = ksp_->solve(rhs_, psi_);
  fell_back_ = ksp_->fell_back();

  // Velocity correction u = u~ - (dt/a0) (1/rho_face) grad psi on the interior faces.
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), psi_, INSERT_VALUES, lpsi_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), psi_, INSERT_VALUES, lpsi_));
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), rho, INSERT_VALUES, lrho_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), rho, INSERT_VALUES, lrho_));
  const PetscScalar **ps, **r;
  Vel** u;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lpsi_, &ps));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), vel, &u));
  const double k = dt / a0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (!b.wall_u(i))
        u[j][i].u -= aperture(i, j) * k * (ps[j][i] - ps[j][i - 1]) / (b.hx * ops::rho_xface(r, i, j));
      else u[j][i].u = 0.0;
      if (j > 0) u[j][i].v -= k * (ps[j][i] - ps[j - 1][i]) / (b.hy * ops::rho_yface(r, i, j));
      else u[j][i].v = 0.0;
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), vel, &u));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lpsi_, &ps));

  // p^{n+1} = p^n + psi, then the level: the mean pressure ON the top boundary y = Ly, linearly
  // extrapolated from the last two rows of cells (p_wall = (3 p_{ny-1} - p_{ny-2}) / 2), is zero.
  // At the wall, not at the first cell centre: where the top is the free surface of a layer
  // (an incline with a free-slip lid), a half-cell offset would leave the top row of cells with
  // no pressure and so no Drucker-Prager yield stress (eq. 19). Ranks own >= 3 rows each, so
  // both rows are local to the top ranks.
  add_increment(psi_, p);
  return its;
}

void Projector::add_increment(Vec psi, Vec p) const {
  GF_PETSC(VecAXPY(p, 1.0, psi));
  ops::set_pressure_level(g_, p);
}

}  // namespace gf::projection
