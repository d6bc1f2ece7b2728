// The side walls of a channel (boundary/SideWalls.hpp) against exact answers: the projection
// onto the disc, the friction bound k = (2/W) tan(alpha_w) K p^+ c, the air's drag coefficient,
// the adjointness of the face force -I^T (k s) and the cell velocity I u (the power of the force
// is -sum k s . I u hx hy, on walled and periodic grids, over MPI subdomains), and the update's
// stick and slide.
#include <gtest/gtest.h>

#include <cmath>

#include "boundary/SideWalls.hpp"
#include "fields/Fields.hpp"
#include "../helpers.hpp"

using namespace gf;

TEST(SideWalls, ProjectionOntoUnitDisc) {
  double x = 3.0, y = -4.0;
  boundary::project_disc(x, y);
  EXPECT_DOUBLE_EQ(x, 0.6);
  EXPECT_DOUBLE_EQ(y, -0.8);
  x = 0.3, y = 0.4;  // inside: unchanged
  boundary::project_disc(x, y);
  EXPECT_DOUBLE_EQ(x, 0.3);
  EXPECT_DOUBLE_EQ(y, 0.4);
}

TEST(SideWalls, FrictionBoundAndAirDrag) {
  Grid g(PETSC_COMM_WORLD, 8, 8, 0.4, 0.4);
  boundary::SideWallParams p;
  p.width = 0.1;
  p.tan_w = std::tan(10.0 * M_PI / 180);
  p.earth_pressure = 0.8;
  p.eta_b = 2.0;
  p.eta_air = 1.8e-5;
  const boundary::SideWalls sw(g, p);
  ASSERT_TRUE(sw.active());
  ASSERT_TRUE(sw.air_drag());
  Field c(g.dm_cell(), "c"), w(g.dm_cell(), "w"), pr(g.dm_cell(), "p"), k(g.dm_cell(), "k"),
      d(g.dm_cell(), "d");
  auto cf = [](double x, double) { return x < 0.2 ? 1.0 : 0.25; };
  auto wf = [](double, double y) { return y < 0.3 ? 0.0 : -1.0; };  // support: y < 0.3
  auto pf = [](double x, double y) { return 1000.0 * (0.25 - y) + 10 * x; };
  test::fill_cells(g, c, cf);
  test::fill_cells(g, w, wf);
  test::fill_cells(g, pr, pf);
  sw.yield(c, w, pr, k);
  sw.drag(c, d);
  const double coef = 2.0 / 0.1 * p.tan_w * 0.8;
  const double dcoef = 2.0 / 0.1 * 1.8e-5 * 2.0 / (1.8e-5 + 2.0 * 0.1 / 6.0);
  const Box& b = g.box();
  const PetscScalar **ka, **da;
  DMDAVecGetArrayRead(g.dm_cell(), k, &ka);
  DMDAVecGetArrayRead(g.dm_cell(), d, &da);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double x = b.xc(i), y = b.yc(j);
      const double want = wf(x, y) >= 0 ? coef * std::max(pf(x, y), 0.0) * cf(x, y) : 0.0;
      EXPECT_NEAR(ka[j][i], want, 1e-12 * coef * 1000) << i << " " << j;
      EXPECT_NEAR(da[j][i], dcoef * (1 - cf(x, y)), 1e-15);
    }
  DMDAVecRestoreArrayRead(g.dm_cell(), d, &da);
  DMDAVecRestoreArrayRead(g.dm_cell(), k, &ka);
}

// sum_faces u . (-I^T k s) hx hy = -sum_cells k s . I u hx hy, with the wall faces' u = 0.
static void check_adjoint(bool periodic) {
  Grid g(PETSC_COMM_WORLD, 9, 8, 0.9, 0.8, periodic);
  boundary::SideWallParams p;
  p.width = 0.05;
  p.tan_w = 0.3;
  const boundary::SideWalls sw(g, p);
  Field k(g.dm_cell(), "k"), s(g.dm_vel(), "s"), u(g.dm_vel(), "u"), f(g.dm_vel(), "f");
  test::fill_cells(g, k, [](double x, double y) { return x + y > 0.6 ? 50 * (1 + x * y) : 0.0; });
  const Box& b = g.box();
  Vel **sa, **ua;
  DMDAVecGetArray(g.dm_vel(), s, &sa);
  DMDAVecGetArray(g.dm_vel(), u, &ua);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      sa[j][i].u = std::sin(1.3 * i + 0.7 * j);
      sa[j][i].v = std::cos(0.4 * i - 1.1 * j);
      ua[j][i].u = b.wall_u(i) ? 0.0 : std::cos(2.1 * i + 0.3 * j);
      ua[j][i].v = j == 0 ? 0.0 : std::sin(0.9 * i * j + 0.2);
    }
  DMDAVecRestoreArray(g.dm_vel(), u, &ua);
  DMDAVecRestoreArray(g.dm_vel(), s, &sa);
  VecSet(f, 0.0);
  sw.add_force(k, s, f);
  PetscScalar dot;
  VecDot(u, f, &dot);
  const double pw = sw.power(u, k, s);
  EXPECT_NEAR(dot * b.hx * b.hy, pw, 1e-12 * std::abs(pw));
  EXPECT_GT(std::abs(pw), 1e-3);
}

TEST(SideWalls, ForceIsTheAdjointOfTheCellVelocity) { check_adjoint(false); }
TEST(SideWalls, ForceIsTheAdjointOfTheCellVelocityPeriodic) { check_adjoint(true); }

TEST(SideWalls, UpdateSticksAndSlides) {
  Grid g(PETSC_COMM_WORLD, 8, 8, 0.8, 0.8, true);
  boundary::SideWallParams p;
  p.width = 0.1;
  p.tan_w = 0.2;
  const boundary::SideWalls sw(g, p);
  Field k(g.dm_cell(), "k"), s(g.dm_vel(), "s"), sn(g.dm_vel(), "sn"), u(g.dm_vel(), "u"),
      rho(g.dm_cell(), "rho"), eta(g.dm_cell(), "eta");
  VecSet(k, 100.0);
  VecSet(rho, 1500.0);
  VecSet(eta, 0.5);
  // A uniform velocity along (3, -4): one update with theta = 0 from s = 0 lands on the disc's
  // boundary at U/|U| (r k |U| = r_factor (rho a0/dt + 2 eta/h^2) |U| / k >> 1).
  const Box& b = g.box();
  Vel** ua;
  DMDAVecGetArray(g.dm_vel(), u, &ua);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      ua[j][i].u = 0.3;
      ua[j][i].v = j == 0 ? 0.0 : -0.4;  // wall faces j = 0, ny: v = 0 (their cells see -0.2)
    }
  DMDAVecRestoreArray(g.dm_vel(), u, &ua);
  sw.update(u, k, s, sn, rho, eta, 1000.0, 0.0, 1.0, 100.0);
  const Vel** sa;
  DMDAVecGetArrayRead(g.dm_vel(), s, &sa);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const bool wall = j == 0 || j == b.ny - 1;  // U = (0.3, -0.2)
      const double m = wall ? std::hypot(0.3, 0.2) : 0.5;
      EXPECT_NEAR(sa[j][i].u, 0.3 / m, 1e-14);
      EXPECT_NEAR(sa[j][i].v, (wall ? -0.2 : -0.4) / m, 1e-14);
    }
  DMDAVecRestoreArrayRead(g.dm_vel(), s, &sa);
  // At rest the direction stays where it is (inside the disc: stick), whatever it is.
  VecSet(u, 0.0);
  VecSet(s, 0.0);
  VecSetValue(s, 0, 0.5, INSERT_VALUES);  // rank 0's first cell, s_x = 0.5
  VecAssemblyBegin(s);
  VecAssemblyEnd(s);
  VecCopy(s, sn);
  const double ch = sw.update(u, k, s, sn, rho, eta, 1000.0, 0.1, 1.0, 100.0);
  EXPECT_EQ(ch, 0.0);
  PetscReal nrm;
  VecNorm(s, NORM_INFINITY, &nrm);
  EXPECT_DOUBLE_EQ(nrm, 0.5);
}
