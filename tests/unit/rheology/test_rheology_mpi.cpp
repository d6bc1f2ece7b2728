// The rheology module against exact answers: the projections P and P_b (eqs. 29-30), the mu(I)
// viscosity (eq. 11), and the hydrostatic pressure of eq. 15 across MPI subdomains.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "boundary/Coulomb.hpp"
#include "fields/Fields.hpp"
#include "levelset/Heaviside.hpp"
#include "levelset/LevelSet.hpp"
#include "rheology/Rheology.hpp"

using namespace gf;

TEST(Rheology, ProjectionOntoUnitBall) {
  double sxx = 3.0, sxy = 4.0;  // |L| = 5 -> L / 5
  rheology::project(sxx, sxy);
  EXPECT_DOUBLE_EQ(sxx, 0.6);
  EXPECT_DOUBLE_EQ(sxy, 0.8);
  sxx = 0.3, sxy = -0.4;  // inside: unchanged
  rheology::project(sxx, sxy);
  EXPECT_DOUBLE_EQ(sxx, 0.3);
  EXPECT_DOUBLE_EQ(sxy, -0.4);
  // P is a projection: idempotent, and non-expansive.
  double a = 2.0, b = -7.0;
  rheology::project(a, b);
  double a2 = a, b2 = b;
  rheology::project(a2, b2);
  EXPECT_DOUBLE_EQ(a, a2);
  EXPECT_DOUBLE_EQ(b, b2);
  EXPECT_DOUBLE_EQ(boundary::project_b(-3.0), -1.0);
  EXPECT_DOUBLE_EQ(boundary::project_b(0.25), 0.25);
}

TEST(Rheology, ModifiedFrobeniusNorm) {
  // |L|^2 = 1/2 sum L_ij^2: simple shear du/dy = g gives D_xy = g/2 and |D| = g/2.
  Grid g(PETSC_COMM_WORLD, 8, 8, 1.0, 1.0);
  Field D(g.dm_ten(), "D"), n(g.dm_cell(), "n");
  VecSet(D, 0.0);
  PetscScalar*** d;
  DMDAVecGetArrayDOF(g.dm_ten(), D, &d);
  for (PetscInt j = g.box().ys; j < g.box().ye(); ++j)
    for (PetscInt i = g.box().xs; i < g.box().xe(); ++i) d[j][i][1] = 0.5 * 3.0;
  DMDAVecRestoreArrayDOF(g.dm_ten(), D, &d);
  rheology::tensor_norm(g, D, n);
  PetscReal mx, mn;
  VecMax(n, nullptr, &mx);
  VecMin(n, nullptr, &mn);
  EXPECT_DOUBLE_EQ(mx, 1.5);
  EXPECT_DOUBLE_EQ(mn, 1.5);
}

TEST(Rheology, MuIViscosityIsEquation11) {
  rheology::Params pr;
  pr.tan_alpha = std::tan(25.5 * M_PI / 180);
  pr.mu_inf = 0.73;
  pr.I0 = 0.279;
  pr.d = 7e-4;
  pr.eta_min = 0;
  pr.eta_max = 1e30;
  const double rho = 1550, p = 1000, D = 2.0;
  // eq. 11 rewritten from mu(I) p / (2|D|) - tan(alpha) p / (2|D|) with I = 2|D| d sqrt(rho/p).
  const double I = 2 * D * pr.d * std::sqrt(rho / p);
  const double mu = pr.tan_alpha + (pr.mu_inf - pr.tan_alpha) / (1 + pr.I0 / I);
  EXPECT_NEAR(rheology::mu_i_viscosity(pr, D, p, rho), (mu - pr.tan_alpha) * p / (2 * D), 1e-12);
  // At rest eq. 11 stays finite: (mu_inf - tan alpha) d sqrt(rho p) / I0.
  EXPECT_NEAR(rheology::mu_i_viscosity(pr, 0.0, p, rho),
              (pr.mu_inf - pr.tan_alpha) * pr.d * std::sqrt(rho * p) / pr.I0, 1e-12);
  pr.eta_max = 1.2;  // at 5 kPa that exceeds the cap, which is applied
  EXPECT_DOUBLE_EQ(rheology::mu_i_viscosity(pr, 0.0, 5000.0, rho), 1.2);
}

TEST(Rheology, HydrostaticPressureAcrossRanks) {
  // A granular layer of thickness H under air: p_hyd = rho g (H - y) in the layer, 0 above.
  // ny = 32 so that 2 ranks may split the columns in y; the scan over ranks must add up.
  Grid g(PETSC_COMM_WORLD, 8, 32, 0.1, 0.4);
  Field c(g.dm_cell(), "c"), ph(g.dm_cell(), "p_hyd");
  const Box& b = g.box();
  const double H = 0.25, rho = 1550, gabs = 9.81;
  PetscScalar** ca;
  DMDAVecGetArray(g.dm_cell(), c, &ca);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) ca[j][i] = b.yc(j) < H ? 1.0 : 0.0;
  DMDAVecRestoreArray(g.dm_cell(), c, &ca);
  rheology::hydrostatic_pressure(g, c, rho, gabs, ph);
  const PetscScalar** pa;
  DMDAVecGetArrayRead(g.dm_cell(), ph, &pa);
  double err = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double exact = b.yc(j) < H ? rho * gabs * (H - b.yc(j)) : 0.0;
      err = std::max(err, std::abs(pa[j][i] - exact));
    }
  DMDAVecRestoreArrayRead(g.dm_cell(), ph, &pa);
  EXPECT_LT(g.max(err), 1e-9 * rho * gabs * H);
}

TEST(Rheology, YieldSupportPhaseOrMass) {
  // Drucker-Prager kappa = tan(alpha) p^+ on a layer phi = y - H: with support 0 (the paper,
  // rheology.yield_support = "phase") only where phi < 0; with support eps ("mass") also in the
  // smeared band 0 <= phi < eps, where eq. 25 still gives granular mass; 0 above either way.
  Grid g(PETSC_COMM_WORLD, 8, 32, 0.1, 0.4);
  Field phi(g.dm_cell(), "phi"), p(g.dm_cell(), "p"), k(g.dm_cell(), "kappa");
  const Box& b = g.box();
  const double H = 0.2, eps = 1.5 * b.hy;
  PetscScalar **fa, **pa;
  DMDAVecGetArray(g.dm_cell(), phi, &fa);
  DMDAVecGetArray(g.dm_cell(), p, &pa);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      fa[j][i] = b.yc(j) - H;
      pa[j][i] = 1000.0 * (b.Ly - b.yc(j));  // positive everywhere: only phi decides
    }
  DMDAVecRestoreArray(g.dm_cell(), p, &pa);
  DMDAVecRestoreArray(g.dm_cell(), phi, &fa);
  rheology::Params pr;
  pr.yield = rheology::Yield::DruckerPrager;
  pr.tan_alpha = 0.5;
  Field w(g.dm_cell(), "support");
  for (const double support : {0.0, eps}) {
    levelset::yield_support(g, phi, support, w);
    rheology::yield_stress(g, pr, w, p, nullptr, k);
    const PetscScalar** ka;
    DMDAVecGetArrayRead(g.dm_cell(), k, &ka);
    double err = 0;
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double ph = b.yc(j) - H;
        const double exact = ph < support ? 0.5 * 1000.0 * (b.Ly - b.yc(j)) : 0.0;
        err = std::max(err, std::abs(ka[j][i] - exact));
      }
    DMDAVecRestoreArrayRead(g.dm_cell(), k, &ka);
    EXPECT_EQ(g.max(err), 0.0) << "support " << support;
  }
}

TEST(Rheology, BinghamMassSupportFollowsTheGranularFraction) {
  // A Bingham tau_y with rheology.yield_support = "mass" on a layer phi = y - H whose surface
  // lies 1.5 h = eps below a row of cell centres (a rectangle's face: that row is air to
  // round-off): kappa = tau_y (1 - H_eps(phi)) in the band, tau_y below it, 0 from phi = eps on
  // (and where the fraction is below 1e-9), whichever side of eps round-off puts the row.
  Grid g(PETSC_COMM_WORLD, 8, 32, 0.1, 0.4);
  Field phi(g.dm_cell(), "phi"), p(g.dm_cell(), "p"), k(g.dm_cell(), "kappa");
  const Box& b = g.box();
  const double eps = 1.5 * b.hy, H = b.yc(20) - eps, tau = 2000.0;
  for (const double shift : {0.0, -1e-12, 1e-12}) {
    PetscScalar** fa;
    DMDAVecGetArray(g.dm_cell(), phi, &fa);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) fa[j][i] = b.yc(j) - H + shift;
    DMDAVecRestoreArray(g.dm_cell(), phi, &fa);
    rheology::Params pr;
    pr.yield = rheology::Yield::Bingham;
    pr.tau_y = tau;
    Field w(g.dm_cell(), "support");
    levelset::yield_support(g, phi, eps, w);
    rheology::yield_stress(g, pr, w, p, nullptr, k);
    const PetscScalar** ka;
    DMDAVecGetArrayRead(g.dm_cell(), k, &ka);
    double err = 0, at_eps = 0;
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double ph = b.yc(j) - H + shift;
        const double exact = ph < -eps ? tau : tau * (1.0 - levelset::heaviside(ph, eps));
        err = std::max(err, std::abs(ka[j][i] - exact));
        if (j >= 20) at_eps = std::max(at_eps, std::abs(ka[j][i]));
      }
    DMDAVecRestoreArrayRead(g.dm_cell(), k, &ka);
    EXPECT_LT(g.max(err), 1e-9 * tau) << "shift " << shift;
    EXPECT_EQ(g.max(at_eps), 0.0) << "shift " << shift;  // no yield stress in the air row
  }
}

TEST(Rheology, RelaxedProjectionFixedPointDependsOnROverTheta) {
  // The local map of eq. 31, S <- P(S + r kappa D + theta (S^n - S)), iterated with D frozen
  // (rheology::update_plastic), converges geometrically (ratio 1 - theta) to:
  //  - where |S^n + r kappa D / theta| <= 1: S = S^n + (r kappa / theta) D, D's deviatoric part.
  //    The step is not rigid: it deforms in proportion to the stress increment, like an elastic
  //    solid whose compliance theta / (r kappa) is set by r and theta together;
  //  - elsewhere: S = (theta S^n + r kappa D) / |theta S^n + r kappa D|, which also depends on r
  //    and theta unless S^n is parallel to D.
  // Only at theta = 0 (eq. 29) is the fixed point the same for any r > 0. The exact answers
  // here use r = r_factor (2 eta + rho a0/dt h^2) / kappa^2 written out, not r_local().
  Grid g(PETSC_COMM_WORLD, 8, 8, 0.08, 0.08);  // h = 0.01 m
  Field S(g.dm_ten(), "S"), Sn(g.dm_ten(), "Sn"), D(g.dm_ten(), "D");
  Field k(g.dm_cell(), "kappa"), rho(g.dm_cell(), "rho"), eta(g.dm_cell(), "eta");
  const double kappa = 200.0, rh = 1500.0, et = 0.5, a0dt = 1.5 / 1e-3;  // SI
  const double snxx = 0.1, snxy = -0.2;                                // S^n
  VecSet(k, kappa);
  VecSet(rho, rh);
  VecSet(eta, et);
  auto fill = [&](Vec v, double xx, double xy, double yy) {
    PetscScalar*** a;
    const Box& b = g.box();
    DMDAVecGetArrayDOF(g.dm_ten(), v, &a);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        a[j][i][0] = xx;
        a[j][i][1] = xy;
        a[j][i][2] = yy;
      }
    DMDAVecRestoreArrayDOF(g.dm_ten(), v, &a);
  };
  // Iterates from S = S^n (not 0: from 0 the boundary case lands on its answer at once).
  auto solve = [&](double r_factor, double theta, double dxx, double dxy) {
    rheology::Params pr;
    pr.yield = rheology::Yield::DruckerPrager;
    pr.r_factor = r_factor;
    fill(Sn, snxx, snxy, -snxx);
    fill(S, snxx, snxy, -snxx);
    fill(D, dxx + 0.3, dxy, -dxx + 0.3);  // a trace (0.6): only the deviatoric part counts
    double ch = 1;
    int it = 0;
    for (; it < 5000 && ch > 1e-14; ++it)
      ch = rheology::update_plastic(g, pr, S, Sn, k, D, rho, eta, a0dt, theta);
    EXPECT_LT(ch, 1e-13);
    EXPECT_GT(it, 5);  // a fixed point reached by iterating, not by the first projection
    const PetscScalar*** a;
    DMDAVecGetArrayDOFRead(g.dm_ten(), S, &a);
    const Box& b = g.box();
    std::array<double, 2> s = {a[b.ys][b.xs][0], a[b.ys][b.xs][1]};
    DMDAVecRestoreArrayDOFRead(g.dm_ten(), S, &a);
    return s;
  };
  const double h2 = 0.01 * 0.01;
  auto rk = [&](double rf) { return rf * (2.0 * et + rh * a0dt * h2) / kappa; };  // r kappa, s
  // Inside the ball, the same small strain rate (1/s) for three (r_factor, theta): the answer
  // moves with r / theta, and the first and last pairs, with the same r / theta, agree.
  const double dxx = 0.02, dxy = 0.01;
  std::array<double, 2> in[3];
  const double pairs[3][2] = {{0.25, 0.05}, {0.5, 0.05}, {0.5, 0.1}};
  for (int q = 0; q < 3; ++q) {
    const double rf = pairs[q][0], th = pairs[q][1], c = rk(rf) / th;
    in[q] = solve(rf, th, dxx, dxy);
    ASSERT_LT(std::hypot(snxx + c * dxx, snxy + c * dxy), 1.0);
    EXPECT_NEAR(in[q][0], snxx + c * dxx, 1e-12) << "r_factor " << rf << " theta " << th;
    EXPECT_NEAR(in[q][1], snxy + c * dxy, 1e-12) << "r_factor " << rf << " theta " << th;
  }
  EXPECT_GT(std::abs(in[1][0] - in[0][0]), 0.05);  // r doubled: a different step
  EXPECT_NEAR(in[2][0], in[0][0], 1e-12);          // r and theta doubled: the same
  EXPECT_NEAR(in[2][1], in[0][1], 1e-12);
  // On the yield surface: a large strain rate not parallel to S^n.
  for (const auto& pq : pairs) {
    const double rf = pq[0], th = pq[1], Dxx = 5.0, Dxy = 3.0;
    const auto t = solve(rf, th, Dxx, Dxy);
    const double ax = th * snxx + rk(rf) * Dxx, ay = th * snxy + rk(rf) * Dxy;
    const double n = std::hypot(ax, ay);
    EXPECT_NEAR(t[0], ax / n, 1e-12) << "r_factor " << rf << " theta " << th;
    EXPECT_NEAR(t[1], ay / n, 1e-12) << "r_factor " << rf << " theta " << th;
  }
}
