// Verification of the level-set module (section 3.1) on the two classical transport benchmarks:
//  * Zalesak's slotted disk in solid-body rotation, one full turn (unit square, disk radius 0.15
//    centred (0.5, 0.75), slot width 0.05 and depth 0.25, rotation about (0.5, 0.5), period
//    2 pi / omega);
//  * the single vortex of LeVeque / Rider & Kothe (circle radius 0.15 centred (0.5, 0.75),
//    psi = sin^2(pi x) sin^2(pi y) cos(pi t / T) / pi, T = 8, evaluated at t = T when the exact
//    solution is the initial circle again).
// WENO5 + TVD-RK3 transport at a fixed CFL, Min (2010) redistancing every few steps. Prints a
// Markdown table: area loss (granular_area with eps = 1.5 h) and the L1 interface error
// (area of the symmetric difference with the exact shape, m^2).
//
// Options (PETSc options database):
//   -n 64,128,256        grid sizes (cells per side)
//   -cfl 0.5             advective CFL, dt * max(|u|/hx + |v|/hy)
//   -redist_every 10     steps between redistancings (0 = never)
//   -redist_iters 3      pseudo-time iterations per redistancing (cfl 0.5)
//   -cases zalesak,vortex
#include <petscsys.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"

namespace ls = gf::levelset;

namespace {

struct Options {
  double cfl = 0.5;
  int redist_every = 10, redist_iters = 3;
};

struct Result {
  double loss_pct, l1;
  int steps;
  double wall_s;
};

Result zalesak(int n, const Options& o) {
  gf::Grid g(PETSC_COMM_WORLD, n, n, 1.0, 1.0);
  const double h = g.hx();
  gf::Field phi(g.dm_cell(), "phi"), exact(g.dm_cell(), "exact"), vel(g.dm_vel(), "vel");
  ls::init_zalesak(g, exact, 0.5, 0.75, 0.15, 0.05, 0.25);
  VecCopy(exact, phi);
  const double omega = 1.0, period = 2 * std::numbers::pi / omega;
  ls::rotation_velocity(g, vel, omega, 0.5, 0.5);
  const int steps = static_cast<int>(std::ceil(period / ls::max_cfl_dt(g, vel, o.cfl)));
  const double dt = period / steps;
  ls::Advector adv(g);
  ls::Redistancer rd(g, o.redist_iters, 0.5);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 1; k <= steps; ++k) {
    adv.step(phi, vel, dt);
    if (o.redist_every > 0 && k % o.redist_every == 0) rd.run(phi);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double a0 = ls::granular_area(g, exact, 1.5 * h), a1 = ls::granular_area(g, phi, 1.5 * h);
  return {100 * (a0 - a1) / a0, ls::interface_l1_error(g, phi, exact), steps, wall};
}

Result vortex(int n, const Options& o) {
  gf::Grid g(PETSC_COMM_WORLD, n, n, 1.0, 1.0);
  const double h = g.hx(), T = 8.0;
  gf::Field phi(g.dm_cell(), "phi"), exact(g.dm_cell(), "exact"), vel(g.dm_vel(), "vel");
  ls::init_circle(g, exact, 0.5, 0.75, 0.15);
  VecCopy(exact, phi);
  ls::single_vortex_velocity(g, vel, 0.0, T);  // the fastest instant sets the step
  const int steps = static_cast<int>(std::ceil(T / ls::max_cfl_dt(g, vel, o.cfl)));
  const double dt = T / steps;
  ls::Advector adv(g);
  ls::Redistancer rd(g, o.redist_iters, 0.5);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 1; k <= steps; ++k) {
    ls::single_vortex_velocity(g, vel, (k - 0.5) * dt, T);  // midpoint of the step
    adv.step(phi, vel, dt);
    if (o.redist_every > 0 && k % o.redist_every == 0) rd.run(phi);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double a0 = ls::granular_area(g, exact, 1.5 * h), a1 = ls::granular_area(g, phi, 1.5 * h);
  return {100 * (a0 - a1) / a0, ls::interface_l1_error(g, phi, exact), steps, wall};
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  {
    Options o;
    PetscInt ns[8] = {64, 128, 256};
    PetscInt nn = 8;
    PetscBool set = PETSC_FALSE;
    PetscCall(PetscOptionsGetIntArray(nullptr, nullptr, "-n", ns, &nn, &set));
    if (!set) nn = 3;
    PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-cfl", &o.cfl, nullptr));
    PetscInt every = o.redist_every, iters = o.redist_iters;
    PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-redist_every", &every, nullptr));
    PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-redist_iters", &iters, nullptr));
    o.redist_every = static_cast<int>(every);
    o.redist_iters = static_cast<int>(iters);
    char cases[256] = "zalesak,vortex";
    PetscCall(PetscOptionsGetString(nullptr, nullptr, "-cases", cases, sizeof cases, nullptr));
    const std::string cs(cases);

    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "CFL %.2f, redistancing every %d steps (%d iterations, cfl 0.5)\n\n"
                          "| case | n | area loss %% | L1 interface error (m^2) | steps | wall s |\n"
                          "|---|---|---|---|---|---|\n",
                          o.cfl, o.redist_every, o.redist_iters));
    for (const char* name : {"zalesak", "vortex"}) {
      if (cs.find(name) == std::string::npos) continue;
      for (PetscInt k = 0; k < nn; ++k) {
        const int n = static_cast<int>(ns[k]);
        const Result r = std::strcmp(name, "zalesak") == 0 ? zalesak(n, o) : vortex(n, o);
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "| %s | %d | %.3f | %.3e | %d | %.1f |\n",
                              std::strcmp(name, "zalesak") == 0 ? "Zalesak disk, 1 turn"
                                                                : "single vortex, T = 8",
                              n, r.loss_pct, r.l1, r.steps, r.wall_s));
      }
    }
  }
  PetscCall(PetscFinalize());
  return 0;
}
