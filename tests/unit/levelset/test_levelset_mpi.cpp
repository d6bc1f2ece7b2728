// Parallel consistency of the level-set module: WENO5/RK3 advection, Min redistancing and the
// properties computed on PETSC_COMM_WORLD (1 or 2 ranks) must equal a serial recomputation on
// PETSC_COMM_SELF done by every rank inside the same test, to round-off.
#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "../helpers.hpp"

namespace ls = gf::levelset;
using gf::Field;
using gf::Grid;

namespace {

struct Outcome {
  double area, l1, redist_iters;
};

// Granular column on the left/bottom walls plus a disk, in the single vortex (the column's
// corner and walls exercise the wall stencils, the disk the interior ones): 24 RK3 steps with a
// redistancing every 6 steps, then a redistancing with early stop; rho and eta from the result.
Outcome evolve(const Grid& g, Vec phi, Vec rho, Vec eta) {
  const gf::Box& b = g.box();
  {
    PetscScalar** p;
    DMDAVecGetArray(g.dm_cell(), phi, &p);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double x = b.xc(i), y = b.yc(j);
        p[j][i] = std::min(ls::rectangle_distance(x, y, -1.0, 0.35, -1.0, 0.3),
                           ls::circle_distance(x, y, 0.6, 0.7, 0.15));
      }
    DMDAVecRestoreArray(g.dm_cell(), phi, &p);
  }
  Field vel(g.dm_vel(), "vel"), phi0(g.dm_cell(), "phi0");
  VecCopy(phi, phi0);
  ls::Advector adv(g);
  ls::Redistancer rd(g, 4, 0.5);
  const double T = 2.0;
  ls::single_vortex_velocity(g, vel, 0.0, T);
  const double dt = ls::max_cfl_dt(g, vel, 0.6);
  for (int k = 1; k <= 24; ++k) {
    ls::single_vortex_velocity(g, vel, (k - 0.5) * dt, T);
    adv.step(phi, vel, dt);
    if (k % 6 == 0) rd.run(phi);
  }
  ls::Redistancer rd2(g, 50, 0.5);
  rd2.set_tolerance(1e-3 * g.hx());
  const int its = rd2.run(phi);
  ls::update_properties(g, phi, {1.2, 1550, 1.8e-5, 0.5, 1.5 * g.hx()}, rho, eta);
  return {ls::granular_area(g, phi, 1.5 * g.hx()), ls::interface_l1_error(g, phi, phi0),
          static_cast<double>(its)};
}

// Max |a - b| / max |b| between a WORLD Vec (DMDA ordering) and a SELF Vec of the same grid.
double rel_diff(const Grid& gw, Vec world, Vec self) {
  const gf::test::WorldVsSelf d = gf::test::world_vs_self(gw.dm_cell(), world, self);
  return d.max_abs / d.max_ref;
}

}  // namespace

TEST(LevelSetParallel, SameResultAsSerial) {
  // Two shapes so that 2 ranks split the grid once along x and once along y (and hx != hy).
  const PetscInt sizes[2][2] = {{56, 32}, {32, 56}};
  for (const auto& sz : sizes) {
    Grid gw(PETSC_COMM_WORLD, sz[0], sz[1], 1.0, 1.0), gs(PETSC_COMM_SELF, sz[0], sz[1], 1.0, 1.0);
    Field pw(gw.dm_cell(), "phi"), rw(gw.dm_cell(), "rho"), ew(gw.dm_cell(), "eta");
    Field ps(gs.dm_cell(), "phi"), rs(gs.dm_cell(), "rho"), es(gs.dm_cell(), "eta");
    const Outcome ow = evolve(gw, pw, rw, ew);
    const Outcome os = evolve(gs, ps, rs, es);
    const double dphi = rel_diff(gw, pw, ps), drho = rel_diff(gw, rw, rs);
    const double deta = rel_diff(gw, ew, es);
    PetscInt px, py;
    DMDAGetInfo(gw.dm_cell(), nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
                nullptr, nullptr, nullptr, nullptr, nullptr);
    if (gw.rank() == 0)
      std::printf("%dx%d on %dx%d ranks: rel. diff phi %.2e rho %.2e eta %.2e; area %.12e vs "
                  "%.12e; L1 %.8e vs %.8e; redistancing its %g vs %g\n",
                  (int)sz[0], (int)sz[1], (int)px, (int)py, dphi, drho, deta, ow.area, os.area,
                  ow.l1, os.l1, ow.redist_iters, os.redist_iters);
    EXPECT_LE(dphi, 1e-12);
    EXPECT_LE(drho, 1e-12);
    EXPECT_LE(deta, 1e-12);
    EXPECT_NEAR(ow.area, os.area, 1e-12 * os.area);
    EXPECT_NEAR(ow.l1, os.l1, 1e-12 * os.l1 + 1e-15);
    EXPECT_GT(os.l1, 0.0);  // the interface did move: the comparison is not vacuous
    EXPECT_EQ(ow.redist_iters, os.redist_iters);
    EXPECT_LT(os.redist_iters, 50);  // the early stop was reached
  }
}
