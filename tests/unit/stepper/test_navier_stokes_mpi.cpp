// The Navier-Stokes core (prediction eq. 31 with kappa = 0, projection eq. 32) against exact
// solutions: second-order convergence on the Taylor-Green vortex, and a heavy layer at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fields/Fields.hpp"
#include "stepper/Stepper.hpp"

using namespace gf;
using std::numbers::pi;

namespace {

// Taylor-Green vortex in the unit square: u = sin(pi x) cos(pi y) F, v = -cos(pi x) sin(pi y) F,
// F = exp(-2 pi^2 nu t). It satisfies u.n = 0 and free slip (eq. 21) on all four walls, so it is
// an exact solution of the incompressible Navier-Stokes equations in our closed box.
struct TaylorGreen {
  double nu;
  double F(double t) const { return std::exp(-2 * pi * pi * nu * t); }
  double u(double x, double y, double t) const { return std::sin(pi * x) * std::cos(pi * y) * F(t); }
  double v(double x, double y, double t) const { return -std::cos(pi * x) * std::sin(pi * y) * F(t); }
  double p(double x, double y, double t) const {
    return 0.25 * (std::cos(2 * pi * x) + std::cos(2 * pi * y)) * F(t) * F(t);
  }
};

void set_exact(const Grid& g, const TaylorGreen& tg, double t, Vec vel, Vec p) {
  const Box& b = g.box();
  Vel** u;
  PetscScalar** pa;
  DMDAVecGetArray(g.dm_vel(), vel, &u);
  DMDAVecGetArray(g.dm_cell(), p, &pa);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      u[j][i].u = i > 0 ? tg.u(b.xf(i), b.yc(j), t) : 0.0;
      u[j][i].v = j > 0 ? tg.v(b.xc(i), b.yf(j), t) : 0.0;
      pa[j][i] = tg.p(b.xc(i), b.yc(j), t);
    }
  DMDAVecRestoreArray(g.dm_cell(), p, &pa);
  DMDAVecRestoreArray(g.dm_vel(), vel, &u);
}

double tg_error(int n) {
  const TaylorGreen tg{0.01};
  Grid g(PETSC_COMM_WORLD, n, n, 1.0, 1.0);
  PhysicsConfig cfg;
  cfg.levelset = false;
  cfg.rho_gran = 1.0;
  cfg.eta_gran = tg.nu;
  cfg.gravity = {0.0, 0.0};
  cfg.pressure_rtol = 1e-12;
  cfg.viscous_rtol = 1e-12;
  for (WallBC* w : {&cfg.bc.left, &cfg.bc.right, &cfg.bc.bottom, &cfg.bc.top})
    *w = {WallType::FreeSlip, 0.0, 0.0};
  Stepper stepper(g, cfg);
  State s(g);
  stepper.initialize(s);
  // Start from the exact state at t = -dt and t = 0 so that BDF2 runs from the first step.
  const double T = 0.5, dt = 0.25 / n;
  set_exact(g, tg, -dt, s.vel_old, s.p);
  set_exact(g, tg, 0.0, s.vel, s.p);
  s.step = 1;
  s.dt = dt;
  while (s.t < T - 1e-12) stepper.step(s, dt);
  Field ex(g.dm_vel(), "exact"), pex(g.dm_cell(), "pexact");
  set_exact(g, tg, s.t, ex, pex);
  VecAXPY(ex, -1.0, s.vel);
  PetscReal e;
  VecNorm(ex, NORM_INFINITY, &e);
  return e;
}

}  // namespace

TEST(NavierStokes, TaylorGreenSecondOrder) {
  const double e16 = tg_error(16), e32 = tg_error(32), e64 = tg_error(64);
  const double o1 = std::log2(e16 / e32), o2 = std::log2(e32 / e64);
  PetscPrintf(PETSC_COMM_WORLD, "Taylor-Green max velocity error: %.3e %.3e %.3e, orders %.2f %.2f\n",
              e16, e32, e64, o1, o2);
  EXPECT_GT(o1, 1.8);
  EXPECT_GT(o2, 1.8);
  EXPECT_LT(e64, 2e-3);
}
