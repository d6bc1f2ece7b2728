// Diagnostics against exact answers, on 1 and 2 ranks (the _mpi suffix runs both).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/Error.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/Heaviside.hpp"

namespace {

using gf::Grid;

template <class F>
void set_cells(const Grid& g, Vec v, F f) {
  const gf::Box& b = g.box();
  PetscScalar** a;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), v, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = f(i, j);
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), v, &a));
}

// fu(i, j): u on the left face of cell (i, j); fv(i, j): v on its bottom face.
template <class Fu, class Fv>
void set_vel(const Grid& g, Vec v, Fu fu, Fv fv) {
  const gf::Box& b = g.box();
  gf::Vel** a;
  GF_PETSC(DMDAVecGetArray(g.dm_vel(), v, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = {fu(i, j), fv(i, j)};
  GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), v, &a));
}

// Uniform flow (U, V) with the wall faces i = 0 / j = 0 at zero, as the convention requires.
void uniform(const Grid& g, Vec vel, double U, double V) {
  set_vel(g, vel, [&](PetscInt i, PetscInt) { return i == 0 ? 0.0 : U; },
          [&](PetscInt, PetscInt j) { return j == 0 ? 0.0 : V; });
}

TEST(Diagnostics, UniformFlowSpeedAndEnergy) {
  Grid g(PETSC_COMM_WORLD, 16, 12, 0.8, 0.3);
  gf::State s(g);
  const double U = 0.3, V = -0.4, rho = 1500;
  uniform(g, s.vel, U, V);
  GF_PETSC(VecSet(s.rho, rho));
  // Interior cells see U and V on both faces; wall cells see half of them.
  EXPECT_NEAR(gf::diag::max_speed(g, s.vel), 0.5, 1e-15);
  // Mean of squares: each interior face counts once in total, wall faces not at all.
  const double nx = 16, ny = 12, hxhy = g.hx() * g.hy();
  const double ke = 0.5 * rho * hxhy * ((nx - 1) * ny * U * U + nx * (ny - 1) * V * V);
  EXPECT_NEAR(gf::diag::kinetic_energy(g, s.vel, s.rho), ke, 1e-13 * ke);
}

TEST(Diagnostics, CheckerboardModeHasEnergy) {
  // u = +-U alternating: the face-average velocity is 0 in every interior cell, so the
  // square of the mean would report no energy; the mean of squares reports all of it.
  Grid g(PETSC_COMM_WORLD, 16, 12, 1.0, 1.0);
  gf::State s(g);
  const double U = 2.0;
  set_vel(g, s.vel, [&](PetscInt i, PetscInt) { return i == 0 ? 0.0 : (i % 2 ? U : -U); },
          [](PetscInt, PetscInt) { return 0.0; });
  GF_PETSC(VecSet(s.rho, 1.0));
  const double ke = 0.5 * g.hx() * g.hy() * 15 * 12 * U * U;
  EXPECT_NEAR(gf::diag::kinetic_energy(g, s.vel, s.rho), ke, 1e-13 * ke);
  EXPECT_NEAR(gf::diag::max_speed(g, s.vel), U / 2, 1e-15);  // only the wall cells
}

TEST(Diagnostics, StreamFunctionFieldIsDivergenceFree) {
  // psi at the nodes (i hx, j hy), zero on the walls: u = d psi / dy, v = -d psi / dx by
  // differences. The discrete divergence cancels identically, so only round-off remains.
  Grid g(PETSC_COMM_WORLD, 24, 16, 2.0, 1.0);
  gf::State s(g);
  const double hx = g.hx(), hy = g.hy(), pi = std::numbers::pi;
  auto psi = [&](PetscInt i, PetscInt j) {
    return std::sin(pi * i * hx / 2.0) * std::sin(pi * j * hy) * (1 + 0.3 * i * hx);
  };
  set_vel(g, s.vel, [&](PetscInt i, PetscInt j) { return (psi(i, j + 1) - psi(i, j)) / hy; },
          [&](PetscInt i, PetscInt j) { return -(psi(i + 1, j) - psi(i, j)) / hx; });
  const double umax = gf::diag::max_speed(g, s.vel);
  ASSERT_GT(umax, 0.5);
  EXPECT_LT(gf::diag::max_divergence(g, s.vel), 1e-13 * umax / hy);
}

TEST(Diagnostics, KnownDivergenceIncludingWallCells) {
  // u = a x (Lx - x), v = b y (Ly - y) at the faces: zero on all four walls, so this is a
  // valid MAC field. Discrete divergence of cell (i, j):
  //   a (Lx - 2 i hx - hx) + b (Ly - 2 j hy - hy),
  // largest in magnitude in the corner cells (0, 0) and (nx-1, ny-1), the second of which
  // needs the unstored wall faces i = nx and j = ny.
  Grid g(PETSC_COMM_WORLD, 20, 10, 1.0, 0.5);
  gf::State s(g);
  const double a = 3.0, b = 5.0, Lx = 1.0, Ly = 0.5, hx = g.hx(), hy = g.hy();
  set_vel(g, s.vel, [&](PetscInt i, PetscInt) { return a * i * hx * (Lx - i * hx); },
          [&](PetscInt, PetscInt j) { return b * j * hy * (Ly - j * hy); });
  const double expect = a * (Lx - hx) + b * (Ly - hy);
  EXPECT_NEAR(gf::diag::max_divergence(g, s.vel), expect, 1e-12 * expect);
}

TEST(Diagnostics, DivergenceAcrossRankBoundary) {
  // A single nonzero face in the middle of the domain (where 2 ranks split): both cells on
  // either side see |u| / hx, one of them through the ghost exchange.
  Grid g(PETSC_COMM_WORLD, 16, 16, 1.0, 1.0);
  gf::State s(g);
  const double u = 0.7;
  set_vel(g, s.vel, [&](PetscInt i, PetscInt j) { return i == 8 && j == 3 ? u : 0.0; },
          [&](PetscInt i, PetscInt j) { return 0.0 * i * j; });
  EXPECT_NEAR(gf::diag::max_divergence(g, s.vel), u / g.hx(), 1e-13);
  set_vel(g, s.vel, [&](PetscInt i, PetscInt j) { return 0.0 * i * j; },
          [&](PetscInt i, PetscInt j) { return i == 5 && j == 8 ? -u : 0.0; });
  EXPECT_NEAR(gf::diag::max_divergence(g, s.vel), u / g.hy(), 1e-13);
}

TEST(Diagnostics, NaNPropagatesToEveryRank) {
  Grid g(PETSC_COMM_WORLD, 16, 16, 1.0, 1.0);
  gf::State s(g);
  // One NaN face in the last cell, owned by the last rank only.
  set_vel(g, s.vel,
          [&](PetscInt i, PetscInt j) {
            return i == 15 && j == 15 ? std::numeric_limits<double>::quiet_NaN() : 0.1;
          },
          [](PetscInt, PetscInt) { return 0.0; });
  EXPECT_TRUE(std::isnan(gf::diag::max_speed(g, s.vel)));
  EXPECT_TRUE(std::isnan(gf::diag::max_divergence(g, s.vel)));
}

TEST(Diagnostics, GranularVolumeOfLayerIsExact) {
  // phi = y - b with b on a face: the centres pair up symmetrically about the interface and
  // H(d) + H(-d) = 1, so the smoothed volume equals Lx * b to round-off for any eps.
  Grid g(PETSC_COMM_WORLD, 16, 32, 0.8, 0.4);
  gf::State s(g);
  const double b = 10 * g.hy();
  set_cells(g, s.phi, [&](PetscInt, PetscInt j) { return g.box().yc(j) - b; });
  for (double eps : {0.5 * g.hy(), 1.5 * g.hy(), 3.0 * g.hy()})
    EXPECT_NEAR(gf::diag::granular_volume(g, s.phi, eps), 0.8 * b, 1e-14) << "eps = " << eps;
}

TEST(Diagnostics, GranularVolumeOfRectangle) {
  // Grid-aligned rectangle [a0, a1] x [b0, b1], phi = max(a0 - x, x - a1, b0 - y, y - b1)
  // (the signed distance inside). Along the edges the 1D pairing argument above makes the
  // sum exact; only the four corner squares of side ~2 eps differ from the sharp area.
  Grid g(PETSC_COMM_WORLD, 40, 40, 1.0, 1.0);
  gf::State s(g);
  const double h = g.hx(), a0 = 8 * h, a1 = 30 * h, b0 = 5 * h, b1 = 22 * h;
  set_cells(g, s.phi, [&](PetscInt i, PetscInt j) {
    const double x = g.box().xc(i), y = g.box().yc(j);
    return std::max(std::max(a0 - x, x - a1), std::max(b0 - y, y - b1));
  });
  const double area = (a1 - a0) * (b1 - b0);
  const double eps = 1.5 * h;
  EXPECT_NEAR(gf::diag::granular_volume(g, s.phi, eps), area, 4 * eps * eps);
  // Sharp limit (eps below half a cell): exactly the cells inside.
  EXPECT_NEAR(gf::diag::granular_volume(g, s.phi, 0.25 * h), area, 1e-14);
}

TEST(Diagnostics, MaxInGranular) {
  Grid g(PETSC_COMM_WORLD, 16, 12, 1.0, 1.0);
  gf::State s(g);
  set_cells(g, s.eta, [](PetscInt i, PetscInt j) { return i + 100.0 * j; });
  set_cells(g, s.phi, [&](PetscInt, PetscInt j) { return j < 5 ? -1.0 : 1.0; });
  EXPECT_EQ(gf::diag::max_in_granular(g, s.eta, s.phi), 15 + 400.0);
  // Negative values are reported as they are (a max, not a max of |f|).
  set_cells(g, s.p, [](PetscInt i, PetscInt j) { return -1.0 - i - j; });
  EXPECT_EQ(gf::diag::max_in_granular(g, s.p, s.phi), -1.0);
  GF_PETSC(VecSet(s.phi, 1.0));  // all air
  EXPECT_EQ(gf::diag::max_in_granular(g, s.eta, s.phi), 0.0);
}

}  // namespace

// Failure locations (sim/ stops a run with "what, where"): the first non-finite cell in (j, i)
// order over all ranks, whatever the field's dof, and the cell of the largest speed.
namespace {
TEST(Diagnostics, FirstNonFiniteCell) {
  Grid g(PETSC_COMM_WORLD, 16, 12, 0.8, 0.3);
  gf::State s(g);
  EXPECT_FALSE(gf::diag::first_nonfinite(g, s.p).found());
  // Two bad cells in p, on different rows (on 2 ranks the rows 2 and 9 lie on different
  // ranks): the one with the lower j is reported.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  set_cells(g, s.p, [&](PetscInt i, PetscInt j) {
    return (i == 3 && j == 9) || (i == 11 && j == 2) ? nan : 1.0;
  });
  auto c = gf::diag::first_nonfinite(g, s.p);
  EXPECT_EQ(c.i, 11);
  EXPECT_EQ(c.j, 2);
  // An infinity in the third component of the tensor S (dof 3) at cell (7, 10).
  const gf::Box& b = g.box();
  PetscScalar*** S;
  GF_PETSC(DMDAVecGetArrayDOF(g.dm_ten(), s.S, &S));
  if (7 >= b.xs && 7 < b.xe() && 10 >= b.ys && 10 < b.ye())
    S[10][7][2] = std::numeric_limits<double>::infinity();
  GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_ten(), s.S, &S));
  c = gf::diag::first_nonfinite(g, s.S);
  EXPECT_EQ(c.i, 7);
  EXPECT_EQ(c.j, 10);
}

TEST(Diagnostics, MaxSpeedLocation) {
  Grid g(PETSC_COMM_WORLD, 16, 12, 0.8, 0.3);
  gf::State s(g);
  // u = 2 m/s on both x-faces of cell (5, 8) only: speed 2 there, 1 in its neighbours.
  set_vel(g, s.vel, [](PetscInt i, PetscInt j) { return j == 8 && (i == 5 || i == 6) ? 2.0 : 0.0; },
          [](PetscInt, PetscInt) { return 0.0; });
  const auto sp = gf::diag::max_speed_at(g, s.vel);
  EXPECT_DOUBLE_EQ(sp.speed, 2.0);
  EXPECT_EQ(sp.at.i, 5);
  EXPECT_EQ(sp.at.j, 8);
}
}  // namespace
