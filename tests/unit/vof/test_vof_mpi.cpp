// The conservative volume fraction (vof/): PLIC geometry against closed forms, the initial
// fraction of known shapes, the Weymouth & Yue transport (volume conserved to round-off under a
// solenoidal velocity, a straight interface carried exactly, Zalesak's disc against the level
// set of section 3.1), the CLSVOF distance rebuild, and the same results on 1 and 2 ranks.
#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "grid/Local.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "vof/Plic.hpp"
#include "vof/Vof.hpp"
#include "../helpers.hpp"

namespace ls = gf::levelset;
namespace vof = gf::vof;
using gf::Field;
using gf::Grid;

namespace {

using gf::test::fill_cells;

double vec_min(Vec v) {
  PetscReal m;
  VecMin(v, nullptr, &m);
  return m;
}
double vec_max(Vec v) {
  PetscReal m;
  VecMax(v, nullptr, &m);
  return m;
}

// Max |a - b| between a WORLD Vec (DMDA ordering) and a SELF Vec of the same grid.
double max_diff(const Grid& gw, Vec world, Vec self) {
  return gf::test::world_vs_self(gw.dm_cell(), world, self).max_abs;
}

}  // namespace

// ----------------------------------------------------------------------------- PLIC geometry

TEST(VofPlic, AreaClosedFormsAndInverse) {
  // Closed forms: the diagonal halves the square, a horizontal line at height a keeps a, the
  // corner triangle x + y <= 1/2 has area 1/8, and the reflected normals mirror them.
  EXPECT_NEAR(vof::line_area(1, 1, 1), 0.5, 1e-15);
  EXPECT_NEAR(vof::line_area(0, 1, 0.3), 0.3, 1e-15);
  EXPECT_NEAR(vof::line_area(0, -1, -0.3), 0.7, 1e-15);
  EXPECT_NEAR(vof::line_area(1, 1, 0.5), 0.125, 1e-15);
  EXPECT_NEAR(vof::line_area(-1, -1, -1.5), 0.125, 1e-15);
  EXPECT_NEAR(vof::line_area(2, 1, 2.5), 1 - 0.5 * 0.5 * 0.25, 1e-15);  // x <= 1 - y/2 ... cut corner
  // Random lines: the inverse, the additivity of sub-rectangles, the segment end points.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), c01(0, 1);
  double worst_inv = 0, worst_add = 0, worst_seg = 0;
  for (int k = 0; k < 2000; ++k) {
    const double m1 = u(rng), m2 = u(rng), c = c01(rng);
    const double a = vof::line_alpha(m1, m2, c);
    worst_inv = std::max(worst_inv, std::abs(vof::line_area(m1, m2, a) - c));
    const vof::Line l{m1, m2, a};
    const double x = c01(rng), y = c01(rng);
    const double sum = vof::rect_area(l, 0, x, 0, y) + vof::rect_area(l, x, 1, 0, y) +
                       vof::rect_area(l, 0, x, y, 1) + vof::rect_area(l, x, 1, y, 1);
    worst_add = std::max(worst_add, std::abs(sum - c));
    double xa, ya, xb, yb;
    if (c > 1e-9 && c < 1 - 1e-9 && vof::line_segment(l, xa, ya, xb, yb))
      worst_seg = std::max({worst_seg, std::abs(m1 * xa + m2 * ya - a),
                            std::abs(m1 * xb + m2 * yb - a)});
  }
  std::printf("PLIC: inverse %.1e, sub-rectangle sum %.1e, segment on its line %.1e\n", worst_inv,
              worst_add, worst_seg);
  EXPECT_LT(worst_inv, 1e-12);
  EXPECT_LT(worst_add, 1e-12);
  EXPECT_LT(worst_seg, 1e-12);
}

// ----------------------------------------------------------------------- the initial fraction

TEST(VofInit, ExactForStraightSidesAndCircleArea) {
  Grid g(PETSC_COMM_WORLD, 64, 64, 1.0, 1.0);
  Field c(g.dm_cell(), "c");
  // A rectangle whose sides cut cells at 1/4 and 3/4 of their width: the fractions are exact
  // (its corner falls on a vertex of the 8 x 8 sub-squares; elsewhere a corner costs O(h^2/64)).
  const double h = 1.0 / 64;
  const double x1 = 20.25 * h, y1 = 30.75 * h;
  vof::init_fraction(g, c, [&](double x, double y) {
    return ls::rectangle_distance(x, y, -1.0, x1, -1.0, y1);
  });
  EXPECT_NEAR(vof::volume(g, c), x1 * y1, 1e-14);
  // A circle: the area to the sub-sampling's accuracy.
  const double r = 0.23;
  vof::init_fraction(g, c, [&](double x, double y) { return ls::circle_distance(x, y, 0.5, 0.5, r); });
  const double area = vof::volume(g, c), exact = std::numbers::pi * r * r;
  std::printf("init: circle area %.12f against %.12f (rel. %.1e)\n", area, exact,
              (area - exact) / exact);
  EXPECT_NEAR(area, exact, 1e-5 * exact);
  EXPECT_GE(vec_min(c), 0.0);
  EXPECT_LE(vec_max(c), 1.0);
}

// --------------------------------------------------------------------------------- transport

// The granular volume is conserved to round-off under a discretely solenoidal velocity (the
// fluxes cancel in pairs, the c_c terms of the two sweeps cancel), and 0 <= c <= 1 holds for
// |s| <= 1/2 with no clipping beyond round-off (Weymouth & Yue 2010, section 3). A column on the
// walls and a disc in the single vortex: corners, walls and a stretched filament.
TEST(VofTransport, ConservesVolumeAndBoundsUnderSolenoidalVelocity) {
  for (const auto normals : {vof::Normals::LevelSet, vof::Normals::Youngs}) {
    Grid g(PETSC_COMM_WORLD, 64, 48, 1.0, 1.0);
    Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi"), vel(g.dm_vel(), "vel");
    auto d = [](double x, double y) {
      return std::min(ls::rectangle_distance(x, y, -1.0, 0.3, -1.0, 0.25),
                      ls::circle_distance(x, y, 0.6, 0.7, 0.15));
    };
    vof::init_fraction(g, c, d);
    fill_cells(g, phi, d);
    const double v0 = vof::volume(g, c);
    vof::Advector adv(g);
    ls::Advector phi_adv(g);
    const double T = 4.0;
    ls::single_vortex_velocity(g, vel, 0.0, T);
    const double dt = ls::max_cfl_dt(g, vel, 0.5);
    double worst_clip = 0;
    for (int k = 0; k < 120; ++k) {
      ls::single_vortex_velocity(g, vel, (k + 0.5) * dt, T);
      adv.step(c, vel, phi, dt, k, normals);
      worst_clip = std::max(worst_clip, adv.clipped());
      phi_adv.step(phi, vel, dt);
      vof::rebuild_distance(g, c, phi, normals);
    }
    const double v1 = vof::volume(g, c);
    std::printf("transport (%s normals): volume change %.2e relative, clipped %.1e, c in [%.1e, "
                "1 + %.1e]\n",
                normals == vof::Normals::LevelSet ? "level-set" : "Youngs", (v1 - v0) / v0,
                worst_clip, vec_min(c), vec_max(c) - 1);
    EXPECT_LT(std::abs(v1 - v0), 1e-13 * v0);
    EXPECT_LT(worst_clip, 1e-13);
    EXPECT_GE(vec_min(c), 0.0);
    EXPECT_LE(vec_max(c), 1.0);
  }
}

// A straight interface carried by a uniform velocity across a periodic domain comes back to
// itself: the PLIC line of a straight vertical interface is exact, so every flux is.
TEST(VofTransport, VerticalBandTranslatesExactly) {
  const PetscInt n = 40;
  Grid g(PETSC_COMM_WORLD, n, 16, 1.0, 0.4, true);
  Field c(g.dm_cell(), "c"), c0(g.dm_cell(), "c0"), phi(g.dm_cell(), "phi"),
      vel(g.dm_vel(), "vel");
  auto d = [](double x, double) { return std::abs(x - 0.41) - 0.173; };  // a band 0.346 wide
  vof::init_fraction(g, c, d);
  VecCopy(c, c0);
  fill_cells(g, phi, d);
  VecSet(vel, 0.0);
  {
    const gf::Box& b = g.box();
    gf::Vel** v;
    DMDAVecGetArray(g.dm_vel(), vel, &v);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) v[j][i].u = 0.37;
    DMDAVecRestoreArray(g.dm_vel(), vel, &v);
  }
  // 0.37 m/s, s = 0.4 per step: 100 steps carry the band one period (1 m).
  const double dt = 0.4 * g.hx() / 0.37;
  vof::Advector adv(g);
  ls::Advector phi_adv(g);
  for (int k = 0; k < 100; ++k) {
    adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
    phi_adv.step(phi, vel, dt);
    vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
  }
  Vec diff;
  VecDuplicate(c, &diff);
  VecWAXPY(diff, -1.0, c0, c);
  PetscReal err;
  VecNorm(diff, NORM_INFINITY, &err);
  VecDestroy(&diff);
  std::printf("band after one period: max |c - c0| = %.1e\n", err);
  EXPECT_LT(err, 1e-12);
}

// Zalesak's disc, one turn at 64^2: the mass to round-off, and an interface error (the level
// set's symmetric difference with the exact disc, as summary.json's interface_l1_error_m2) no
// larger than the level set's own (section 3.1: WENO5 + TVD-RK3, redistanced every 10 steps, as
// cases/verify/zalesak.toml) on the same grid and steps.
TEST(VofTransport, ZalesakOneTurnBeatsTheLevelSet) {
  Grid g(PETSC_COMM_WORLD, 64, 64, 1.0, 1.0);
  Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi"), phi0(g.dm_cell(), "phi0"),
      ls_phi(g.dm_cell(), "ls"), vel(g.dm_vel(), "vel");
  auto d = [](double x, double y) {
    return ls::zalesak_distance(x, y, 0.5, 0.75, 0.15, 0.05, 0.25);
  };
  fill_cells(g, phi0, d);
  VecCopy(phi0, phi);
  VecCopy(phi0, ls_phi);
  vof::init_fraction(g, c, d);
  const double v0 = vof::volume(g, c);
  ls::rotation_velocity(g, vel, 1.0, 0.5, 0.5);
  const int steps = 489;  // dt ~ 0.5 h / |u|max as the bench (docs/levelset_verification.md)
  const double dt = 2 * std::numbers::pi / steps;
  vof::Advector adv(g);
  ls::Advector phi_adv(g);
  ls::Redistancer rd(g, 10, 0.5);
  for (int k = 0; k < steps; ++k) {
    adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
    phi_adv.step(phi, vel, dt);
    vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
    phi_adv.step(ls_phi, vel, dt);
    if ((k + 1) % 10 == 0) rd.run(ls_phi);
  }
  const double l1_vof = ls::interface_l1_error(g, phi, phi0);
  const double l1_ls = ls::interface_l1_error(g, ls_phi, phi0);
  const double dv = (vof::volume(g, c) - v0) / v0;
  std::printf("Zalesak 64^2: CLSVOF L1 %.3e m^2, volume change %.1e; level set L1 %.3e m^2\n",
              l1_vof, dv, l1_ls);
  EXPECT_LT(std::abs(dv), 1e-12);
  EXPECT_LT(l1_vof, l1_ls);
}

// ------------------------------------------------------------------------------- the rebuild

// phi rebuilt from the fraction of a circle is the circle's distance within the PLIC
// approximation (second order: the chord of an arc of one cell lies within h^2 / (8 R) of it),
// and its sign is the fraction's.
TEST(VofRebuild, CircleDistance) {
  const PetscInt n = 64;
  Grid g(PETSC_COMM_WORLD, n, n, 1.0, 1.0);
  Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi");
  const double R = 0.27;
  auto d = [&](double x, double y) { return ls::circle_distance(x, y, 0.48, 0.53, R); };
  vof::init_fraction(g, c, d);
  fill_cells(g, phi, d);
  vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
  const gf::Box& b = g.box();
  const double h = b.hx;
  const gf::LocalCells p(g.dm_cell(), phi), cc(g.dm_cell(), c);
  double near = 0, sign_bad = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double e = d(b.xc(i), b.yc(j));
      if (std::abs(e) < 2.5 * h) near = std::max(near, std::abs(p[j][i] - e));
      if ((p[j][i] < 0) != (cc[j][i] > 0.5)) sign_bad += 1;
    }
  near = g.max(near);
  sign_bad = g.sum(sign_bad);
  std::printf("rebuild: circle distance within 2.5 h: max error %.4f h\n", near / h);
  EXPECT_LT(near, 0.05 * h);
  EXPECT_EQ(sign_bad, 0.0);
}

// --------------------------------------------------------------------------------- parallel

TEST(VofParallel, SameResultAsSerial) {
  const PetscInt sizes[2][2] = {{56, 32}, {32, 56}};
  for (const auto& sz : sizes) {
    double cdiff = 0, pdiff = 0;
    Grid gw(PETSC_COMM_WORLD, sz[0], sz[1], 1.0, 1.0), gs(PETSC_COMM_SELF, sz[0], sz[1], 1.0, 1.0);
    Field cw(gw.dm_cell(), "c"), pw(gw.dm_cell(), "phi"), cs(gs.dm_cell(), "c"),
        ps(gs.dm_cell(), "phi");
    auto run = [](const Grid& g, Vec c, Vec phi) {
      auto d = [](double x, double y) {
        return std::min(ls::rectangle_distance(x, y, -1.0, 0.35, -1.0, 0.3),
                        ls::circle_distance(x, y, 0.6, 0.7, 0.15));
      };
      vof::init_fraction(g, c, d);
      fill_cells(g, phi, d);
      Field vel(g.dm_vel(), "vel");
      vof::Advector adv(g);
      ls::Advector phi_adv(g);
      ls::single_vortex_velocity(g, vel, 0.0, 2.0);
      const double dt = ls::max_cfl_dt(g, vel, 0.5);
      for (int k = 0; k < 30; ++k) {
        ls::single_vortex_velocity(g, vel, (k + 0.5) * dt, 2.0);
        adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
        phi_adv.step(phi, vel, dt);
        vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
      }
    };
    run(gw, cw, pw);
    run(gs, cs, ps);
    cdiff = max_diff(gw, cw, cs);
    pdiff = max_diff(gw, pw, ps);
    if (gw.rank() == 0)
      std::printf("%dx%d: 1 vs %d ranks: max |dc| %.1e, max |dphi| %.1e m\n", (int)sz[0],
                  (int)sz[1], gw.size(), cdiff, pdiff);
    EXPECT_LE(cdiff, 1e-13);
    EXPECT_LE(pdiff, 1e-13);
  }
}
