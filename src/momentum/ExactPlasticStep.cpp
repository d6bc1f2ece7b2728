// One step's plastic problem solved exactly: the method of multipliers with a semismooth Newton
// inner solve (see ExactPlasticStep.hpp).
#include "momentum/ExactPlasticStep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/Error.hpp"
#include "grid/Local.hpp"

namespace gf::momentum {

namespace {
// One point's linearisation of s = P(s + c x), P the projection on the unit disc (a cell's S
// with x = E u, a cell's side-wall friction with x = U; see solve_newton in the header).
struct DiscLinearisation {
  double r;        // |s - P(s + c x)| at the iterate itself
  double nqr;      // |s + c x| there
  bool rigid;      // |q| <= 1 (rigid, sticking), q = P(s) + c x (retracted) or s + c x
  double G[2][2];  // s_{k+1} = s0 + G x_{k+1}
  double s0[2];
};
// retract: linearise at P(s), s retracted onto the unit disc (ExactStepOptions::retract);
// rigid_step: the rigid class's step (c_R); gap_floor: ExactStepOptions::gap_floor.
DiscLinearisation linearise_disc(const double s[2], const double x[2], double c, bool retract,
                                 double rigid_step, double gap_floor) {
  DiscLinearisation o{};
  const double qr[2] = {s[0] + c * x[0], s[1] + c * x[1]};
  o.nqr = std::hypot(qr[0], qr[1]);
  const double f = o.nqr > 1 ? 1 / o.nqr : 1.0;
  o.r = std::hypot(s[0] - f * qr[0], s[1] - f * qr[1]);
  // The linearisation at s retracted onto the unit ball, P(s): after a yielded point's Newton
  // step s sits on the tangent line, outside the ball by about half its rotation squared, and
  // |q| - 1 measured from there, not from c n.x, made gamma 4 to 100 times too small in the
  // cells at their yield limit.
  const double ns = std::hypot(s[0], s[1]);
  const double fs = retract && ns > 1 ? 1 / ns : 1.0;
  const double sl[2] = {fs * s[0], fs * s[1]};
  const double q[2] = {sl[0] + c * x[0], sl[1] + c * x[1]};
  const double nq = std::hypot(q[0], q[1]);
  o.rigid = nq <= 1;
  if (o.rigid) {  // x = 0 in its augmented form, step rigid_step
    o.G[0][0] = o.G[1][1] = rigid_step;
    o.s0[0] = sl[0];
    o.s0[1] = sl[1];
  } else {  // yielded or sliding: Newton on s = q / |q|
    const double n[2] = {q[0] / nq, q[1] / nq};
    const double gam = c / std::max(nq - 1, gap_floor);
    o.G[0][0] = gam * (1 - n[0] * n[0]);
    o.G[0][1] = o.G[1][0] = -gam * n[0] * n[1];
    o.G[1][1] = gam * (1 - n[1] * n[1]);
    o.s0[0] = n[0];
    o.s0[1] = n[1];
  }
  return o;
}

// The 3 x 3 block of a cell in M = Pi scale G L (dm_ten numbering from base), with
// L = [[1/2, 0, -1/2], [0, 1, 0]] (the deviatoric strain rate (Dxx - Dyy)/2, Dxy) and Pi the
// rows sxx, sxy, -sxx of the traceless tensor. Every entry is set, so the pattern stays.
void set_cell_block(Mat M, PetscInt base, double scale, const double G[2][2]) {
  double GL[2][3];
  for (int a = 0; a < 2; ++a) {
    GL[a][0] = scale * 0.5 * G[a][0];
    GL[a][1] = scale * G[a][1];
    GL[a][2] = -scale * 0.5 * G[a][0];
  }
  const PetscInt idx[3] = {base, base + 1, base + 2};
  const double vals[9] = {GL[0][0], GL[0][1], GL[0][2], GL[1][0], GL[1][1],
                          GL[1][2], -GL[0][0], -GL[0][1], -GL[0][2]};
  GF_PETSC(MatSetValues(M, 3, idx, 3, idx, vals, INSERT_VALUES));
}
// A KSP that solves by one factorisation (MUMPS; LU here, solve_newton may make it Cholesky),
// options prefix `prefix`.
void make_direct_ksp(MPI_Comm comm, const char* prefix, KSP* ksp) {
  GF_PETSC(KSPCreate(comm, ksp));
  GF_PETSC(KSPSetOptionsPrefix(*ksp, prefix));
  GF_PETSC(KSPSetType(*ksp, KSPPREONLY));
  PC pc;
  GF_PETSC(KSPGetPC(*ksp, &pc));
  GF_PETSC(PCSetType(pc, PCLU));
  GF_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
}
// Flags M symmetric positive definite for good (its values change, its kind does not): MUMPS
// then factorises it by Cholesky without pivoting (SYM = 1).
void set_spd(Mat M) {
  GF_PETSC(MatSetOption(M, MAT_SPD, PETSC_TRUE));
  GF_PETSC(MatSetOption(M, MAT_SPD_ETERNAL, PETSC_TRUE));
}
// The MUMPS factor of a direct KSP's PC, or nullptr if it factorises with another solver.
Mat mumps_factor(KSP ksp) {
  PC pc;
  GF_PETSC(KSPGetPC(ksp, &pc));
  MatSolverType type = nullptr;
  GF_PETSC(PCFactorGetMatSolverType(pc, &type));
  if (!type || std::string(type) != MATSOLVERMUMPS) return nullptr;
  Mat F = nullptr;
  GF_PETSC(PCFactorGetMatrix(pc, &F));
  return F;
}
// Why a direct solve failed: the PC's reason and, from MUMPS, INFOG(1) and INFOG(2) (the
// error and its detail, e.g. -9: the workspace ICNTL(14) too small; -10: a singular matrix).
std::string lu_failure(KSP ksp) {
  PC pc;
  GF_PETSC(KSPGetPC(ksp, &pc));
  PCFailedReason pr;
  GF_PETSC(PCGetFailedReason(pc, &pr));
  std::string s = std::string("PC: ") + PCFailedReasons[pr];
  if (Mat F = mumps_factor(ksp)) {
    PetscInt g1 = 0, g2 = 0;
    GF_PETSC(MatMumpsGetInfog(F, 1, &g1));
    GF_PETSC(MatMumpsGetInfog(F, 2, &g2));
    s += ", MUMPS INFOG(1) = " + std::to_string(g1) + ", INFOG(2) = " + std::to_string(g2);
  }
  return s;
}
// KSPSolve with the direct solver, and once more with twice the workspace each time MUMPS
// runs out of it (INFOG(1) = -9 or -8: delayed pivots beyond the analysis' estimate plus
// ICNTL(14) percent, default 20; case B at n = 128 with the exact solver, the local rows,
// step 96, wanted 10,044 more entries). The answer does not depend on the workspace. A
// Cholesky factorisation that fails otherwise is replaced by LU (*to_lu set). Gives the
// solve's reason; a failure of another kind is left to the caller.
KSPConvergedReason direct_solve(KSP ksp, Mat J, Vec rhs, Vec x, bool* to_lu = nullptr) {
  GF_PETSC(KSPSetOperators(ksp, J, J));
  GF_PETSC(KSPSolve(ksp, rhs, x));
  KSPConvergedReason why;
  GF_PETSC(KSPGetConvergedReason(ksp, &why));
  for (int retry = 0; why < 0 && retry < 6; ++retry) {
    const Mat F = mumps_factor(ksp);
    if (!F) break;
    PetscInt g1 = 0, pct = 0;
    GF_PETSC(MatMumpsGetInfog(F, 1, &g1));
    PC pc;
    GF_PETSC(KSPGetPC(ksp, &pc));
    PCType type;
    GF_PETSC(PCGetType(pc, &type));
    if (g1 < 0 && g1 != -9 && g1 != -8 && std::string(type) == PCCHOLESKY) {
      // A Cholesky factorisation without pivoting (MUMPS SYM = 1, the matrix flagged SPD) that
      // fails for another reason than its workspace: LU from here on, for this KSP.
      PetscPrintf(PetscObjectComm(reinterpret_cast<PetscObject>(ksp)),
                  "granflow: note: the exact plastic step's Cholesky factorisation (MUMPS) "
                  "failed (INFOG(1) = %d); LU from here on\n",
                  static_cast<int>(g1));
      GF_PETSC(PCReset(pc));
      GF_PETSC(PCSetType(pc, PCLU));
      GF_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      GF_PETSC(KSPSetOperators(ksp, J, J));
      GF_PETSC(KSPSolve(ksp, rhs, x));
      GF_PETSC(KSPGetConvergedReason(ksp, &why));
      if (to_lu) *to_lu = true;
      continue;
    }
    if (g1 != -9 && g1 != -8) break;
    GF_PETSC(MatMumpsGetIcntl(F, 14, &pct));
    const PetscInt more = std::max<PetscInt>(2 * pct, 40);
    PetscPrintf(PetscObjectComm(reinterpret_cast<PetscObject>(ksp)),
                "granflow: note: the exact plastic step's factorisation (MUMPS) ran out of "
                "workspace (INFOG(1) = %d); factorising again with ICNTL(14) = %d %% (was %d)\n",
                static_cast<int>(g1), static_cast<int>(more), static_cast<int>(pct));
    // A new factor from a new analysis: PETSc 3.18's MUMPS interface skips the numerical
    // factorisation of a factor whose last phase failed (INFOG(1) < 0), and MUMPS reads its
    // ICNTL from the options database (under the KSP's prefix) at the analysis. The larger
    // workspace stays for the rest of the run (both KSPs with this prefix).
    const char* prefix = nullptr;
    GF_PETSC(KSPGetOptionsPrefix(ksp, &prefix));
    const std::string key = "-" + std::string(prefix ? prefix : "") + "mat_mumps_icntl_14";
    GF_PETSC(PetscOptionsSetValue(nullptr, key.c_str(), std::to_string(more).c_str()));
    GF_PETSC(PCReset(pc));
    GF_PETSC(KSPSetOperators(ksp, J, J));
    GF_PETSC(KSPSolve(ksp, rhs, x));
    GF_PETSC(KSPGetConvergedReason(ksp, &why));
  }
  return why;
}
}  // namespace

void saddle_blocks(const Grid& g, NewtonPressure& p) {
  const Box& b = g.box();
  PetscInt nv, nc, vx, vy, vm, cx, cy, cm;
  {
    Vec t;
    GF_PETSC(DMGetGlobalVector(g.dm_vel(), &t));
    GF_PETSC(VecGetLocalSize(t, &nv));
    GF_PETSC(DMRestoreGlobalVector(g.dm_vel(), &t));
    GF_PETSC(DMGetGlobalVector(g.dm_cell(), &t));
    GF_PETSC(VecGetLocalSize(t, &nc));
    GF_PETSC(DMRestoreGlobalVector(g.dm_cell(), &t));
  }
  GF_PETSC(DMDAGetGhostCorners(g.dm_vel(), &vx, &vy, nullptr, &vm, nullptr, nullptr));
  GF_PETSC(DMDAGetGhostCorners(g.dm_cell(), &cx, &cy, nullptr, &cm, nullptr, nullptr));
  // Local (ghosted) indices: the DMs' local-to-global maps wrap a periodic x.
  auto vel = [&](PetscInt i, PetscInt j, int q) { return ((j - vy) * vm + (i - vx)) * 2 + q; };
  auto cell = [&](PetscInt i, PetscInt j) { return (j - cy) * cm + (i - cx); };
  ISLocalToGlobalMapping lv, lc;
  GF_PETSC(DMGetLocalToGlobalMapping(g.dm_vel(), &lv));
  GF_PETSC(DMGetLocalToGlobalMapping(g.dm_cell(), &lc));
  const MPI_Comm comm = g.comm();
  GF_PETSC(MatCreateAIJ(comm, nv, nc, PETSC_DETERMINE, PETSC_DETERMINE, 2, nullptr, 2, nullptr,
                        &p.G));
  GF_PETSC(MatCreateAIJ(comm, nc, nv, PETSC_DETERMINE, PETSC_DETERMINE, 4, nullptr, 4, nullptr,
                        &p.Dv));
  GF_PETSC(MatCreateAIJ(comm, nc, nc, PETSC_DETERMINE, PETSC_DETERMINE, 1, nullptr, 0, nullptr,
                        &p.Z));
  GF_PETSC(MatSetLocalToGlobalMapping(p.G, lv, lc));
  GF_PETSC(MatSetLocalToGlobalMapping(p.Dv, lc, lv));
  GF_PETSC(MatSetLocalToGlobalMapping(p.Z, lc, lc));
  const double ihx = 1.0 / b.hx, ihy = 1.0 / b.hy;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      // The gradient on the u-face i and the v-face j of the cell (wall faces: none, their rows
      // of A keep u = 0).
      if (!b.wall_u(i)) {
        const PetscInt r = vel(i, j, 0), c[2] = {cell(i - 1, j), cell(i, j)};
        const double v[2] = {-ihx, ihx};
        GF_PETSC(MatSetValuesLocal(p.G, 1, &r, 2, c, v, INSERT_VALUES));
      }
      if (j > 0) {
        const PetscInt r = vel(i, j, 1), c[2] = {cell(i, j - 1), cell(i, j)};
        const double v[2] = {-ihy, ihy};
        GF_PETSC(MatSetValuesLocal(p.G, 1, &r, 2, c, v, INSERT_VALUES));
      }
      const PetscInt r = cell(i, j);
      // Every diagonal entry of Z is in its pattern (solve_saddle sets the rigid cells').
      const double zd = (i == 0 && j == 0) ? 1.0 : 0.0;
      GF_PETSC(MatSetValuesLocal(p.Z, 1, &r, 1, &r, &zd, INSERT_VALUES));
      if (i == 0 && j == 0) continue;
      // div u = (u_{i+1} - u_i) / hx + (v_{j+1} - v_j) / hy over the faces that are not walls.
      PetscInt c[4];
      double v[4];
      int n = 0;
      if (!b.wall_u(i)) { c[n] = vel(i, j, 0); v[n++] = -ihx; }
      if (!b.wall_u(i + 1)) { c[n] = vel(i + 1, j, 0); v[n++] = ihx; }
      if (j > 0) { c[n] = vel(i, j, 1); v[n++] = -ihy; }
      if (j + 1 < b.ny) { c[n] = vel(i, j + 1, 1); v[n++] = ihy; }
      GF_PETSC(MatSetValuesLocal(p.Dv, 1, &r, n, c, v, INSERT_VALUES));
    }
  for (Mat M : {p.G, p.Dv, p.Z}) {
    GF_PETSC(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
    GF_PETSC(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  }
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &p.psi));
}

ExactPlasticStep::ExactPlasticStep(const Grid& g) : g_(g) {
  GF_PETSC(SNESCreate(g.comm(), &snes_));
  GF_PETSC(SNESSetOptionsPrefix(snes_, "exact_"));
  GF_PETSC(SNESSetType(snes_, SNESNEWTONLS));
  KSP ksp;
  PC pc;
  GF_PETSC(SNESGetKSP(snes_, &ksp));
  GF_PETSC(KSPSetType(ksp, KSPPREONLY));
  GF_PETSC(KSPGetPC(ksp, &pc));
  GF_PETSC(PCSetType(pc, PCLU));
  // PETSc's own LU is serial; on more ranks MUMPS (in Debian's petsc-dev).
  if (g.size() > 1) GF_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &lambda_));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &D_));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &T_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &CT_));
  for (Vec* v : {&rhs_, &u_prev_, &u_newton_, &wdiag_, &wrhs_, &sw_prev_, &sw_newton_, &kb_old_})
    GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
  for (Vec* v : {&S_prev_, &S_newton_, &S_best_}) GF_PETSC(DMCreateGlobalVector(g.dm_ten(), v));
  for (Vec* v : {&u_best_, &sw_best_}) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
  // MUMPS also on one rank: its factorisation of the Newton matrix (the plastic coupling
  // C M B widens the rows) took 18 ms where PETSc's own took 40 ms (Coulomb block, 120 x 30).
  make_direct_ksp(g.comm(), "exactpd_", &ksp_);
  make_direct_ksp(g.comm(), "exactpd_", &ksp_loc_);  // the same solver on the local rows
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &work_vel_));
  make_direct_ksp(g.comm(), "exactpd_sp_", &ksp_sp_);
  for (Vec* v : {&psi_prev_, &psi_newton_}) GF_PETSC(DMCreateGlobalVector(g.dm_cell(), v));
}

void ExactPlasticStep::side_matrices() {
  const Box& b = g_.box();
  if (!I_) {
    for (Vec* v : {&srhs_, &ks0_, &Us_, &ss_prev_, &ss_newton_, &ss_best_})
      GF_PETSC(DMCreateGlobalVector(g_.dm_vel(), v));
    // I: U_x of cell (i, j) = (u(i, j) + u(i + 1, j)) / 2, U_y = (v(i, j) + v(i, j + 1)) / 2
    // (grid/Local.hpp cell_centre_velocity), over the faces that are unknowns: the wall faces
    // (u at i = 0 and nx without periodic x, v at j = 0 and ny) are not, and their values
    // enter the linearisation as a constant (linearise_side). Indices through the DM's
    // local-to-global map, which wraps the periodic seam.
    PetscInt n, gxs, gys, gxm, gym;
    GF_PETSC(VecGetLocalSize(Us_, &n));
    GF_PETSC(DMDAGetGhostCorners(g_.dm_vel(), &gxs, &gys, nullptr, &gxm, &gym, nullptr));
    ISLocalToGlobalMapping l2g;
    GF_PETSC(DMGetLocalToGlobalMapping(g_.dm_vel(), &l2g));
    GF_PETSC(MatCreateAIJ(g_.comm(), n, n, PETSC_DETERMINE, PETSC_DETERMINE, 2, nullptr, 2,
                          nullptr, &I_));
    GF_PETSC(MatSetLocalToGlobalMapping(I_, l2g, l2g));
    const auto loc = [&](PetscInt i, PetscInt j, int comp) {
      return ((j - gys) * gxm + (i - gxs)) * 2 + comp;
    };
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        PetscInt row = loc(i, j, 0), cols[2];
        const PetscScalar half[2] = {0.5, 0.5};
        int nc = 0;
        if (!b.wall_u(i)) cols[nc++] = loc(i, j, 0);
        if (!b.wall_u(i + 1)) cols[nc++] = loc(i + 1, j, 0);
        if (nc) GF_PETSC(MatSetValuesLocal(I_, 1, &row, nc, cols, half, INSERT_VALUES));
        row = loc(i, j, 1);
        nc = 0;
        if (j >= 1) cols[nc++] = loc(i, j, 1);
        if (j + 1 <= b.ny - 1) cols[nc++] = loc(i, j + 1, 1);
        if (nc) GF_PETSC(MatSetValuesLocal(I_, 1, &row, nc, cols, half, INSERT_VALUES));
      }
    GF_PETSC(MatAssemblyBegin(I_, MAT_FINAL_ASSEMBLY));
    GF_PETSC(MatAssemblyEnd(I_, MAT_FINAL_ASSEMBLY));
  }
  // Ms: a 2 x 2 block in each cell with k > 0 (the step's k is fixed), so that SIDE_ = I^T Ms I
  // and J's pattern cover only the cells the friction acts on.
  MatDestroy(&Ms_);
  MatDestroy(&SIDE_);
  PetscInt n, r0;
  GF_PETSC(VecGetLocalSize(Us_, &n));
  GF_PETSC(VecGetOwnershipRange(Us_, &r0, nullptr));
  GF_PETSC(MatCreateAIJ(g_.comm(), n, n, PETSC_DETERMINE, PETSC_DETERMINE, 2, nullptr, 0, nullptr,
                        &Ms_));
  const PetscScalar* k;
  GF_PETSC(VecGetArrayRead(side_->k, &k));
  const PetscScalar zero[4] = {0, 0, 0, 0};
  for (PetscInt c = 0; c < b.xm * b.ym; ++c)
    if (k[c] > 0) {
      const PetscInt rc[2] = {r0 + 2 * c, r0 + 2 * c + 1};
      GF_PETSC(MatSetValues(Ms_, 2, rc, 2, rc, zero, INSERT_VALUES));
    }
  GF_PETSC(VecRestoreArrayRead(side_->k, &k));
  GF_PETSC(MatAssemblyBegin(Ms_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(Ms_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatSetOption(Ms_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  GF_PETSC(MatPtAP(Ms_, I_, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &SIDE_));
}

void ExactPlasticStep::make_M(bool granular_only) {
  MatDestroy(&M_);
  PetscInt n, r0;
  GF_PETSC(VecGetLocalSize(D_, &n));
  GF_PETSC(VecGetOwnershipRange(D_, &r0, nullptr));
  GF_PETSC(MatCreateAIJ(g_.comm(), n, n, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr,
                        &M_));
  const Box& b = g_.box();
  const PetscScalar** k;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa_, &k));
  const double zero[2][2] = {{0, 0}, {0, 0}};
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      if (!granular_only || k[j][i] > 0)
        set_cell_block(M_, r0 + ((j - b.ys) * b.xm + (i - b.xs)) * 3, 0.0, zero);
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(MatAssemblyBegin(M_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(M_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatSetOption(M_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
}

ExactPlasticStep::~ExactPlasticStep() {
  SNESDestroy(&snes_);
  KSPDestroy(&ksp_);
  KSPDestroy(&ksp_sp_);
  KSPDestroy(&ksp_loc_);
  ISDestroy(&is_loc_);
  MatDestroy(&Jloc_);
  VecDestroy(&work_vel_);
  for (Vec* v : {&u_best_, &S_best_, &sw_best_}) VecDestroy(v);
  for (Vec* v : {&srhs_, &ks0_, &Us_, &ss_prev_, &ss_newton_, &ss_best_}) VecDestroy(v);
  MatDestroy(&I_);
  MatDestroy(&Ms_);
  MatDestroy(&SIDE_);
  MatDestroy(&K_);
  MatDestroy(&Zk_);
  for (Vec* v : {&X_, &R_, &psi_prev_, &psi_newton_, &zdiag_}) VecDestroy(v);
  for (Vec* v : {&rhs_, &u_prev_, &u_newton_, &S_prev_, &S_newton_, &wdiag_, &wrhs_, &sw_prev_,
                 &sw_newton_, &kb_old_})
    VecDestroy(v);
  MatDestroy(&J_);
  MatDestroy(&AJ_);
  MatDestroy(&CMB_);
  MatDestroy(&M_);
  VecDestroy(&lambda_);
  VecDestroy(&D_);
  VecDestroy(&T_);
  VecDestroy(&CT_);
}

// T = Pi kappa P(lambda + c E u) and, with jacobian, its derivative M = Pi kappa c P'(q) L in
// the dm_ten numbering (a 3 x 3 block per cell, every entry set so that the pattern stays).
void ExactPlasticStep::plastic_stress(Vec u, Vec T, bool jacobian) {
  const Box& b = g_.box();
  GF_PETSC(MatMultAdd(m_->B, u, m_->d0, D_));
  const PetscScalar ***d, ***lam, **k, **c;
  PetscScalar*** t;
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), D_, &d));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), lambda_, &lam));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), c_, &c));
  GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), T, &t));
  PetscInt r0;
  GF_PETSC(VecGetOwnershipRange(D_, &r0, nullptr));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double kk = k[j][i] > 0 ? k[j][i] : 0.0;
      const double q0 = lam[j][i][0] + c[j][i] * 0.5 * (d[j][i][0] - d[j][i][2]);
      const double q1 = lam[j][i][1] + c[j][i] * d[j][i][1];
      const double nq = std::hypot(q0, q1);
      const double f = nq > 1 ? 1 / nq : 1.0;
      t[j][i][0] = kk * f * q0;
      t[j][i][1] = kk * f * q1;
      t[j][i][2] = -kk * f * q0;
      if (!jacobian) continue;
      // G = kappa c P'(q): I inside the ball, (I - n n^T) / |q| outside.
      double G[2][2] = {{1, 0}, {0, 1}};
      if (nq > 1) {
        const double n0 = q0 / nq, n1 = q1 / nq;
        G[0][0] = (1 - n0 * n0) / nq;
        G[0][1] = G[1][0] = -n0 * n1 / nq;
        G[1][1] = (1 - n1 * n1) / nq;
      }
      set_cell_block(M_, r0 + ((j - b.ys) * b.xm + (i - b.xs)) * 3, kk * c[j][i], G);
    }
  GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), T, &t));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), c_, &c));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), lambda_, &lam));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), D_, &d));
  if (jacobian) {
    GF_PETSC(MatAssemblyBegin(M_, MAT_FINAL_ASSEMBLY));
    GF_PETSC(MatAssemblyEnd(M_, MAT_FINAL_ASSEMBLY));
  }
}

PetscErrorCode ExactPlasticStep::residual(SNES, Vec u, Vec F, void* ctx) {
  auto* self = static_cast<ExactPlasticStep*>(ctx);
  try {
    self->plastic_stress(u, self->T_, false);
    GF_PETSC(MatMult(self->A_, u, F));
    GF_PETSC(VecAXPY(F, -1.0, self->b_));
    GF_PETSC(MatMult(self->m_->C, self->T_, self->CT_));
    GF_PETSC(VecAXPY(F, -1.0, self->CT_));
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
  return 0;
}

// J = A - C M B.
PetscErrorCode ExactPlasticStep::jacobian(SNES, Vec u, Mat J, Mat, void* ctx) {
  auto* self = static_cast<ExactPlasticStep*>(ctx);
  try {
    self->plastic_stress(u, self->T_, true);
    GF_PETSC(MatMatMatMult(self->m_->C, self->M_, self->m_->B, MAT_REUSE_MATRIX, PETSC_DEFAULT,
                           &self->CMB_));
    self->fill_jacobian();  // J is J_
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
  return 0;
}

void ExactPlasticStep::jacobian_pattern(Mat A) {
  MatDestroy(&CMB_);
  MatDestroy(&J_);
  MatDestroy(&AJ_);
  GF_PETSC(MatMatMatMult(m_->C, M_, m_->B, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &CMB_));
  GF_PETSC(MatDuplicate(CMB_, MAT_DO_NOT_COPY_VALUES, &J_));
  if (side_) {  // the side walls' pattern too, with zeros (AJ_ must hold A's values alone)
    Mat z;
    GF_PETSC(MatDuplicate(SIDE_, MAT_DO_NOT_COPY_VALUES, &z));
    GF_PETSC(MatAXPY(J_, 1.0, z, DIFFERENT_NONZERO_PATTERN));
    MatDestroy(&z);
  }
  GF_PETSC(MatAXPY(J_, 1.0, A, DIFFERENT_NONZERO_PATTERN));  // A in the union of the patterns
  GF_PETSC(MatDuplicate(J_, MAT_COPY_VALUES, &AJ_));
  if (spd_) set_spd(J_);
  map_.clear();  // fill_jacobian's map, for this pattern
  map_built_ = false;
}

bool ExactPlasticStep::newton_matrix_symmetric(Mat A) {
  // J = A - C M B with M = Pi kappa G L per cell: symmetric for every G (symmetric in each cell)
  // when A is and C = -B^T W on the columns of the cells with a yield stress (W = diag(1, 2, 1);
  // PlasticMatrices.hpp). Checked on B and C themselves, not on J: a J of one iteration can
  // hide the difference (a yielded cell at a no-slip wall in pure shear has G's shear column
  // near 0, and can turn rigid later in the step).
  if (!a_checked_) {  // A's pattern and kind are the run's; its values change every step
    a_checked_ = true;
    PetscBool sym = PETSC_FALSE;
    GF_PETSC(MatIsSymmetric(A, 1e-12, &sym));
    a_symmetric_ = sym;
  }
  if (!a_symmetric_) return false;
  Vec w, mask;
  GF_PETSC(VecDuplicate(lambda_, &w));
  GF_PETSC(VecDuplicate(lambda_, &mask));
  {
    const Box& b = g_.box();
    const PetscScalar** k;
    PetscScalar ***ww, ***mm;
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa_, &k));
    GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), w, &ww));
    GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), mask, &mm));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double on = k[j][i] > 0 ? 1.0 : 0.0;
        mm[j][i][0] = mm[j][i][1] = mm[j][i][2] = on;
        ww[j][i][0] = ww[j][i][2] = on;
        ww[j][i][1] = 2 * on;
      }
    GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), mask, &mm));
    GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), w, &ww));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa_, &k));
  }
  Mat E, Bt;
  GF_PETSC(MatTranspose(m_->B, MAT_INITIAL_MATRIX, &Bt));
  GF_PETSC(MatDiagonalScale(Bt, nullptr, w));  // B^T W on the grains' columns
  GF_PETSC(MatDuplicate(m_->C, MAT_COPY_VALUES, &E));
  GF_PETSC(MatDiagonalScale(E, nullptr, mask));
  PetscReal cn, en;
  GF_PETSC(MatNorm(E, NORM_INFINITY, &cn));
  GF_PETSC(MatAXPY(E, 1.0, Bt, DIFFERENT_NONZERO_PATTERN));
  GF_PETSC(MatNorm(E, NORM_INFINITY, &en));
  GF_PETSC(MatDestroy(&E));
  GF_PETSC(MatDestroy(&Bt));
  GF_PETSC(VecDestroy(&w));
  GF_PETSC(VecDestroy(&mask));
  return en <= 1e-12 * cn;
}

void ExactPlasticStep::use_lu() {
  cholesky_failed_ = true;
  spd_ = false;
  set_factorisation(ksp_);
  set_factorisation(ksp_loc_);
}

void ExactPlasticStep::set_factorisation(KSP k) {
  if (!pc_auto_) return;
  PC pc;
  GF_PETSC(KSPGetPC(k, &pc));
  GF_PETSC(PCSetType(pc, spd_ ? PCCHOLESKY : PCLU));
  GF_PETSC(PCFactorSetMatSolverType(pc, solver_.c_str()));
}

namespace {
// The local blocks of an AIJ matrix: (diag, offdiag, garray) on more ranks; (M, null, null) on
// one.
void local_blocks(Mat M, Mat* d, Mat* o, const PetscInt** garray) {
  PetscBool mpi = PETSC_FALSE;
  GF_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(M), MATMPIAIJ, &mpi));
  if (mpi) {
    GF_PETSC(MatMPIAIJGetSeqAIJ(M, d, o, garray));
  } else {
    *d = M;
    *o = nullptr;
    *garray = nullptr;
  }
}
// For each entry of the SeqAIJ block `sub`, the index of the same (row, column) in `big`'s
// value array, appended to map; columns through the garrays if given (global columns).
void subset_map(Mat sub, const PetscInt* gsub, Mat big, const PetscInt* gbig,
                std::vector<PetscInt>& map) {
  const PetscInt *si, *sj, *bi, *bj;
  PetscInt ns, nb;
  PetscBool ok1, ok2;
  GF_PETSC(MatGetRowIJ(sub, 0, PETSC_FALSE, PETSC_FALSE, &ns, &si, &sj, &ok1));
  GF_PETSC(MatGetRowIJ(big, 0, PETSC_FALSE, PETSC_FALSE, &nb, &bi, &bj, &ok2));
  if (!ok1 || !ok2 || ns != nb) throw RunError("exact plastic step: J's pattern not readable");
  for (PetscInt r = 0; r < ns; ++r) {
    PetscInt k = bi[r];
    for (PetscInt e = si[r]; e < si[r + 1]; ++e) {
      const PetscInt col = gsub ? gsub[sj[e]] : sj[e];
      // Both rows are sorted by local column, and the garrays are increasing, so the global
      // columns are sorted too.
      while (k < bi[r + 1] && (gbig ? gbig[bj[k]] : bj[k]) < col) ++k;
      if (k == bi[r + 1] || (gbig ? gbig[bj[k]] : bj[k]) != col)
        throw RunError("exact plastic step: C M B has an entry outside J's pattern");
      map.push_back(k);
    }
  }
  GF_PETSC(MatRestoreRowIJ(sub, 0, PETSC_FALSE, PETSC_FALSE, &ns, &si, &sj, &ok1));
  GF_PETSC(MatRestoreRowIJ(big, 0, PETSC_FALSE, PETSC_FALSE, &nb, &bi, &bj, &ok2));
}
}  // namespace

void ExactPlasticStep::fill_jacobian() {
  GF_PETSC(MatCopy(AJ_, J_, SAME_NONZERO_PATTERN));
  // J_ -= CMB_ entry by entry through map_ (MatAXPY with a subset pattern inserts row by row:
  // 1.9 ms per iteration on case A at n = 64, 9 % of the run). The same arithmetic, so the
  // same values.
  Mat jd, jo, cd, co;
  const PetscInt *gj, *gc;
  local_blocks(J_, &jd, &jo, &gj);
  local_blocks(CMB_, &cd, &co, &gc);
  if (!map_built_) {
    map_built_ = true;
    subset_map(cd, nullptr, jd, nullptr, map_);
    map_diag_ = map_.size();
    if (co) subset_map(co, gc, jo, gj, map_);
  }
  const auto sub = [](Mat big, Mat small, const PetscInt* m, size_t n) {
    PetscScalar* bv;
    const PetscScalar* sv;
    GF_PETSC(MatSeqAIJGetArray(big, &bv));
    GF_PETSC(MatSeqAIJGetArrayRead(small, &sv));
    for (size_t e = 0; e < n; ++e) bv[m[e]] -= sv[e];
    GF_PETSC(MatSeqAIJRestoreArrayRead(small, &sv));
    GF_PETSC(MatSeqAIJRestoreArray(big, &bv));
  };
  sub(jd, cd, map_.data(), map_diag_);
  if (co) {
    sub(jo, co, map_.data() + map_diag_, map_.size() - map_diag_);
    // The blocks' states have moved; the parallel matrix's moves with an assembly.
    GF_PETSC(MatAssemblyBegin(J_, MAT_FINAL_ASSEMBLY));
    GF_PETSC(MatAssemblyEnd(J_, MAT_FINAL_ASSEMBLY));
  }
}

ExactStepStats ExactPlasticStep::solve(Mat A, Vec b, const PlasticMatrices& m, Vec kappa, Vec c,
                                       Vec u, Vec S, const ExactStepOptions& opt) {
  A_ = A;
  b_ = b;
  m_ = &m;
  kappa_ = kappa;
  c_ = c;
  GF_PETSC(VecCopy(S, lambda_));
  make_M(false);
  // The Jacobian's pattern: A's and that of C M B with every 3 x 3 block of M full.
  plastic_stress(u, T_, true);
  jacobian_pattern(A);
  Vec F;
  GF_PETSC(VecDuplicate(u, &F));
  GF_PETSC(SNESSetFunction(snes_, F, &ExactPlasticStep::residual, this));
  GF_PETSC(SNESSetJacobian(snes_, J_, J_, &ExactPlasticStep::jacobian, this));
  // The residual's scale: the drive b and the largest plastic force, C Pi kappa (1, 1) (its
  // cancellation against b sets the round-off floor of F).
  double scale;
  {
    double bnorm, tnorm;
    GF_PETSC(VecNorm(b, NORM_2, &bnorm));
    PetscScalar*** t;
    const PetscScalar** k;
    const Box& bx = g_.box();
    GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), T_, &t));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa, &k));
    for (PetscInt j = bx.ys; j < bx.ye(); ++j)
      for (PetscInt i = bx.xs; i < bx.xe(); ++i) {
        const double kk = std::max(k[j][i], 0.0);
        t[j][i][0] = kk;
        t[j][i][1] = kk;
        t[j][i][2] = -kk;
      }
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa, &k));
    GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), T_, &t));
    GF_PETSC(MatMult(m.C, T_, F));
    GF_PETSC(VecNorm(F, NORM_2, &tnorm));
    scale = bnorm + tnorm;
  }
  GF_PETSC(SNESSetTolerances(snes_, 1e-13 * scale, opt.inner_rtol, 0.0, 200, 100000));
  GF_PETSC(SNESSetFromOptions(snes_));

  const Box& bx = g_.box();
  ExactStepStats st;
  for (st.outer = 1; st.outer <= opt.max_outer; ++st.outer) {
    GF_PETSC(SNESSolve(snes_, nullptr, u));
    SNESConvergedReason why;
    PetscInt its;
    GF_PETSC(SNESGetConvergedReason(snes_, &why));
    GF_PETSC(SNESGetIterationNumber(snes_, &its));
    st.newton += static_cast<int>(its);
    double fnorm;
    GF_PETSC(SNESGetFunctionNorm(snes_, &fnorm));
    // A line search that cannot decrease |F| any more at the round-off floor has converged.
    if (why == SNES_DIVERGED_LINE_SEARCH && fnorm <= 1e-10 * scale) why = SNES_CONVERGED_FNORM_ABS;
    if (why < 0)
      throw RunError("exact plastic step: Newton's method failed (" +
                     std::string(SNESConvergedReasons[why]) + ", |F| = " + std::to_string(fnorm) +
                     ") in multiplier update " + std::to_string(st.outer) + "; try -exact_snes_monitor to see it");
    // lambda <- P(lambda + c E u) = T / kappa, and its change.
    plastic_stress(u, T_, false);
    double change = 0;
    {
      PetscScalar*** lam;
      const PetscScalar ***t, **k;
      GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), lambda_, &lam));
      GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), T_, &t));
      GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa, &k));
      for (PetscInt j = bx.ys; j < bx.ye(); ++j)
        for (PetscInt i = bx.xs; i < bx.xe(); ++i) {
          if (k[j][i] <= 0) {
            lam[j][i][0] = lam[j][i][1] = lam[j][i][2] = 0;
            continue;
          }
          const double s0 = t[j][i][0] / k[j][i], s1 = t[j][i][1] / k[j][i];
          change = std::max(change, std::hypot(s0 - lam[j][i][0], s1 - lam[j][i][1]));
          lam[j][i][0] = s0;
          lam[j][i][1] = s1;
          lam[j][i][2] = -s0;
        }
      GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa, &k));
      GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), T_, &t));
      GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), lambda_, &lam));
    }
    st.change = g_.max(change);
    if (st.change <= opt.tol) {
      st.converged = true;
      break;
    }
  }
  st.outer = std::min(st.outer, opt.max_outer);
  GF_PETSC(VecCopy(lambda_, S));
  GF_PETSC(VecDestroy(&F));
  return st;
}


// The linearisation of S = P(S + c E u) at (u, lambda_) (see solve_newton in the header).
ExactPlasticStep::Residual ExactPlasticStep::linearise(Vec u, const ExactStepOptions& opt) {
  worst_ = {};
  const Box& b = g_.box();
  GF_PETSC(MatMultAdd(m_->B, u, m_->d0, D_));
  double wl2 = 0, wmax = 0, wrig = 0;
  const size_t ncell = static_cast<size_t>(b.xm) * b.ym;
  // the cells, then their faces, then the cells' side-wall friction
  if (active_.size() != 4 * ncell) active_.assign(4 * ncell, 0);
  double wchanges = 0;
  if (walls_) {
    wmax = linearise_walls(u, opt, wl2, wchanges, wrig);
  }
  if (side_) wmax = std::max(wmax, linearise_side(u, opt, wl2, wchanges, wrig));
  const PetscScalar ***d, ***d0, ***lam, **k, **c, **cr = nullptr;
  PetscScalar*** t;
  if (c_rigid_) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), c_rigid_, &cr));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), D_, &d));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), m_->d0, &d0));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), lambda_, &lam));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), c_, &c));
  GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), T_, &t));
  PetscInt r0;
  GF_PETSC(VecGetOwnershipRange(D_, &r0, nullptr));
  lin_.assign(static_cast<size_t>(b.xm) * b.ym * 5, 0.0);
  double changes = 0;
  if (pres_) prox_.assign(static_cast<size_t>(b.xm) * b.ym, 0.0);
  // max and sum of squares of |S - P(S + c E u)| (and walls'), and the max over the rigid
  // cells and sticking faces
  double loc[3] = {wmax, wl2, wrig};
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const size_t cell = static_cast<size_t>((j - b.ys) * b.xm + (i - b.xs));
      const double kk = k[j][i] > 0 ? k[j][i] : 0.0;
      double G[2][2] = {{0, 0}, {0, 0}}, s0[2] = {0, 0};
      if (kk > 0) {
        const double cc = c[j][i];
        const double s[2] = {lam[j][i][0], lam[j][i][1]};
        const double e[2] = {0.5 * (d[j][i][0] - d[j][i][2]), d[j][i][1]};
        // Retracted (linearise_disc) not with the pressure: in the unit test's channel with
        // gravity it took 74 iterations instead of 21 (51 with the yielded cells alone
        // retracted). The rigid step: rigid_factor c, or the cell's own c_R.
        const DiscLinearisation dl =
            linearise_disc(s, e, cc, opt.retract && !pres_,
                           boost_ * (cr ? cr[j][i] : opt.rigid_factor * cc), opt.gap_floor);
        // With the pressure, a rigid cell's incompressibility is in its augmented form too
        // (solve_saddle): c |div u| joins its residual (0 in a yielded cell after a solve).
        const double dv = pres_ ? cc * (d[j][i][0] + d[j][i][2]) : 0.0;
        const double r = std::hypot(dl.r, dv);
        if (r > worst_.r) worst_ = {r, static_cast<int>(i), static_cast<int>(j), 0, dl.nqr};
        loc[0] = std::max(loc[0], r);
        loc[1] += r * r;
        const signed char cls = dl.rigid ? 1 : 2;
        if (cls == 1) loc[2] = std::max(loc[2], r);
        if (active_[cell] != 0 && active_[cell] != cls) ++changes;
        active_[cell] = cls;
        if (pres_ && dl.rigid) prox_[cell] = kk * dl.G[0][0];
        for (int a = 0; a < 2; ++a) {
          s0[a] = dl.s0[a];
          for (int bb = 0; bb < 2; ++bb) G[a][bb] = dl.G[a][bb];
        }
      }
      double* l = &lin_[5 * cell];
      l[0] = s0[0];
      l[1] = s0[1];
      l[2] = G[0][0];
      l[3] = G[0][1];
      l[4] = G[1][1];
      // T = Pi kappa (S0 + G L d0); M = Pi kappa G L with L = [[1/2, 0, -1/2], [0, 1, 0]].
      const double ld0[2] = {0.5 * (d0[j][i][0] - d0[j][i][2]), d0[j][i][1]};
      const double tx = kk * (s0[0] + G[0][0] * ld0[0] + G[0][1] * ld0[1]);
      const double ty = kk * (s0[1] + G[1][0] * ld0[0] + G[1][1] * ld0[1]);
      t[j][i][0] = tx;
      t[j][i][1] = ty;
      t[j][i][2] = -tx;
      if (kk > 0) set_cell_block(M_, r0 + static_cast<PetscInt>(cell) * 3, kk, G);
    }
  GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), T_, &t));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), c_, &c));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), lambda_, &lam));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), m_->d0, &d0));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), D_, &d));
  if (cr) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), c_rigid_, &cr));
  GF_PETSC(MatAssemblyBegin(M_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(M_, MAT_FINAL_ASSEMBLY));
  active_changes_ = g_.sum(changes + wchanges);
  return {g_.max(loc[0]), std::sqrt(g_.sum(loc[1])), g_.max(loc[2])};
}

double ExactPlasticStep::refresh_kappa_b(Vec u) {
  GF_PETSC(VecCopy(walls_->kappa_b, kb_old_));
  GF_PETSC(MatMultAdd(m_->B, u, m_->d0, D_));
  walls_->refresh(D_, lambda_, walls_->kappa_b);
  PetscReal kmax, dmax;
  GF_PETSC(VecNorm(walls_->kappa_b, NORM_INFINITY, &kmax));
  GF_PETSC(VecAXPY(kb_old_, -1.0, walls_->kappa_b));
  GF_PETSC(VecNorm(kb_old_, NORM_INFINITY, &dmax));
  return kmax > 0 ? dmax / kmax : 0.0;
}

template <class F>
void ExactPlasticStep::for_wall_faces(F&& f) const {
  const Box& b = g_.box();
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if ((j == 0 || j == b.ny - 1) && !b.wall_u(i)) f(i, j, 0, b.hy);
      if (!b.periodic_x && (i == 0 || i == b.nx - 1) && j >= 1) f(i, j, 1, b.hx);
    }
}

// The walls' part of linearise: linw_, wdiag_, wrhs_; returns the local max of |s_t -
// P_b(s_t + c_b u_t)| and adds its squares to l2.
double ExactPlasticStep::linearise_walls(Vec u, const ExactStepOptions& opt, double& l2,
                                         double& changes, double& rigid) {
  const Box& b = g_.box();
  GF_PETSC(VecSet(wdiag_, 0.0));
  GF_PETSC(VecSet(wrhs_, 0.0));
  const PetscScalar *uu, *kb, *cn, *sw;
  PetscScalar *wd, *wr;
  GF_PETSC(VecGetArrayRead(u, &uu));
  GF_PETSC(VecGetArrayRead(walls_->kappa_b, &kb));
  GF_PETSC(VecGetArrayRead(walls_->c_num, &cn));
  GF_PETSC(VecGetArrayRead(walls_->s_wall, &sw));
  GF_PETSC(VecGetArray(wdiag_, &wd));
  GF_PETSC(VecGetArray(wrhs_, &wr));
  linw_.assign(static_cast<size_t>(b.xm) * b.ym * 4, 0.0);
  double mx = 0;
  for_wall_faces([&](PetscInt i, PetscInt j, int q, double h) {
    const size_t f = static_cast<size_t>(((j - b.ys) * b.xm + (i - b.xs)) * 2 + q);
    if (kb[f] <= 0) return;  // s_t = 0 (linw_ holds 0, 0)
    const double cb = cn[f] / kb[f];
    const double qq = sw[f] + cb * uu[f];
    const double r = std::abs(sw[f] - std::clamp(qq, -1.0, 1.0));
    if (r > worst_.r) worst_ = {r, static_cast<int>(i), static_cast<int>(j), q + 1, qq};
    mx = std::max(mx, r);
    l2 += r * r;
    const bool stick = std::abs(qq) <= 1;
    if (stick) rigid = std::max(rigid, r);
    signed char& cls = active_[static_cast<size_t>(b.xm) * b.ym + f];
    if (cls != 0 && cls != (stick ? 1 : 2)) ++changes;
    cls = stick ? 1 : 2;
    const double s0 = stick ? sw[f] : (qq > 0 ? 1.0 : -1.0);
    const double gg =
        stick ? std::min(boost_, opt.wall_boost_max) * opt.wall_rigid_factor * cb : 0.0;
    linw_[2 * f] = s0;
    linw_[2 * f + 1] = gg;
    wd[f] = kb[f] * gg / h;
    wr[f] = -kb[f] * s0 / h;
  });
  GF_PETSC(VecRestoreArray(wrhs_, &wr));
  GF_PETSC(VecRestoreArray(wdiag_, &wd));
  GF_PETSC(VecRestoreArrayRead(walls_->s_wall, &sw));
  GF_PETSC(VecRestoreArrayRead(walls_->c_num, &cn));
  GF_PETSC(VecRestoreArrayRead(walls_->kappa_b, &kb));
  GF_PETSC(VecRestoreArrayRead(u, &uu));
  return mx;
}

void ExactPlasticStep::newton_update_walls(Vec u) {
  const Box& b = g_.box();
  const PetscScalar* uu;
  PetscScalar* sw;
  GF_PETSC(VecGetArrayRead(u, &uu));
  GF_PETSC(VecGetArray(walls_->s_wall, &sw));
  for_wall_faces([&](PetscInt i, PetscInt j, int q, double) {
    const size_t f = static_cast<size_t>(((j - b.ys) * b.xm + (i - b.xs)) * 2 + q);
    sw[f] = linw_[2 * f] + linw_[2 * f + 1] * uu[f];
  });
  GF_PETSC(VecRestoreArray(walls_->s_wall, &sw));
  GF_PETSC(VecRestoreArrayRead(u, &uu));
}

// The side walls' part of linearise (see NewtonSide): lins_, Ms_, srhs_; returns the local max
// of |s - P(s + c_s U)| and adds its squares to l2.
double ExactPlasticStep::linearise_side(Vec u, const ExactStepOptions& opt, double& l2,
                                        double& changes, double& rigid) {
  const Box& b = g_.box();
  const size_t ncell = static_cast<size_t>(b.xm) * b.ym;
  GF_PETSC(MatMult(I_, u, Us_));  // the unknown faces' part of U
  const LocalVelocity v(g_, u);
  const PetscScalar *k, *c, *s, *iu;
  PetscScalar* ks0;
  GF_PETSC(VecGetArrayRead(side_->k, &k));
  GF_PETSC(VecGetArrayRead(side_->c, &c));
  GF_PETSC(VecGetArrayRead(side_->s, &s));
  GF_PETSC(VecGetArrayRead(Us_, &iu));
  GF_PETSC(VecGetArray(ks0_, &ks0));
  PetscInt r0;
  GF_PETSC(VecGetOwnershipRange(Us_, &r0, nullptr));
  lins_.assign(5 * ncell, 0.0);
  double mx = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const size_t cell = static_cast<size_t>((j - b.ys) * b.xm + (i - b.xs));
      ks0[2 * cell] = ks0[2 * cell + 1] = 0.0;
      const double kk = k[cell];
      if (kk <= 0) continue;
      const double cs = c[cell];
      double U[2];
      cell_centre_velocity(v, i, j, U[0], U[1]);
      // U = I u + U0: U0 the wall faces' part, a constant of the step (zero on walls at rest).
      const double U0[2] = {U[0] - iu[2 * cell], U[1] - iu[2 * cell + 1]};
      const double sv[2] = {s[2 * cell], s[2 * cell + 1]};
      // Linearised as the cells' S (retracted, the cells' rigid step).
      const DiscLinearisation dl = linearise_disc(sv, U, cs, opt.retract && !pres_,
                                                  boost_ * opt.rigid_factor * cs, opt.gap_floor);
      // Weighted by k / k_max, the force's share (as SideWalls::update measures the fixed
      // point's change): where a cell's load k is small, c_s = r (...) / k is large and s
      // turns with the velocity's round-off, a change of up to 2 in s but not in the force.
      // Measured: the channel collapse (cases/ar07_rough_channel.toml without its gate, n = 16)
      // to 0.06 s, 20,520 iterations and 8 capped steps weighted, 22,066 and 10 not; a held
      // layer whose side walls are all weak (1e-7 deg, 10 steps) 143 and 151 (17 at 10 deg):
      // there every k is small, and the weight relative to the largest does not help.
      const double r = kk / side_kmax_ * dl.r;
      if (r > worst_.r) worst_ = {r, static_cast<int>(i), static_cast<int>(j), 3, dl.nqr};
      mx = std::max(mx, r);
      l2 += r * r;
      const signed char cls = dl.rigid ? 1 : 2;
      if (cls == 1) rigid = std::max(rigid, r);
      signed char& a = active_[3 * ncell + cell];
      if (a != 0 && a != cls) ++changes;
      a = cls;
      const auto& G = dl.G;
      const auto& s0 = dl.s0;
      double* l = &lins_[5 * cell];
      l[0] = s0[0];
      l[1] = s0[1];
      l[2] = G[0][0];
      l[3] = G[0][1];
      l[4] = G[1][1];
      // s = s0 + G (I u + U0): the force -I^T k s puts k (s0 + G U0) on the right-hand side
      // and I^T k G I into the Newton matrix.
      ks0[2 * cell] = kk * (s0[0] + G[0][0] * U0[0] + G[0][1] * U0[1]);
      ks0[2 * cell + 1] = kk * (s0[1] + G[1][0] * U0[0] + G[1][1] * U0[1]);
      const PetscInt rc[2] = {r0 + 2 * static_cast<PetscInt>(cell),
                              r0 + 2 * static_cast<PetscInt>(cell) + 1};
      const PetscScalar kg[4] = {kk * G[0][0], kk * G[0][1], kk * G[1][0], kk * G[1][1]};
      GF_PETSC(MatSetValues(Ms_, 2, rc, 2, rc, kg, INSERT_VALUES));
    }
  GF_PETSC(VecRestoreArray(ks0_, &ks0));
  GF_PETSC(VecRestoreArrayRead(Us_, &iu));
  GF_PETSC(VecRestoreArrayRead(side_->s, &s));
  GF_PETSC(VecRestoreArrayRead(side_->c, &c));
  GF_PETSC(VecRestoreArrayRead(side_->k, &k));
  GF_PETSC(MatAssemblyBegin(Ms_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatAssemblyEnd(Ms_, MAT_FINAL_ASSEMBLY));
  GF_PETSC(MatMultTranspose(I_, ks0_, srhs_));
  GF_PETSC(VecScale(srhs_, -1.0));
  return mx;
}

void ExactPlasticStep::newton_update_side(Vec u) {
  const Box& b = g_.box();
  const LocalVelocity v(g_, u);
  PetscScalar* s;
  GF_PETSC(VecGetArray(side_->s, &s));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const size_t cell = static_cast<size_t>((j - b.ys) * b.xm + (i - b.xs));
      const double* l = &lins_[5 * cell];
      double U[2];
      cell_centre_velocity(v, i, j, U[0], U[1]);
      s[2 * cell] = l[0] + l[2] * U[0] + l[3] * U[1];  // zero where k = 0 (lins_ holds zeros)
      s[2 * cell + 1] = l[1] + l[3] * U[0] + l[4] * U[1];
    }
  GF_PETSC(VecRestoreArray(side_->s, &s));
}

void ExactPlasticStep::newton_update(Vec u) {
  const Box& b = g_.box();
  if (walls_) newton_update_walls(u);
  if (side_) newton_update_side(u);
  GF_PETSC(MatMultAdd(m_->B, u, m_->d0, D_));
  const PetscScalar*** d;
  PetscScalar*** lam;
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), D_, &d));
  GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), lambda_, &lam));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double* l = &lin_[5 * static_cast<size_t>((j - b.ys) * b.xm + (i - b.xs))];
      const double e0 = 0.5 * (d[j][i][0] - d[j][i][2]), e1 = d[j][i][1];
      lam[j][i][0] = l[0] + l[2] * e0 + l[3] * e1;
      lam[j][i][1] = l[1] + l[3] * e0 + l[4] * e1;
      lam[j][i][2] = -lam[j][i][0];
    }
  GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), lambda_, &lam));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), D_, &d));
}

ExactStepStats ExactPlasticStep::solve_newton(Mat A, Vec b, const PlasticMatrices& m, Vec kappa,
                                              Vec c, Vec u, Vec S, const ExactStepOptions& opt,
                                              const NewtonWalls* walls, Vec c_rigid,
                                              const NewtonPressure* pressure,
                                              const std::vector<PetscInt>* local_rows,
                                              const NewtonSide* side) {
  walls_ = walls;
  side_ = side;
  pres_ = pressure;
  c_rigid_ = c_rigid;
  A_ = A;
  b_ = b;
  m_ = &m;
  kappa_ = kappa;
  c_ = c;
  GF_PETSC(VecCopy(S, lambda_));
  // M's pattern: the cells with a yield stress only, so that C M B, and J's update from it,
  // cost what the granular region holds, not the grid (case A at n = 64: the MatAXPY of
  // fill_jacobian 10 ms per iteration over the whole grid).
  make_M(true);
  if (side_) {
    side_matrices();
    GF_PETSC(VecMax(side_->k, nullptr, &side_kmax_));
  }
  std::fill(active_.begin(), active_.end(), 0);  // no class yet: the first linearisation sets it
  boost_ = 1;
  int calm = 0;  // iterations since the active sets last changed
  int short_steps = 0;  // line searches in a row that took a step of 1/64 or less
  ExactStepStats st;
  if (walls_ && walls_->refresh) {  // kappa_b of the start
    GF_PETSC(MatMultAdd(m.B, u, m.d0, D_));
    walls_->refresh(D_, lambda_, walls_->kappa_b);
  }
  // Options set here, not at construction, so that a run that does not use them is not warned
  // of unused options; the user's own value, if any, stays.
  const auto default_option = [](const char* key, const char* value) {
    PetscBool set = PETSC_FALSE;
    GF_PETSC(PetscOptionsHasName(nullptr, nullptr, key, &set));
    if (!set) GF_PETSC(PetscOptionsSetValue(nullptr, key, value));
  };
  if (pres_) {
    // The saddle point's zero (2,2) block makes MUMPS delay pivots beyond its default
    // workspace (INFOG(1) = -9 on the unit test's 8 x 32 channel at the default 20 %, solved at
    // 100 %): 200 %.
    default_option("-exactpd_sp_mat_mumps_icntl_14", "200");
    GF_PETSC(KSPSetFromOptions(ksp_sp_));
  } else {
    // MUMPS' ordering QAMD (ICNTL(7) = 6) instead of its default (METIS here): case A at
    // n = 128, its first 14 steps, the analyses took 20.4 s with METIS and 1.0 s with QAMD,
    // and the numerical factorisations 157 s and 109 s (the flop count 11 % higher; timings of
    // single runs, docs/RHEOLOGY.md). Each step analyses two matrices anew (the granular
    // cells, and the local rows, move).
    default_option("-exactpd_mat_mumps_icntl_7", "6");
  }
  {
    // J = A + B^T Pi kappa G L B + the walls' diagonal: with A symmetric positive definite
    // (the viscous operator, Predictor), every cell's G symmetric positive semi-definite
    // (gamma (I - n n^T), or c_R I) and C = -B^T W on the grains (free-slip, periodic and
    // Coulomb walls; not at no-slip walls, whose extrapolated shear stress in C is not the
    // adjoint of B's, nor at Navier walls: PlasticMatrices.hpp), J is symmetric positive
    // definite, and is factorised by Cholesky (MUMPS, SYM = 1 with J flagged SPD: no pivoting)
    // instead of LU. newton_matrix_symmetric() makes sure at every step. Measured on case A at
    // n = 64, its first 20 steps:
    // 11.0 ms per factorisation against 16.0 ms by LU, the solves 2.0 ms both
    // (docs/RHEOLOGY.md). -exactpd_pc_type lu: LU; another PC: the options' own.
    char type[64] = "", solver[64] = MATSOLVERMUMPS;
    PetscBool set = PETSC_FALSE;
    GF_PETSC(PetscOptionsGetString(nullptr, "exactpd_", "-pc_type", type, sizeof type, &set));
    GF_PETSC(PetscOptionsGetString(nullptr, "exactpd_", "-pc_factor_mat_solver_type", solver,
                                   sizeof solver, nullptr));
    const std::string t = type;
    solver_ = solver;
    pc_auto_ = !set || t == PCCHOLESKY || t == PCLU;
    // Cholesky by MUMPS only (UMFPACK and KLU have no Cholesky in PETSc 3.18).
    spd_ = !pres_ && !cholesky_failed_ && (!set || t == PCCHOLESKY) &&
           solver_ == MATSOLVERMUMPS;
  }
  if (spd_ && !newton_matrix_symmetric(A)) {
    PetscPrintf(g_.comm(),
                "granflow: note: the exact plastic step's Newton matrix is not symmetric (the "
                "grains at a no-slip or Navier wall, where the plastic stress's divergence is "
                "not the adjoint of the strain rate); LU instead of Cholesky from here on\n");
    use_lu();
  }
  // The PC's type before the options are read (so that its -exactpd_pc_factor_* options stay)
  // and after (-exactpd_pc_type may have changed it).
  set_factorisation(ksp_);
  GF_PETSC(KSPSetFromOptions(ksp_));
  set_factorisation(ksp_);
  Residual res = linearise(u, opt);
  jacobian_pattern(A);  // every 3 x 3 block of M is full: linearise sets them all
  // The local rows of this step (global indices; each rank its own), or none.
  ISDestroy(&is_loc_);
  MatDestroy(&Jloc_);
  GF_PETSC(KSPReset(ksp_loc_));  // the rows change from step to step
  PetscInt n_loc = 0;
  if (local_rows && !pres_) {
    PetscInt rstart;
    GF_PETSC(VecGetOwnershipRange(u, &rstart, nullptr));
    std::vector<PetscInt> rows(local_rows->size());
    for (size_t q = 0; q < rows.size(); ++q) rows[q] = rstart + (*local_rows)[q];
    n_loc = g_.sum(static_cast<double>(rows.size()));
    PetscInt n_all;
    GF_PETSC(VecGetSize(u, &n_all));
    if (n_loc > 0 && n_loc < n_all) {
      GF_PETSC(ISCreateGeneral(g_.comm(), static_cast<PetscInt>(rows.size()), rows.data(),
                               PETSC_COPY_VALUES, &is_loc_));
      set_factorisation(ksp_loc_);
      GF_PETSC(KSPSetFromOptions(ksp_loc_));
      set_factorisation(ksp_loc_);
    }
  }
  double best = std::numeric_limits<double>::infinity();  // the best iterate's residual max
  bool full_next = true;  // the first iteration of a step solves on every row
  int local_since_full = 0;
  // The line search's window: the 2-norms of the residual after the last iterations (from the
  // first solve on, and again from each refresh of kappa_b).
  constexpr size_t kWindow = 5;
  std::vector<double> window;
  bool tail = false;  // kappa_b refreshed after every solve
  PetscBool monitor = PETSC_FALSE;
  GF_PETSC(PetscOptionsHasName(nullptr, nullptr, "-exactpd_monitor", &monitor));
  // The rigid cells and sticking wall faces, optionally to a tighter bound (ExactStepOptions::
  // rigid_tol_factor).
  const double rigid_tol = opt.rigid_tol_factor * opt.tol;
  const auto within = [&](const Residual& r) {
    return r.max <= opt.tol && r.rigid <= rigid_tol;
  };
  for (int it = 0;; ++it) {
    st.change = res.max;
    st.rigid = res.rigid;
    if (monitor)
      GF_PETSC(PetscPrintf(g_.comm(),
                           "  exact plastic step: iteration %d, residual max %.3e (rigid %.3e), "
                           "2-norm %.3e, %d halvings, %.0f active-set changes\n",
                           it, res.max, res.rigid, res.l2, st.backtracks, active_changes_));
    if (monitor) print_worst();
    // After a solve the momentum equation holds with the updated S (the linear system is that
    // equation), so what is left is the projection's residual; before the first solve the
    // momentum equation is not known to hold.
    if (it > 0 && within(res) && !full_next && is_loc_ && local_since_full > 0) {
      // Converged on the local rows: the rows outside them are frozen at the last full solve,
      // and must still satisfy the momentum equation with the final S.
      const double mr = momentum_residual(u);
      if (monitor)
        GF_PETSC(PetscPrintf(g_.comm(), "  exact plastic step: momentum residual %.3e of |b|\n",
                             mr));
      if (mr > opt.momentum_rtol) full_next = true;
    }
    if (it > 0 && (within(res) || tail) && !(full_next && is_loc_)) {
      // Converged with kappa_b fixed: refresh kappa_b (a fixed point on kappa_b, whose
      // derivative is not in the Jacobian). While it changes by more than 1 %, the next
      // problem is solved to tol with kappa_b fixed again; below, kappa_b is refreshed from
      // every iterate (one solve per refresh) until both the residual and the change of kappa_b
      // are below their tolerances. Measured on the Coulomb block: refreshed from the start,
      // while the active sets still change, it stalled the line search at residuals of 1e-6;
      // refreshed after every solve from the first step's 50 % change, it cycled.
      if (!walls_ || !walls_->refresh) {
        st.converged = true;
        break;
      }
      const double dk = refresh_kappa_b(u);
      if (monitor)
        GF_PETSC(PetscPrintf(g_.comm(),
                             "  exact plastic step: kappa_b refreshed, max change %.3e of its "
                             "max\n",
                             dk));
      if (dk <= opt.kappa_b_tol && within(res)) {
        st.converged = true;
        break;
      }
      boost_ = 1;  // a new problem: its active sets are searched again with the plain steps
      calm = 0;
      res = linearise(u, opt);  // the same (u, S) with the new kappa_b
      // The new kappa_b changes the wall tractions, so (u, S) no longer satisfies the momentum
      // equation: like the start, the next step is taken whole.
      window.clear();
      tail = dk < 1e-2;
      ++st.refreshes;
    }
    if (it > 0 && res.max < best) {  // the best iterate so far (after a solve)
      best = res.max;
      GF_PETSC(VecCopy(u, u_best_));
      GF_PETSC(VecCopy(lambda_, S_best_));
      if (walls_) GF_PETSC(VecCopy(walls_->s_wall, sw_best_));
      if (side_) GF_PETSC(VecCopy(side_->s, ss_best_));
    }
    // (Restarts from the best iterate with a smaller c were tried until 2026-12-06: with the
    // stopping test at the step's own c they capped more steps, not fewer; docs/RHEOLOGY.md.)
    if (it == opt.max_outer) {
      // Capped: end at the best iterate rather than the last (the last can be any point of a
      // cycle: on case A at n = 32 the last had a residual of 0.57 where the best had 1.5e-3).
      if (best < res.max && !pres_) {
        GF_PETSC(VecCopy(u_best_, u));
        GF_PETSC(VecCopy(S_best_, lambda_));
        if (walls_) GF_PETSC(VecCopy(sw_best_, walls_->s_wall));
        if (side_) GF_PETSC(VecCopy(ss_best_, side_->s));
        res = linearise(u, opt);
        st.change = res.max;
        st.rigid = res.rigid;
      }
      break;
    }
    if (it > 0) GF_PETSC(MatMatMatMult(m.C, M_, m.B, MAT_REUSE_MATRIX, PETSC_DEFAULT, &CMB_));
    fill_jacobian();
    GF_PETSC(MatMult(m.C, T_, rhs_));
    GF_PETSC(VecAYPX(rhs_, 1.0, b));
    if (walls_) {
      GF_PETSC(MatDiagonalSet(J_, wdiag_, ADD_VALUES));
      GF_PETSC(VecAXPY(rhs_, 1.0, wrhs_));
    }
    if (side_) {
      GF_PETSC(MatPtAP(Ms_, I_, MAT_REUSE_MATRIX, PETSC_DEFAULT, &SIDE_));
      GF_PETSC(MatAXPY(J_, 1.0, SIDE_, SUBSET_NONZERO_PATTERN));
      if (spd_) set_spd(J_);
      GF_PETSC(VecAXPY(rhs_, 1.0, srhs_));
    }
    if (pres_) {
      solve_saddle(u, it);
    } else if (is_loc_ && !full_next) {
      solve_local(u, it);
      ++st.local;
      ++local_since_full;
    } else {
      full_next = false;
      local_since_full = 0;
      ++st.full;
      bool to_lu = false;
      const KSPConvergedReason why = direct_solve(ksp_, J_, rhs_, u, &to_lu);
      if (to_lu) use_lu();
      if (why < 0)
        throw RunError("exact plastic step: the Newton system's solve failed (" +
                       std::string(KSPConvergedReasons[why]) + ", " + lu_failure(ksp_) +
                       ") in iteration " + std::to_string(it + 1) +
                       "; try -exactpd_ksp_monitor to see it");
    }
    newton_update(u);
    st.outer = st.newton = it + 1;
    res = linearise(u, opt);
    // With the active sets unchanged by the Newton point, the full step is taken: there the
    // iteration is Newton's on a smooth system (see the header).
    if (!window.empty() && active_changes_ > 0) {
      // Non-monotone backtracking (Grippo, Lampariello & Lucidi 1986) on the 2-norm of the
      // projection's residual, against the largest of the last kWindow values, between the
      // last iterate and the Newton point: both satisfy the momentum equation, which is linear
      // in (u, S), so every point between them does too. A monotone test (against the last
      // value) stalled the iteration at residuals of 1e-3 to 1e-6 on the Coulomb block, where
      // the full steps converge: near the kinks of P the residual need not fall at every step.
      double ref = 0;
      for (double v : window) ref = std::max(ref, v);
      GF_PETSC(VecCopy(u, u_newton_));
      GF_PETSC(VecCopy(lambda_, S_newton_));
      if (walls_) GF_PETSC(VecCopy(walls_->s_wall, sw_newton_));
      if (side_) GF_PETSC(VecCopy(side_->s, ss_newton_));
      if (pres_) GF_PETSC(VecCopy(pres_->psi, psi_newton_));
      // After creep_steps iterations in a row whose line search accepted a step of 1/64 or
      // less, the Newton point is taken whole (ExactStepOptions::creep_steps).
      const bool whole = opt.creep_steps > 0 && short_steps >= opt.creep_steps;
      double tau_taken = 1;
      for (double tau = 0.5;
           !whole && res.l2 >= (1 - 1e-4 * 2 * tau) * ref && tau > 1.0 / 1024; tau *= 0.5) {
        tau_taken = tau;
        GF_PETSC(VecAXPBYPCZ(u, 1 - tau, tau, 0.0, u_prev_, u_newton_));
        GF_PETSC(VecAXPBYPCZ(lambda_, 1 - tau, tau, 0.0, S_prev_, S_newton_));
        if (walls_)
          GF_PETSC(VecAXPBYPCZ(walls_->s_wall, 1 - tau, tau, 0.0, sw_prev_, sw_newton_));
        if (side_) GF_PETSC(VecAXPBYPCZ(side_->s, 1 - tau, tau, 0.0, ss_prev_, ss_newton_));
        if (pres_) GF_PETSC(VecAXPBYPCZ(pres_->psi, 1 - tau, tau, 0.0, psi_prev_, psi_newton_));
        res = linearise(u, opt);
        ++st.backtracks;
      }
      short_steps = whole ? 0 : (tau_taken <= 1.0 / 64 ? short_steps + 1 : 0);
      if (whole && res.l2 >= (1 - 1e-4 / 512) * ref) {
        // A whole step without decrease is kept, and the iteration counts as calm: no class
        // is taken to have changed (the measurements of creep_steps were made so).
        active_changes_ = 0;
      } else if (res.l2 >= (1 - 1e-4 / 512) * ref) {
        // No decrease down to the shortest step: take the Newton point. Steps of 1/1024 make
        // no progress, and at a face or cell at its threshold the residual can rise along the
        // whole segment (case A at n = 16, a bottom wall face at q = 1.000002: the residual
        // crept from 1.1e-6 to 3.3e-6 over 70 such steps and the step was capped; with the
        // Newton point 0 of 600 steps capped, 7981 iterations instead of 8362).
        GF_PETSC(VecCopy(u_newton_, u));
        GF_PETSC(VecCopy(S_newton_, lambda_));
        if (walls_) GF_PETSC(VecCopy(sw_newton_, walls_->s_wall));
        if (side_) GF_PETSC(VecCopy(ss_newton_, side_->s));
        if (pres_) GF_PETSC(VecCopy(psi_newton_, pres_->psi));
        res = linearise(u, opt);
      }
    }
    window.push_back(res.l2);
    // Once the active sets have stayed the same for two iterations, what is left is the
    // proximal drift of the rigid cells' S and the sticking faces' s_t (not unique there): their
    // steps grow tenfold per iteration up to rigid_boost_max (the faces' up to wall_boost_max),
    // towards Newton's own E u = 0 and u_t = 0; back to 1 as soon as the active sets change (a
    // large step from the start slows the active-set search: rigid_factor 1e5 instead of 1e4
    // capped more steps, not fewer).
    calm = active_changes_ > 0 ? 0 : calm + 1;
    if (calm >= 2 && boost_ < opt.rigid_boost_max) {
      boost_ = std::min(boost_ * 10, opt.rigid_boost_max);
      res = linearise(u, opt);  // the same point, the longer steps
    } else if (calm == 0 && boost_ > 1) {
      boost_ = 1;
      res = linearise(u, opt);
    }
    if (window.size() > kWindow) window.erase(window.begin());
    GF_PETSC(VecCopy(u, u_prev_));
    GF_PETSC(VecCopy(lambda_, S_prev_));
    if (walls_) GF_PETSC(VecCopy(walls_->s_wall, sw_prev_));
    if (side_) GF_PETSC(VecCopy(side_->s, ss_prev_));
    if (pres_) GF_PETSC(VecCopy(pres_->psi, psi_prev_));
  }
  GF_PETSC(VecCopy(lambda_, S));
  {
    PC pc;
    PCType type;
    GF_PETSC(KSPGetPC(ksp_, &pc));
    GF_PETSC(PCGetType(pc, &type));
    PetscBool known = PETSC_FALSE, spd = PETSC_FALSE;
    if (J_) GF_PETSC(MatIsSPDKnown(J_, &known, &spd));
    st.cholesky = std::string(type) == PCCHOLESKY && known && spd;
  }
  return st;
}

void ExactPlasticStep::print_worst() const {
  // The rank that holds the largest residual says where it is.
  struct {
    double r;
    int rank;
  } in{worst_.r, g_.rank()}, out{};
  MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, g_.comm());
  if (out.rank != g_.rank() || worst_.r < 0) return;
  static const char* kind[4] = {"cell", "wall face u", "wall face v", "side walls of cell"};
  std::printf("    largest at %s (%d, %d): %s = %.9f\n", kind[worst_.kind], worst_.i, worst_.j,
              worst_.kind == 0 || worst_.kind == 3 ? "|q|" : "q", worst_.q);
  std::fflush(stdout);
}

void ExactPlasticStep::solve_local(Vec u, int it) {
  GF_PETSC(MatCreateSubMatrix(J_, is_loc_, is_loc_, Jloc_ ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX,
                              &Jloc_));
  if (spd_) set_spd(Jloc_);
  GF_PETSC(MatMult(J_, u, work_vel_));
  GF_PETSC(VecAYPX(work_vel_, -1.0, rhs_));  // rhs - J u: zero outside the rows up to the frozen
  Vec r, d, ul;
  GF_PETSC(VecGetSubVector(work_vel_, is_loc_, &r));
  GF_PETSC(VecDuplicate(r, &d));
  bool to_lu = false;
  const KSPConvergedReason why = direct_solve(ksp_loc_, Jloc_, r, d, &to_lu);
  if (to_lu) use_lu();
  GF_PETSC(VecRestoreSubVector(work_vel_, is_loc_, &r));
  if (why < 0) {
    VecDestroy(&d);
    throw RunError("exact plastic step: the local Newton system's solve failed (" +
                   std::string(KSPConvergedReasons[why]) + ", " + lu_failure(ksp_loc_) +
                   ") in iteration " + std::to_string(it + 1) +
                   "; try solver.viscous_local_margin = 0");
  }
  GF_PETSC(VecGetSubVector(u, is_loc_, &ul));
  GF_PETSC(VecAXPY(ul, 1.0, d));
  GF_PETSC(VecRestoreSubVector(u, is_loc_, &ul));
  GF_PETSC(VecDestroy(&d));
}

double ExactPlasticStep::momentum_residual(Vec u) {
  // Outside the local rows there is no plastic term and no wall traction (the rows hold every
  // face of the granular cells and of their margin), so the momentum residual there is
  // A u - b. Inside them it is the Newton system's, which the solve made zero up to the
  // round-off of its penalties (on the sliding block at n = 15 a full LU left 2.5e-9 of |b|
  // there, in the walls' rows).
  GF_PETSC(MatMult(A_, u, work_vel_));
  GF_PETSC(VecAXPY(work_vel_, -1.0, b_));
  Vec inside;
  GF_PETSC(VecGetSubVector(work_vel_, is_loc_, &inside));
  GF_PETSC(VecSet(inside, 0.0));
  GF_PETSC(VecRestoreSubVector(work_vel_, is_loc_, &inside));
  PetscReal rn, bn;
  GF_PETSC(VecNorm(work_vel_, NORM_2, &rn));
  GF_PETSC(VecNorm(b_, NORM_2, &bn));
  return bn > 0 ? rn / bn : rn;
}

void ExactPlasticStep::solve_saddle(Vec u, int it) {
  // The blocks in a nest, assembled into one AIJ matrix for the direct solve (J_ changes at
  // every iteration; the nest's index sets number each rank's u rows, then its psi rows).
  // The rigid cells' rows of D: div u + (psi - psi_k) / (kappa c_R) = 0, the augmented form of
  // div u = 0 with the step of their S (S = S_k + c_R E u): the pressure and the deviatoric
  // stress kappa S of a rigid cell move by the same proximal step, kappa c_R times the
  // violation of div u = 0 and E u = 0, so that the whole stress tensor moves by as little as
  // the iteration needs (equal weights in its Frobenius norm). A rigid zone's stress is not
  // unique (any equilibrium stress inside the yield surface will do); with div u = 0 held
  // exactly there the pressure was free to drift from iteration to iteration and step to
  // step: on the sliding Coulomb block at 120 x 30 cells it grew within 2 steps into a
  // +-2000 Pa checkerboard with |S| near 1, the clipped wall load (p - kappa S_nn)^+ rose by
  // 32 % and the block slid at half its acceleration. A pressure step 100 or 1e4 times
  // longer than S's drifts the same way (the wall load up by 53 % and 23 %). Every fixed point
  // still has div u = 0 and E u = 0 in the rigid cells.
  if (!Zk_) {
    GF_PETSC(MatDuplicate(pres_->Z, MAT_COPY_VALUES, &Zk_));
    GF_PETSC(DMCreateGlobalVector(g_.dm_cell(), &zdiag_));
  }
  Vec rp;  // the psi rows' right-hand side
  GF_PETSC(DMGetGlobalVector(g_.dm_cell(), &rp));
  {
    const Box& b = g_.box();
    PetscScalar **z, **r;
    const PetscScalar** ps;
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), zdiag_, &z));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), pres_->psi, &ps));
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), rp, &r));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double pr = prox_[static_cast<size_t>((j - b.ys) * b.xm + (i - b.xs))];
        const bool pin = (i == 0 && j == 0);
        z[j][i] = pin ? 1.0 : (pr > 0 ? 1.0 / pr : 0.0);
        r[j][i] = pin ? 0.0 : z[j][i] * ps[j][i];
      }
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), rp, &r));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), pres_->psi, &ps));
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), zdiag_, &z));
    GF_PETSC(MatDiagonalSet(Zk_, zdiag_, INSERT_VALUES));
  }
  Mat blocks[4] = {J_, pres_->G, pres_->Dv, Zk_};
  Mat nest;
  GF_PETSC(MatCreateNest(g_.comm(), 2, nullptr, 2, nullptr, blocks, &nest));
  // The pattern of K is the same at every iteration (J's and Z's are fixed for the step), so
  // from the second on the copy is refilled and the direct solver keeps its analysis (on one
  // rank: on more, PETSc 3.18's MatConvert_Nest_AIJ preallocates the reused matrix again, so
  // MUMPS analyses it again; the answers are the same).
  const bool reuse = K_ != nullptr && it > 0;
  if (!reuse) MatDestroy(&K_);
  GF_PETSC(MatConvert(nest, MATAIJ, reuse ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &K_));
  IS rows[2];
  GF_PETSC(MatNestGetISs(nest, rows, nullptr));
  if (!X_) GF_PETSC(MatCreateVecs(K_, &X_, &R_));
  Vec sub;
  GF_PETSC(VecGetSubVector(R_, rows[0], &sub));
  GF_PETSC(VecCopy(rhs_, sub));
  GF_PETSC(VecRestoreSubVector(R_, rows[0], &sub));
  GF_PETSC(VecGetSubVector(R_, rows[1], &sub));
  GF_PETSC(VecCopy(rp, sub));
  GF_PETSC(VecRestoreSubVector(R_, rows[1], &sub));
  GF_PETSC(DMRestoreGlobalVector(g_.dm_cell(), &rp));
  const KSPConvergedReason why = direct_solve(ksp_sp_, K_, R_, X_);
  if (why < 0) {
    MatDestroy(&nest);
    throw RunError("exact plastic step: the Newton system's solve with the pressure failed (" +
                   std::string(KSPConvergedReasons[why]) + ", " + lu_failure(ksp_sp_) +
                   ") in iteration " +
                   std::to_string(it + 1) + "; try -exactpd_sp_ksp_monitor to see it");
  }
  GF_PETSC(VecGetSubVector(X_, rows[0], &sub));
  GF_PETSC(VecCopy(sub, u));
  GF_PETSC(VecRestoreSubVector(X_, rows[0], &sub));
  GF_PETSC(VecGetSubVector(X_, rows[1], &sub));
  GF_PETSC(VecCopy(sub, pres_->psi));
  GF_PETSC(VecRestoreSubVector(X_, rows[1], &sub));
  GF_PETSC(MatDestroy(&nest));
}

}  // namespace gf::momentum
