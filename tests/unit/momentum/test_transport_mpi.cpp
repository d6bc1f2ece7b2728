// The momentum transport consistent with the volume-fraction mass transport
// (momentum::Predictor::transport, ops::momentum_sweep): a uniform velocity crosses a density
// jump of 1300 unchanged (the momentum jump travels with the density jump), the transported
// velocity stays within the bounds of the old one, and the kinetic energy of a transport step
// does not grow; on 1 and 2 ranks.
#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "boundary/Boundary.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "grid/Local.hpp"
#include "momentum/Momentum.hpp"
#include "operators/Operators.hpp"
#include "projection/Projection.hpp"
#include "vof/Vof.hpp"
#include "../helpers.hpp"

namespace ls = gf::levelset;
namespace vof = gf::vof;
using gf::Field;
using gf::Grid;

namespace {

constexpr double kRhoAir = 1.2, kRhoGran = 1550;

using gf::test::fill_cells;

// The face kinetic energy sum 1/2 rho_f u^2 hx hy with rho_f the mean of the two cells' rho(c).
double face_energy(const Grid& g, Vec vel, Vec c) {
  const gf::Box& b = g.box();
  Vec lc;
  DMGetLocalVector(g.dm_cell(), &lc);
  gf::to_local(g.dm_cell(), c, lc);
  const PetscScalar** a;
  const gf::Vel** v;
  DMDAVecGetArrayRead(g.dm_cell(), lc, &a);
  DMDAVecGetArrayRead(g.dm_vel(), vel, &v);
  auto rho = [](double cv) { return kRhoAir + (kRhoGran - kRhoAir) * cv; };
  double e = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (!b.wall_u(i)) e += 0.25 * (rho(a[j][i - 1]) + rho(a[j][i])) * v[j][i].u * v[j][i].u;
      if (j > 0) e += 0.25 * (rho(a[j - 1][i]) + rho(a[j][i])) * v[j][i].v * v[j][i].v;
    }
  DMDAVecRestoreArrayRead(g.dm_vel(), vel, &v);
  DMDAVecRestoreArrayRead(g.dm_cell(), lc, &a);
  DMRestoreLocalVector(g.dm_cell(), &lc);
  return g.sum(e) * b.hx * b.hy;
}

// max and min over the owned faces of one component (0: u, 1: v), walls left out.
void bounds(const Grid& g, Vec vel, int comp, double& lo, double& hi) {
  const gf::Box& b = g.box();
  const gf::Vel** v;
  DMDAVecGetArrayRead(g.dm_vel(), vel, &v);
  lo = 1e300, hi = -1e300;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (comp == 0 && b.wall_u(i)) continue;
      if (comp == 1 && j == 0) continue;
      const double q = comp == 0 ? v[j][i].u : v[j][i].v;
      lo = std::min(lo, q);
      hi = std::max(hi, q);
    }
  DMDAVecRestoreArrayRead(g.dm_vel(), vel, &v);
  lo = -g.max(-lo);
  hi = g.max(hi);
}

}  // namespace

// A heavy disc (1550 kg/m^3 in 1.2 kg/m^3 air) carried by a uniform velocity across a periodic
// channel: after each step's volume-fraction transport, the transported velocity u* is still the
// uniform one. A velocity transport that ignores the mass fluxes also keeps it, but a momentum
// transport with mass fluxes other than the density's would not: rho_f^{n+1} u* must be
// rho_f^n U minus the fluxes of rho_f^n U exactly.
TEST(MomentumTransport, UniformVelocityCrossesTheDensityJump) {
  Grid g(PETSC_COMM_WORLD, 48, 24, 1.0, 0.5, true);
  Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi"), vel(g.dm_vel(), "vel"),
      ustar(g.dm_vel(), "ustar");
  auto d = [](double x, double y) { return ls::circle_distance(x, y, 0.43, 0.23, 0.13); };
  vof::init_fraction(g, c, d);
  {
    const gf::Box& b = g.box();
    fill_cells(g, phi, d);
    gf::Vel** v;
    DMDAVecGetArray(g.dm_vel(), vel, &v);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        v[j][i].u = 0.8;
        v[j][i].v = 0.0;
      }
    DMDAVecRestoreArray(g.dm_vel(), vel, &v);
  }
  gf::Boundaries bc;
  gf::momentum::Predictor pred(g, bc, 1e-10);
  vof::Advector adv(g);
  const double dt = 0.45 * g.hx() / 0.8;
  double worst_u = 0, worst_v = 0;
  for (int k = 0; k < 40; ++k) {
    adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
    vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
    const gf::momentum::MassSweeps m{adv.flux(), adv.c_start(), c, adv.cc(), kRhoAir, kRhoGran};
    pred.transport(vel, vel, m, dt, ustar);
    double lo, hi;
    bounds(g, ustar, 0, lo, hi);
    worst_u = std::max({worst_u, std::abs(hi - 0.8), std::abs(lo - 0.8)});
    bounds(g, ustar, 1, lo, hi);
    worst_v = std::max({worst_v, std::abs(hi), std::abs(lo)});
  }
  std::printf("uniform 0.8 m/s across a 1300:1 jump, 40 steps: max |u* - U| %.1e, max |v*| %.1e\n",
              worst_u, worst_v);
  EXPECT_LT(worst_u, 1e-12);
  EXPECT_LT(worst_v, 1e-12);
}

// Where the density is uniform the consistent transport is the conservative MUSCL convection
// of the level-set scheme (ops::convection, explicit Euler): the mass fluxes are then rho s and
// the side fluxes the means of the face velocities that convection() uses.
TEST(MomentumTransport, SinglePhaseIsTheConvectionStep) {
  Grid g(PETSC_COMM_WORLD, 36, 28, 1.0, 1.0);
  Field c(g.dm_cell(), "c"), vel(g.dm_vel(), "vel"), ustar(g.dm_vel(), "ustar"),
      conv(g.dm_vel(), "conv");
  VecSet(c, 0.0);
  ls::single_vortex_velocity(g, vel, 0.3, 8.0);
  gf::Boundaries bc;
  gf::momentum::Predictor pred(g, bc, 1e-10);
  vof::Advector adv(g);
  const double dt = ls::max_cfl_dt(g, vel, 0.5);
  adv.step(c, vel, nullptr, dt, 0, vof::Normals::Youngs);
  const gf::momentum::MassSweeps m{adv.flux(), adv.c_start(), c, adv.cc(), kRhoAir, kRhoGran};
  pred.transport(vel, vel, m, dt, ustar);
  const gf::Box& b = g.box();
  double worst = 0, scale = 0;
  {
    gf::LocalVelocity lv(g, vel);
    gf::Vel** cv;
    DMDAVecGetArray(g.dm_vel(), conv, &cv);
    gf::ops::convection(b, lv.array(), cv);
    const gf::Vel** us;
    DMDAVecGetArrayRead(g.dm_vel(), ustar, &us);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        worst = std::max({worst, std::abs(us[j][i].u - (lv[j][i].u - dt * cv[j][i].u)),
                          std::abs(us[j][i].v - (lv[j][i].v - dt * cv[j][i].v))});
        scale = std::max({scale, std::abs(dt * cv[j][i].u), std::abs(dt * cv[j][i].v)});
      }
    DMDAVecRestoreArrayRead(g.dm_vel(), ustar, &us);
    DMDAVecRestoreArray(g.dm_vel(), conv, &cv);
  }
  worst = g.max(worst);
  scale = g.max(scale);
  std::printf("single phase: max |u* - (u - dt conv(u))| = %.1e (the convection term reaches "
              "%.1e m/s)\n",
              worst, scale);
  EXPECT_GT(scale, 1e-3);  // the flow does convect: the comparison is not vacuous
  EXPECT_LT(worst, 1e-14);
}

// A heavy disc in a solid-body rotation, transport alone (no pressure, no viscosity): the
// transported velocity stays within the old bounds (the sides are upwinded and the MUSCL
// correction limited where the upwind control volume's local Courant number M / rho_b is large;
// without that limit the first step leaves the bounds by 1.3 m/s in a 0.4 m/s rotation).
TEST(MomentumTransport, BoundedAcrossTheDensityJump) {
  Grid g(PETSC_COMM_WORLD, 40, 40, 1.0, 1.0);
  Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi"), vel(g.dm_vel(), "vel"),
      ustar(g.dm_vel(), "ustar");
  auto d = [](double x, double y) { return ls::circle_distance(x, y, 0.5, 0.7, 0.14); };
  vof::init_fraction(g, c, d);
  fill_cells(g, phi, d);
  ls::rotation_velocity(g, vel, 1.0, 0.5, 0.5);
  gf::Boundaries bc;
  gf::momentum::Predictor pred(g, bc, 1e-10);
  vof::Advector adv(g);
  const double dt = ls::max_cfl_dt(g, vel, 0.5);
  double ulo, uhi, vlo, vhi;
  bounds(g, vel, 0, ulo, uhi);
  bounds(g, vel, 1, vlo, vhi);
  double out_of_bounds = 0;
  for (int k = 0; k < 20; ++k) {  // the same rotation advects every step: u^n is transported
    adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
    vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
    const gf::momentum::MassSweeps m{adv.flux(), adv.c_start(), c, adv.cc(), kRhoAir, kRhoGran};
    pred.transport(vel, vel, m, dt, ustar);
    double lo, hi;
    bounds(g, ustar, 0, lo, hi);
    out_of_bounds = std::max({out_of_bounds, lo < ulo ? ulo - lo : 0.0, hi > uhi ? hi - uhi : 0.0});
    bounds(g, ustar, 1, lo, hi);
    out_of_bounds = std::max({out_of_bounds, lo < vlo ? vlo - lo : 0.0, hi > vhi ? hi - vhi : 0.0});
  }
  std::printf("rotation with a heavy disc, 20 transport steps: beyond the old bounds by %.1e m/s\n",
              out_of_bounds);
  EXPECT_LE(out_of_bounds, 1e-12);
}

// Inviscid steps (transport, then the projection of eq. 32 with rho^{n+1}) of a heavy disc
// (1300:1) in a solid-body rotation, whose exact kinetic energy is constant. The velocity
// transport of the level-set scheme (u^n - dt conv(u^n) under the moved density, explicit
// Euler) gains energy where the heavy phase enters faces whose velocity was the air's; the
// consistent transport gains at least ten times less (measured: worst step +2.9e-4 against
// +7.9e-3, mean +2.1e-4 against +1.9e-3, on 40 x 40 over 60 steps).
TEST(MomentumTransport, InviscidStepsGainFarLessEnergyThanVelocityTransport) {
  auto run = [](bool consistent, double& worst, double& mean) {
    Grid g(PETSC_COMM_WORLD, 40, 40, 1.0, 1.0);
    Field c(g.dm_cell(), "c"), phi(g.dm_cell(), "phi"), vel(g.dm_vel(), "vel"),
        ustar(g.dm_vel(), "ustar"), conv(g.dm_vel(), "conv"), p(g.dm_cell(), "p"),
        rho(g.dm_cell(), "rho"), eta(g.dm_cell(), "eta");
    auto d = [](double x, double y) { return ls::circle_distance(x, y, 0.5, 0.7, 0.14); };
    vof::init_fraction(g, c, d);
    fill_cells(g, phi, d);
    ls::rotation_velocity(g, vel, 1.0, 0.5, 0.5);
    gf::Boundaries bc;
    gf::momentum::Predictor pred(g, bc, 1e-10);
    gf::projection::Projector proj(g, 1e-12);
    vof::Advector adv(g);
    const double dt = ls::max_cfl_dt(g, vel, 0.5);
    auto project = [&](Vec u) {
      vof::update_properties(g, c, kRhoAir, kRhoGran, 1e-5, 1e-3, rho, eta, nullptr);
      proj.assemble(rho);
      proj.project(u, p, rho, 1.0, dt);
    };
    project(vel);
    worst = -1e300;
    mean = 0;
    const int steps = 60;
    for (int k = 0; k < steps; ++k) {
      const double e0 = face_energy(g, vel, c);
      adv.step(c, vel, phi, dt, k, vof::Normals::LevelSet);
      vof::rebuild_distance(g, c, phi, vof::Normals::LevelSet);
      if (consistent) {
        const gf::momentum::MassSweeps m{adv.flux(), adv.c_start(), c, adv.cc(), kRhoAir,
                                         kRhoGran};
        pred.transport(vel, vel, m, dt, ustar);
      } else {
        const gf::Box& b = g.box();
        gf::LocalVelocity lv(g, vel);
        gf::Vel **cv, **us;
        DMDAVecGetArray(g.dm_vel(), conv, &cv);
        gf::ops::convection(b, lv.array(), cv);
        DMDAVecGetArray(g.dm_vel(), ustar, &us);
        for (PetscInt j = b.ys; j < b.ye(); ++j)
          for (PetscInt i = b.xs; i < b.xe(); ++i)
            us[j][i] = {lv[j][i].u - dt * cv[j][i].u, lv[j][i].v - dt * cv[j][i].v};
        DMDAVecRestoreArray(g.dm_vel(), ustar, &us);
        DMDAVecRestoreArray(g.dm_vel(), conv, &cv);
      }
      project(ustar);
      VecCopy(ustar, vel);
      const double r = (face_energy(g, vel, c) - e0) / e0;
      worst = std::max(worst, r);
      mean += r / steps;
    }
  };
  double wc, mc, wv, mv;
  run(true, wc, mc);
  run(false, wv, mv);
  std::printf("inviscid steps, heavy disc in a rotation: relative energy change per step, "
              "consistent worst %+.2e mean %+.2e; velocity transport worst %+.2e mean %+.2e\n",
              wc, mc, wv, mv);
  EXPECT_GT(wv, 0.0);  // the velocity transport does gain: the comparison is not vacuous
  EXPECT_LT(wc, 0.1 * wv);
  EXPECT_LT(mc, 0.2 * mv);
}
