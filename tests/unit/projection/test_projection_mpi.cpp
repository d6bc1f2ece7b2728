// The projection of eq. 32 and the viscous operator of eq. 31, checked against exact answers.
#include <gtest/gtest.h>

#include <cmath>

#include "boundary/Boundary.hpp"
#include "core/Error.hpp"
#include "fields/Fields.hpp"
#include "momentum/Momentum.hpp"
#include "operators/Operators.hpp"
#include "projection/Projection.hpp"

using namespace gf;

namespace {

// A heavy column (1550) in air (1.2): the density ratio of the paper's case A.
void column_density(const Grid& g, Vec rho) {
  const Box& b = g.box();
  PetscScalar** r;
  DMDAVecGetArray(g.dm_cell(), rho, &r);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      r[j][i] = (b.xc(i) < 0.3 * b.Lx && b.yc(j) < 0.6 * b.Ly) ? 1550.0 : 1.2;
  DMDAVecRestoreArray(g.dm_cell(), rho, &r);
}

double max_abs_div(const Grid& g, Vec vel) {
  Vec lv;
  DMCreateLocalVector(g.dm_vel(), &lv);
  DMGlobalToLocalBegin(g.dm_vel(), vel, INSERT_VALUES, lv);
  DMGlobalToLocalEnd(g.dm_vel(), vel, INSERT_VALUES, lv);
  Vel** a;
  DMDAVecGetArray(g.dm_vel(), lv, &a);
  fill_velocity_ghosts(g, a);
  Field div(g.dm_cell(), "div");
  PetscScalar** d;
  DMDAVecGetArray(g.dm_cell(), div, &d);
  ops::divergence(g.box(), a, d);
  DMDAVecRestoreArray(g.dm_cell(), div, &d);
  DMDAVecRestoreArray(g.dm_vel(), lv, &a);
  VecDestroy(&lv);
  PetscReal m;
  VecNorm(div, NORM_INFINITY, &m);
  return m;
}

}  // namespace

TEST(Projection, DivergenceAtRoundOffWithDensityJump) {
  Grid g(PETSC_COMM_WORLD, 64, 32, 0.8, 0.4);
  Field vel(g.dm_vel(), "u"), p(g.dm_cell(), "p"), rho(g.dm_cell(), "rho");
  column_density(g, rho);
  const Box& b = g.box();
  Vel** u;
  DMDAVecGetArray(g.dm_vel(), vel, &u);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      u[j][i].u = i > 0 ? std::sin(3 * b.xf(i)) * std::cos(5 * b.yc(j)) + 0.3 : 0.0;
      u[j][i].v = j > 0 ? std::exp(b.xc(i)) * b.yf(j) : 0.0;
    }
  DMDAVecRestoreArray(g.dm_vel(), vel, &u);
  const double div0 = max_abs_div(g, vel);
  ASSERT_GT(div0, 0.1);
  projection::Projector pr(g, 1e-13);
  pr.assemble(rho);
  pr.project(vel, p, rho, 1.5, 1e-3);
  // Relative to the initial divergence: the residual of a CG solve at rtol 1e-13.
  EXPECT_LT(max_abs_div(g, vel) / div0, 1e-9);
  // Projecting a solenoidal field changes nothing (idempotent up to the tolerance).
  Field v2(g.dm_vel(), "u2");
  VecCopy(vel, v2);
  pr.project(v2, p, rho, 1.5, 1e-3);
  VecAXPY(v2, -1.0, vel);
  PetscReal dn, un;
  VecNorm(v2, NORM_INFINITY, &dn);
  VecNorm(vel, NORM_INFINITY, &un);
  EXPECT_LT(dn / un, 1e-9);
}

TEST(Projection, HydrostaticPressureOfALayerAtRest) {
  // A heavy layer under air: projecting u* = g dt gives u = 0 and p = rho g (depth) exactly in
  // the discrete sense, with p = 0 on the top boundary (the pressure reference).
  Grid g(PETSC_COMM_WORLD, 16, 32, 0.2, 0.4);
  Field vel(g.dm_vel(), "u"), p(g.dm_cell(), "p"), rho(g.dm_cell(), "rho");
  const Box& b = g.box();
  const double H = 0.2, gy = -9.81, dt = 1e-3;
  PetscScalar** r;
  Vel** u;
  DMDAVecGetArray(g.dm_cell(), rho, &r);
  DMDAVecGetArray(g.dm_vel(), vel, &u);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      r[j][i] = b.yc(j) < H ? 1550.0 : 1.2;
      u[j][i].u = 0.0;
      u[j][i].v = j > 0 ? gy * dt : 0.0;
    }
  DMDAVecRestoreArray(g.dm_vel(), vel, &u);
  DMDAVecRestoreArray(g.dm_cell(), rho, &r);
  projection::Projector pr(g, 1e-13);
  pr.assemble(rho);
  pr.project(vel, p, rho, 1.0, dt);
  PetscReal un;
  VecNorm(vel, NORM_INFINITY, &un);
  EXPECT_LT(un, 1e-10 * std::abs(gy * dt));
  // Discrete hydrostatics: p_j - p_{j+1} = rho_face g hy, summed from the top row, with the
  // level set by a zero pressure on the top boundary, p_wall = (3 p_{ny-1} - p_{ny-2}) / 2.
  auto rho_at = [&](PetscInt k) { return b.yc(k) < H ? 1550.0 : 1.2; };
  auto from_top = [&](PetscInt j) {
    double s = 0;
    for (PetscInt k = j + 1; k < b.ny; ++k) s += 0.5 * (rho_at(k - 1) + rho_at(k)) * (-gy) * b.hy;
    return s;
  };
  const double shift = 0.5 * from_top(b.ny - 2);  // -(p_wall) of the top-row-zero field
  const PetscScalar** pa;
  DMDAVecGetArrayRead(g.dm_cell(), p, &pa);
  double worst = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      worst = std::max(worst, std::abs(pa[j][i] - (from_top(j) + shift)));
  DMDAVecRestoreArrayRead(g.dm_cell(), p, &pa);
  EXPECT_LT(g.max(worst), 1e-8 * 1550 * 9.81 * H);
}

TEST(Projection, PfmgAndBoomerAmgGiveTheSameProjection) {
  // The default preconditioner (hypre PFMG on a MATHYPRESTRUCT matrix of a 3D nx x ny x 1
  // DMDA) against the AIJ matrix with BoomerAMG (-pres_pc_type hypre): the same operator, so
  // the same velocity and pressure to the solver tolerance, on 1 and 2 ranks (the struct DMDA
  // copies the cell DM's decomposition).
  Grid g(PETSC_COMM_WORLD, 48, 24, 0.8, 0.4);
  Field rho(g.dm_cell(), "rho"), v1(g.dm_vel(), "u1"), v2(g.dm_vel(), "u2"), p1(g.dm_cell(), "p1"),
      p2(g.dm_cell(), "p2");
  column_density(g, rho);
  const Box& b = g.box();
  Vel** u;
  DMDAVecGetArray(g.dm_vel(), v1, &u);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      u[j][i].u = i > 0 ? std::cos(4 * b.xf(i)) * std::sin(2 * b.yc(j)) - 0.1 : 0.0;
      u[j][i].v = j > 0 ? std::exp(b.xc(i)) * b.yf(j) - 9.81e-3 : 0.0;
    }
  DMDAVecRestoreArray(g.dm_vel(), v1, &u);
  VecCopy(v1, v2);
  {
    projection::Projector pr(g, 1e-12);
    EXPECT_TRUE(pr.pfmg());
    pr.assemble(rho);
    EXPECT_GT(pr.project(v1, p1, rho, 1.5, 1e-3), 0);
    EXPECT_FALSE(pr.fell_back());
  }
  PetscOptionsSetValue(nullptr, "-pres_pc_type", "hypre");
  {
    projection::Projector pr(g, 1e-12);
    EXPECT_FALSE(pr.pfmg());
    pr.assemble(rho);
    pr.project(v2, p2, rho, 1.5, 1e-3);
  }
  PetscOptionsClearValue(nullptr, "-pres_pc_type");
  PetscReal dv, vn, dp, pn;
  VecNorm(v1, NORM_INFINITY, &vn);
  VecNorm(p1, NORM_INFINITY, &pn);
  VecAXPY(v2, -1.0, v1);
  VecAXPY(p2, -1.0, p1);
  VecNorm(v2, NORM_INFINITY, &dv);
  VecNorm(p2, NORM_INFINITY, &dp);
  EXPECT_LT(dv / vn, 1e-8);
  EXPECT_LT(dp / pn, 1e-8);
}

TEST(Viscous, OperatorIsSymmetricAndSolvesToTolerance) {
  Grid g(PETSC_COMM_WORLD, 24, 16, 0.3, 0.2);
  Field rho(g.dm_cell(), "rho"), eta(g.dm_cell(), "eta"), etan(g.dm_cell(), "etan");
  column_density(g, rho);
  // A viscosity contrast like the paper's (0.5 Pa s against 1.8e-5 Pa s).
  VecCopy(rho, eta);
  VecScale(eta, 0.5 / 1550.0);
  VecCopy(eta, etan);
  Boundaries bc;
  bc.left = {WallType::Navier, 1.0, 0.0};
  bc.bottom = {WallType::NoSlip, 0.0, 0.0};
  bc.top = {WallType::NoSlip, 0.0, 1.0};
  momentum::Predictor pred(g, bc, 1e-12);
  pred.assemble(rho, eta, etan, 1.5 / 1e-3);
  PetscBool sym = PETSC_FALSE;
  MatIsSymmetric(pred.matrix(), 1e-12, &sym);
  EXPECT_TRUE(sym);
  // A manufactured discrete solution: b = A x, solve, compare.
  Field x(g.dm_vel(), "x"), bvec(g.dm_vel(), "b"), y(g.dm_vel(), "y");
  const Box& b = g.box();
  Vel** xa;
  DMDAVecGetArray(g.dm_vel(), x, &xa);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      xa[j][i].u = i > 0 ? std::sin(7 * b.xf(i) + 3 * b.yc(j)) : 0.0;
      xa[j][i].v = j > 0 ? std::cos(2 * b.xc(i) * b.yf(j)) : 0.0;
    }
  DMDAVecRestoreArray(g.dm_vel(), x, &xa);
  MatMult(pred.matrix(), x, bvec);
  VecSet(y, 0.0);
  pred.solve(bvec, y);
  VecAXPY(y, -1.0, x);
  PetscReal e;
  VecNorm(y, NORM_INFINITY, &e);
  EXPECT_LT(e, 1e-8);
}

// Predictor::begin_local / solve_local (solver.viscous_local_margin): a change of the right-hand
// side in a patch of cells, solved on the patch widened by m cells with the rest frozen. With
// every row in R the sub-problem is the full one; with fewer, the error is what the frozen rows
// miss, which falls geometrically with m (the mass term dominates the operator); rows outside R
// are not touched.
TEST(Viscous, LocalSolveConvergesToTheFullSolveWithTheMargin) {
  Grid g(PETSC_COMM_WORLD, 48, 32, 0.3, 0.2);
  Field rho(g.dm_cell(), "rho"), eta(g.dm_cell(), "eta"), etan(g.dm_cell(), "etan");
  column_density(g, rho);
  VecCopy(rho, eta);  // 0.5 Pa s in the column, 3.9e-4 in air
  VecScale(eta, 0.5 / 1550.0);
  VecCopy(eta, etan);
  Boundaries bc;
  bc.left = {WallType::Navier, 1.0, 0.0};
  bc.bottom = {WallType::NoSlip, 0.0, 0.0};
  momentum::Predictor pred(g, bc, 1e-13);
  // dt = 1e-2 s: eta / h^2 = 1.3e4 against rho a0 / dt = 1.6e5 in the column, 180 in air.
  pred.assemble(rho, eta, etan, 1.5 / 1e-2);
  const Box& b = g.box();
  Field b0(g.dm_vel(), "b0"), b1(g.dm_vel(), "b1"), y0(g.dm_vel(), "y0"), yf(g.dm_vel(), "yf"),
      yl(g.dm_vel(), "yl");
  Vel** a;
  DMDAVecGetArray(g.dm_vel(), b0, &a);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      a[j][i].u = i > 0 ? 1e3 * std::sin(7 * b.xf(i) + 3 * b.yc(j)) : 0.0;
      a[j][i].v = j > 0 ? 1e3 * std::cos(2 * b.xc(i) * b.yf(j)) : 0.0;
    }
  DMDAVecRestoreArray(g.dm_vel(), b0, &a);
  VecSet(y0, 0.0);
  pred.solve(b0, y0);
  // The patch: cells 4..9 x 6..11, inside the column (cells i < 14, j < 19).
  auto in_patch = [](PetscInt i, PetscInt j, PetscInt m) {
    return i >= 4 - m && i < 10 + m && j >= 6 - m && j < 12 + m;
  };
  VecCopy(b0, b1);
  DMDAVecGetArray(g.dm_vel(), b1, &a);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      if (in_patch(i, j, 0)) {
        a[j][i].u += 5e3;
        a[j][i].v -= 3e3;
      }
  DMDAVecRestoreArray(g.dm_vel(), b1, &a);
  VecCopy(y0, yf);
  pred.solve(b1, yf);
  Field d(g.dm_vel(), "d");
  VecWAXPY(d, -1.0, y0, yf);
  PetscReal change;
  VecNorm(d, NORM_INFINITY, &change);
  ASSERT_GT(change, 1e-3);
  int its = 0;
  auto local_error = [&](PetscInt m, PetscReal* untouched) {
    std::vector<PetscInt> rows;
    for (PetscInt j = b.ys, c = 0; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i, ++c)
        if (in_patch(i, j, m)) {
          rows.push_back(2 * c);
          rows.push_back(2 * c + 1);
        }
    VecCopy(y0, yl);
    pred.begin_local(rows, b1, yl);
    EXPECT_TRUE(pred.local_active());
    its = pred.solve_local(b1, yl);
    pred.end_local();
    // Outside R: exactly y0.
    const PetscScalar *l, *z;
    VecGetArrayRead(yl, &l);
    VecGetArrayRead(y0, &z);
    PetscReal out = 0;
    std::size_t r = 0;
    PetscInt len;
    VecGetLocalSize(yl, &len);
    for (PetscInt q = 0; q < len; ++q) {
      if (r < rows.size() && rows[r] == q) { ++r; continue; }
      out = std::max(out, std::abs(l[q] - z[q]));
    }
    VecRestoreArrayRead(y0, &z);
    VecRestoreArrayRead(yl, &l);
    MPI_Allreduce(&out, untouched, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
    VecWAXPY(d, -1.0, yf, yl);
    PetscReal e;
    VecNorm(d, NORM_INFINITY, &e);
    return e / change;
  };
  PetscReal untouched;
  const PetscReal e_all = local_error(100, &untouched);
  EXPECT_LT(e_all, 1e-9);
  std::vector<PetscReal> e;
  std::vector<int> it;
  for (PetscInt m : {1, 3, 6}) {
    e.push_back(local_error(m, &untouched));
    it.push_back(its);
    EXPECT_EQ(untouched, 0.0) << "margin " << m;
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "local solve error / change: all rows %.2e, margin 1: %.2e (%d its), 3: %.2e (%d), "
              "6: %.2e (%d)\n",
              (double)e_all, (double)e[0], it[0], (double)e[1], it[1], (double)e[2], it[2]);
  EXPECT_GT(e[0], 10 * e[1]);
  EXPECT_GT(e[1], 10 * e[2]);
  EXPECT_LT(e[2], 1e-5);
  // Nothing to solve on any rank: the local solves stay off.
  pred.begin_local({}, b1, yl);
  EXPECT_FALSE(pred.local_active());
}
