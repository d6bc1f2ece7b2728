// A periodic x direction (boundary.periodic_x): exact solutions that cross the seam x = 0 = Lx,
// and the same results on 1 and 2 ranks split in x.
//  1. viscous shear wave u = cos(2 pi y/Ly) exp(-nu (2 pi/Ly)^2 t), v = 0, free-slip bottom/top
//     (du/dy = 0 there): the viscous rows of the u-faces at i = 0 and the wrapped columns;
//  2. a Taylor-Green cell shifted in x, psi = sin(a (x - x0)) sin(b y), a = 2 pi/Lx, b = pi/Ly:
//     u = b sin(a(x-x0)) cos(b y) F, v = -a cos(a(x-x0)) sin(b y) F, F = exp(-nu (a^2+b^2) t),
//     p = (b^2 cos(2a(x-x0)) + a^2 cos(2 b y)) F^2 / 4 (rho = 1), exact with free-slip
//     bottom/top; u != 0 on the seam, so treating it as a wall would fail. Second order;
//  3. a level-set disk carried once across the seam by u = 1 comes back to its start;
//  4. the "vortex" initial velocity (setup/Build.hpp), with walls and periodic: divergence free;
//  5. 1 vs 2 ranks: the same run on PETSC_COMM_WORLD and PETSC_COMM_SELF (64 x 16: PETSc splits
//     x on 2 ranks), for the level set (bit for bit) and for a two-phase Bingham step sequence
//     with Coulomb friction on the bottom (to solver tolerance).
#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "setup/Case.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "setup/Build.hpp"
#include "stepper/Stepper.hpp"
#include "../helpers.hpp"

using namespace gf;
using std::numbers::pi;

namespace {

using FieldFn = std::function<double(double, double, double)>;  // (x, y, t)

struct Exact {
  FieldFn u, v, p;
};

void set_exact(const Grid& g, const Exact& ex, double t, Vec vel, Vec p) {
  const Box& b = g.box();
  Vel** u;
  PetscScalar** pa;
  DMDAVecGetArray(g.dm_vel(), vel, &u);
  DMDAVecGetArray(g.dm_cell(), p, &pa);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      u[j][i].u = ex.u(b.xf(i), b.yc(j), t);  // periodic: face 0 is an interior face
      u[j][i].v = j > 0 ? ex.v(b.xc(i), b.yf(j), t) : 0.0;
      pa[j][i] = ex.p(b.xc(i), b.yc(j), t);
    }
  DMDAVecRestoreArray(g.dm_cell(), p, &pa);
  DMDAVecRestoreArray(g.dm_vel(), vel, &u);
}

PhysicsConfig one_phase(double nu) {
  PhysicsConfig cfg;
  cfg.levelset = false;
  cfg.rho_gran = 1.0;
  cfg.eta_gran = nu;
  cfg.gravity = {0.0, 0.0};
  cfg.pressure_rtol = 1e-12;
  cfg.viscous_rtol = 1e-12;
  for (WallBC* w : {&cfg.bc.left, &cfg.bc.right, &cfg.bc.bottom, &cfg.bc.top})
    *w = {WallType::FreeSlip, 0.0, 0.0};
  return cfg;
}

// Runs from the exact state at t = -dt and 0 (BDF2 from the first step) to T; returns the max
// velocity error and the max |exact velocity| at T.
std::array<double, 2> run_exact(int nx, int ny, double Lx, double Ly, double nu, const Exact& ex,
                                double T, double dt) {
  Grid g(PETSC_COMM_WORLD, nx, ny, Lx, Ly, true);
  Stepper stepper(g, one_phase(nu));
  State s(g);
  stepper.initialize(s);
  set_exact(g, ex, -dt, s.vel_old, s.p);
  set_exact(g, ex, 0.0, s.vel, s.p);
  s.step = 1;
  s.dt = dt;
  while (s.t < T - 1e-12) stepper.step(s, std::min(dt, T - s.t));
  Field e(g.dm_vel(), "exact"), pe(g.dm_cell(), "pexact");
  set_exact(g, ex, s.t, e, pe);
  PetscReal emax, err;
  VecNorm(e, NORM_INFINITY, &emax);
  VecAXPY(e, -1.0, s.vel);
  VecNorm(e, NORM_INFINITY, &err);
  return {err, emax};
}

}  // namespace

TEST(Periodic, ShearWaveDecays) {
  const double nu = 0.01, Lx = 1.0, Ly = 1.0, k = 2 * pi / Ly, T = 1.0;
  const Exact ex{[=](double, double y, double t) { return std::cos(k * y) * std::exp(-nu * k * k * t); },
                 [](double, double, double) { return 0.0; },
                 [](double, double, double) { return 0.0; }};
  double err[3];
  const int ns[3] = {16, 32, 64};
  for (int m = 0; m < 3; ++m) {
    const auto r = run_exact(ns[m], ns[m], Lx, Ly, nu, ex, T, 0.5 / ns[m]);
    err[m] = r[0] / r[1];
  }
  const double o1 = std::log2(err[0] / err[1]), o2 = std::log2(err[1] / err[2]);
  PetscPrintf(PETSC_COMM_WORLD, "shear wave relative error at T = %g: %.3e %.3e %.3e, orders %.2f %.2f\n",
              T, err[0], err[1], err[2], o1, o2);
  // The error is the spatial one, (k h)^2/12 of the decay rate: 1.3e-3 at n = 32.
  EXPECT_LT(err[2], 1e-3);
  EXPECT_GT(o1, 1.8);
  EXPECT_GT(o2, 1.8);
}

TEST(Periodic, ShiftedTaylorGreenSecondOrder) {
  const double nu = 0.01, Lx = 2.0, Ly = 1.0, x0 = 0.3, T = 0.5;
  const double a = 2 * pi / Lx, b = pi / Ly;
  auto F = [=](double t) { return std::exp(-nu * (a * a + b * b) * t); };
  const Exact ex{
      [=](double x, double y, double t) { return b * std::sin(a * (x - x0)) * std::cos(b * y) * F(t); },
      [=](double x, double y, double t) { return -a * std::cos(a * (x - x0)) * std::sin(b * y) * F(t); },
      [=](double x, double y, double t) {
        return 0.25 * (b * b * std::cos(2 * a * (x - x0)) + a * a * std::cos(2 * b * y)) * F(t) * F(t);
      }};
  double err[3];
  const int ns[3] = {16, 32, 64};
  for (int m = 0; m < 3; ++m) {
    const auto r = run_exact(2 * ns[m], ns[m], Lx, Ly, nu, ex, T, 0.25 / ns[m]);
    err[m] = r[0] / r[1];
  }
  const double o1 = std::log2(err[0] / err[1]), o2 = std::log2(err[1] / err[2]);
  PetscPrintf(PETSC_COMM_WORLD,
              "shifted Taylor-Green relative velocity error: %.3e %.3e %.3e, orders %.2f %.2f\n",
              err[0], err[1], err[2], o1, o2);
  EXPECT_GT(o1, 1.8);
  EXPECT_GT(o2, 1.8);
  EXPECT_LT(err[2], 1e-3);
}

TEST(Periodic, DiskCrossesTheSeamAndReturns) {
  // Disk of radius 0.15 centred at x = 0.75 in a 1 x 0.5 channel, u = 1: after t = Lx / u = 1
  // it has crossed x = Lx once and is back. WENO5 + RK3 with redistancing every 10 steps.
  const int n = 64;
  Grid g(PETSC_COMM_WORLD, n, n / 2, 1.0, 0.5, true);
  Field phi(g.dm_cell(), "phi"), phi0(g.dm_cell(), "phi0"), vel(g.dm_vel(), "vel");
  levelset::init_circle(g, phi, 0.75, 0.25, 0.15);
  VecCopy(phi, phi0);
  levelset::velocity_from_stream_function(g, vel, [](double, double y) { return y; });  // u = 1
  levelset::Advector adv(g);
  levelset::Redistancer rd(g, 3, 0.5);
  const double eps = 1.5 * g.hx();  // the smoothed area (eq. 25) sees sub-cell changes
  const double dt = levelset::max_cfl_dt(g, vel, 0.45);
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  const double dt1 = 1.0 / steps;
  double half_area_err = 0;
  for (int k = 1; k <= steps; ++k) {
    adv.step(phi, vel, dt1);
    if (k % 10 == 0) rd.run(phi);
    if (k == steps / 4) {  // centre at x = 1.0: the disk straddles the seam
      const double a = levelset::granular_area(g, phi, eps), a0 = levelset::granular_area(g, phi0, eps);
      half_area_err = std::abs(a - a0) / a0;
    }
  }
  const double a0 = levelset::granular_area(g, phi0, eps), a1 = levelset::granular_area(g, phi, eps);
  const double l1 = levelset::interface_l1_error(g, phi, phi0);
  const double perimeter = 2 * pi * 0.15;
  PetscPrintf(PETSC_COMM_WORLD,
              "disk across the seam: area change %.3e (on the seam %.3e), L1 %.3e m^2 = %.3e cells "
              "of mean displacement\n",
              (a1 - a0) / a0, half_area_err, l1, l1 / perimeter / g.hx());
  EXPECT_LT(std::abs(a1 - a0) / a0, 5e-3);
  EXPECT_LT(half_area_err, 5e-3);
  EXPECT_LT(l1 / perimeter, 0.05 * g.hx());
}

namespace {

// Max |a - b| / max |b| between a WORLD Vec (DMDA ordering) of dm and a SELF Vec of the same grid.
double rel_diff(DM dm, Vec world, Vec self) {
  return gf::test::world_vs_self(dm, world, self).rel();
}

// Level set across the seam: a disk on the seam in a shear flow u = sin(2 pi y/Ly) + 0.5,
// advection, redistancing, cell and node height fractions.
void levelset_run(const Grid& g, Vec phi, Vec rho, Vec eta, Vec eta_node) {
  const Box& b = g.box();
  levelset::init_circle(g, phi, 0.02, 0.12, 0.07);  // straddles x = 0
  Field vel(g.dm_vel(), "vel");
  levelset::velocity_from_stream_function(g, vel, [&](double, double y) {
    return 0.5 * y - b.Ly / (2 * pi) * std::cos(2 * pi * y / b.Ly);
  });
  levelset::Advector adv(g);
  levelset::Redistancer rd(g, 4, 0.5);
  const double dt = levelset::max_cfl_dt(g, vel, 0.5);
  for (int k = 1; k <= 40; ++k) {
    adv.step(phi, vel, dt);
    if (k % 8 == 0) rd.run(phi);
  }
  levelset::update_properties(g, phi, {1.2, 1550, 1.8e-5, 0.5, 1.5 * g.hx()}, rho, eta);
  Vec lphi;
  DMGetLocalVector(g.dm_cell(), &lphi);
  DMGlobalToLocalBegin(g.dm_cell(), phi, INSERT_VALUES, lphi);
  DMGlobalToLocalEnd(g.dm_cell(), phi, INSERT_VALUES, lphi);
  const PetscScalar** p;
  PetscScalar** en;
  DMDAVecGetArrayRead(g.dm_cell(), lphi, &p);
  DMDAVecGetArray(g.dm_cell(), eta_node, &en);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) en[j][i] = levelset::height_fraction_node(b, p, i, j);
  DMDAVecRestoreArray(g.dm_cell(), eta_node, &en);
  DMDAVecRestoreArrayRead(g.dm_cell(), lphi, &p);
  DMRestoreLocalVector(g.dm_cell(), &lphi);
}

// Two-phase Bingham flow in a periodic channel tilted by gravity: a granular layer with a bump
// (phi < 0 below y = 0.08 + 0.03 sin(2 pi x)) under air, Coulomb friction on the bottom.
void stepper_run(const Grid& g, State& s) {
  PhysicsConfig cfg;
  cfg.gravity = {4.0, -9.0};
  cfg.eps = 1.5 * g.hx();
  cfg.eta_gran = 0.05;
  cfg.rheo.yield = rheology::Yield::Bingham;
  cfg.rheo.tau_y = 5.0;
  cfg.rheo.fp_tol = 1e-6;
  cfg.rheo.fp_max_iter = 30;
  cfg.wall_tan_b = {0.0, 0.0, 0.4, 0.0};
  cfg.bc.left = cfg.bc.right = {WallType::FreeSlip, 0.0, 0.0};
  cfg.bc.bottom = {WallType::NoSlip, 0.0, 0.0};
  cfg.bc.top = {WallType::FreeSlip, 0.0, 0.0};
  cfg.pressure_rtol = 1e-12;
  cfg.viscous_rtol = 1e-12;
  const Box& b = g.box();
  {
    PetscScalar** p;
    DMDAVecGetArray(g.dm_cell(), s.phi, &p);
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i)
        p[j][i] = b.yc(j) - (0.08 + 0.03 * std::sin(2 * pi * b.xc(i) / b.Lx));
    DMDAVecRestoreArray(g.dm_cell(), s.phi, &p);
  }
  Stepper st(g, cfg);
  st.initialize(s);
  for (int k = 0; k < 6; ++k) st.step(s, 2e-3);
}

}  // namespace

TEST(Periodic, SameResultOnOneAndTwoRanks) {
  const PetscInt nx = 64, ny = 16;
  const double Lx = 0.8, Ly = 0.2;
  Grid gw(PETSC_COMM_WORLD, nx, ny, Lx, Ly, true), gs(PETSC_COMM_SELF, nx, ny, Lx, Ly, true);
  PetscInt px, py;
  DMDAGetInfo(gw.dm_cell(), nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr, nullptr,
              nullptr, nullptr, nullptr, nullptr, nullptr);
  EXPECT_EQ(py, 1);  // the split, if any, is in x: ranks meet across the seam
  {
    Field pw(gw.dm_cell(), "phi"), rw(gw.dm_cell(), "rho"), ew(gw.dm_cell(), "eta"),
        nw(gw.dm_cell(), "theta_node");
    Field ps(gs.dm_cell(), "phi"), rs(gs.dm_cell(), "rho"), es(gs.dm_cell(), "eta"),
        ns(gs.dm_cell(), "theta_node");
    levelset_run(gw, pw, rw, ew, nw);
    levelset_run(gs, ps, rs, es, ns);
    const double dphi = rel_diff(gw.dm_cell(), pw, ps), drho = rel_diff(gw.dm_cell(), rw, rs),
                 deta = rel_diff(gw.dm_cell(), ew, es), dnode = rel_diff(gw.dm_cell(), nw, ns);
    PetscPrintf(PETSC_COMM_WORLD,
                "level set, %dx%d ranks vs 1: rel. diff phi %.2e rho %.2e eta %.2e theta_node %.2e\n",
                (int)px, (int)py, dphi, drho, deta, dnode);
    EXPECT_EQ(dphi, 0.0);
    EXPECT_EQ(drho, 0.0);
    EXPECT_EQ(deta, 0.0);
    EXPECT_EQ(dnode, 0.0);
  }
  {
    State sw(gw), ss(gs);
    stepper_run(gw, sw);
    stepper_run(gs, ss);
    const double du = rel_diff(gw.dm_vel(), sw.vel, ss.vel), dp = rel_diff(gw.dm_cell(), sw.p, ss.p),
                 dphi = rel_diff(gw.dm_cell(), sw.phi, ss.phi),
                 dS = rel_diff(gw.dm_ten(), sw.S, ss.S);
    PetscReal umax;
    VecNorm(ss.vel, NORM_INFINITY, &umax);
    PetscPrintf(PETSC_COMM_WORLD,
                "Bingham periodic channel, %dx%d ranks vs 1: rel. diff u %.2e p %.2e phi %.2e "
                "S %.2e (max |u| %.3e)\n",
                (int)px, (int)py, du, dp, dphi, dS, (double)umax);
    EXPECT_GT(umax, 1e-3);  // it flows: the comparison is not vacuous
    EXPECT_LT(du, 1e-8);
    EXPECT_LT(dp, 1e-8);
    EXPECT_LT(dphi, 1e-8);
    EXPECT_LT(dS, 1e-6);
  }
}

TEST(Periodic, InitialVortexIsDivergenceFree) {
  for (const bool periodic : {false, true}) {
    const std::string text = std::string("[domain]\nLx = 1.5\nLy = 1.0\n[grid]\nn = 24\n") +
                             "[levelset]\nenabled = false\n[initial]\nshape = \"none\"\n" +
                             "velocity = \"vortex\"\nvelocity_amplitude = 2.0\n[boundary]\n" +
                             "periodic_x = " + (periodic ? "true" : "false") + "\n";
    const CaseConfig c = load_case_string(text, "vortex.toml", {});
    Grid g(PETSC_COMM_WORLD, c.nx, c.ny, c.domain.Lx, c.domain.Ly, c.periodic_x);
    State s(g);
    initial_velocity(g, c, s.vel, s.vel_old);
    const double div = diag::max_divergence(g, s.vel), umax = diag::max_speed(g, s.vel);
    PetscBool same;
    VecEqual(s.vel, s.vel_old, &same);
    // Largest |u| on the faces x = 0 (the wall: 0) and |v| in the first column (periodic: the
    // shear across the seam, v = -2 A (Ly/Lx) cos(2 pi x/Lx) sin^2(pi y/Ly)).
    const Box& b = g.box();
    double u0 = 0, v0 = 0;
    {
      const Vel** v;
      DMDAVecGetArrayRead(g.dm_vel(), s.vel, &v);
      if (b.xs == 0)
        for (PetscInt j = b.ys; j < b.ye(); ++j) {
          u0 = std::max(u0, std::abs(v[j][0].u));
          v0 = std::max(v0, std::abs(v[j][0].v));
        }
      DMDAVecRestoreArrayRead(g.dm_vel(), s.vel, &v);
    }
    u0 = g.max(u0);
    v0 = g.max(v0);
    PetscPrintf(PETSC_COMM_WORLD,
                "vortex (%s): max div %.2e 1/s, max speed %.4f m/s, on x = 0: max |u| %.3f, "
                "|v| %.3f\n",
                periodic ? "periodic x" : "walls", div, umax, u0, v0);
    EXPECT_LT(div, 1e-12);
    EXPECT_TRUE(same);
    EXPECT_GT(umax, 1.5);
    EXPECT_LT(umax, 3.1);
    if (!periodic) EXPECT_EQ(u0, 0.0);
    if (periodic) EXPECT_GT(v0, 2.5);
    else EXPECT_LT(v0, 0.5);
  }
}
