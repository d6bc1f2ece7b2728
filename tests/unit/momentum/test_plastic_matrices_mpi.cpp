// The plastic operators of eq. 31 as matrices (momentum/PlasticMatrices.hpp), on 1 and 2 ranks:
// B u + d0 is Predictor::strain_rate(u) and C T is Predictor::add_plastic with kappa S = T, for
// non-trivial fields, on walls of every kind (no slip at rest and moving, Navier, free slip) and
// periodic in x with nx not a multiple of 3 (the colouring's seam); C = -B^T W (W = diag(1, 2, 1))
// exactly where the walls are free-slip or periodic, and by how much it is not on no-slip and
// Navier walls.
#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "boundary/Boundary.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "momentum/Momentum.hpp"
#include "momentum/PlasticMatrices.hpp"

using gf::Field;
using gf::Grid;

namespace {

// Irregular, rank-independent test values at the global point (i, j), component c.
double wobble(PetscInt i, PetscInt j, int c) {
  return std::sin(1.3 * i + 0.7 * j + 2.1 * c) + 0.5 * std::cos(0.37 * i * j + 1.1 * c + 0.2 * j);
}

void fill_vel(const Grid& g, Vec vel) {
  const gf::Box& b = g.box();
  gf::Vel** v;
  DMDAVecGetArray(g.dm_vel(), vel, &v);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      v[j][i].u = b.wall_u(i) ? 0.0 : wobble(i, j, 0);
      v[j][i].v = j == 0 ? 0.0 : wobble(i, j, 1);
    }
  DMDAVecRestoreArray(g.dm_vel(), vel, &v);
}

void fill_ten(const Grid& g, Vec t, int shift) {
  const gf::Box& b = g.box();
  PetscScalar*** s;
  DMDAVecGetArrayDOF(g.dm_ten(), t, &s);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      for (int c = 0; c < 3; ++c) s[j][i][c] = wobble(i + shift, j, c + 3);
  DMDAVecRestoreArrayDOF(g.dm_ten(), t, &s);
}

void fill_scalar(const Grid& g, Vec f, double lo, double hi) {
  const gf::Box& b = g.box();
  PetscScalar** a;
  DMDAVecGetArray(g.dm_cell(), f, &a);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = lo + (hi - lo) * (0.5 + 0.5 * wobble(i, j, 7));
  DMDAVecRestoreArray(g.dm_cell(), f, &a);
}

// max |a - b| / max |b|.
double rel_diff(Vec a, Vec b) {
  Vec d;
  VecDuplicate(a, &d);
  VecWAXPY(d, -1.0, b, a);
  double nd, nb;
  VecNorm(d, NORM_INFINITY, &nd);
  VecNorm(b, NORM_INFINITY, &nb);
  VecDestroy(&d);
  return nb > 0 ? nd / nb : nd;
}

struct WallSetup {
  const char* name;
  bool periodic;
  gf::Boundaries bc;
};

std::vector<WallSetup> setups() {
  gf::Boundaries walls;
  walls.bottom.type = gf::WallType::NoSlip;
  walls.top.type = gf::WallType::NoSlip;
  walls.top.velocity = 0.3;  // a moving lid: d0 != 0
  walls.right.type = gf::WallType::Navier;
  walls.right.eta_b = 50.0;
  walls.left.type = gf::WallType::FreeSlip;
  gf::Boundaries periodic;
  periodic.bottom.type = gf::WallType::NoSlip;
  periodic.top.type = gf::WallType::Navier;
  periodic.top.eta_b = 3.0;
  return {{"walls", false, walls}, {"periodic", true, periodic}};
}

}  // namespace

// The matrices give back the two kernels on a 17 x 11 grid, walls of every kind and periodic.
TEST(PlasticMatrices, ReproduceTheKernels) {
  for (const WallSetup& s : setups()) {
    Grid g(PETSC_COMM_WORLD, 17, 11, 0.34, 0.2, s.periodic);
    gf::momentum::Predictor pred(g, s.bc, 1e-10);
    Field eta(g.dm_cell(), "eta"), kappa(g.dm_cell(), "kappa"), vel(g.dm_vel(), "vel"),
        S(g.dm_ten(), "S"), T(g.dm_ten(), "T"), D(g.dm_ten(), "D"), BD(g.dm_ten(), "BD"),
        kb(g.dm_vel(), "kb"), sw(g.dm_vel(), "sw"), f(g.dm_vel(), "f"), Cf(g.dm_vel(), "Cf");
    fill_scalar(g, eta, 0.01, 2.0);
    gf::momentum::PlasticMatrices m;
    gf::momentum::assemble_plastic_matrices(g, pred, eta, m);
    fill_vel(g, vel);
    pred.strain_rate(vel, eta, D);
    MatMultAdd(m.B, vel, m.d0, BD);
    const double eB = rel_diff(BD, D);
    double nd0;
    VecNorm(m.d0, NORM_INFINITY, &nd0);
    // add_plastic with a varying kappa against C (kappa S).
    fill_scalar(g, kappa, 100.0, 3000.0);
    fill_ten(g, S, 5);
    VecSet(kb, 0.0);
    VecSet(sw, 0.0);
    VecSet(f, 0.0);
    pred.add_plastic(kappa, S, kb, sw, f);
    {
      const gf::Box& b = g.box();
      const PetscScalar** k;
      PetscScalar ***sa, ***ta;
      DMDAVecGetArrayRead(g.dm_cell(), kappa, &k);
      DMDAVecGetArrayDOF(g.dm_ten(), S, &sa);
      DMDAVecGetArrayDOF(g.dm_ten(), T, &ta);
      for (PetscInt j = b.ys; j < b.ye(); ++j)
        for (PetscInt i = b.xs; i < b.xe(); ++i)
          for (int c = 0; c < 3; ++c) ta[j][i][c] = k[j][i] * sa[j][i][c];
      DMDAVecRestoreArrayDOF(g.dm_ten(), T, &ta);
      DMDAVecRestoreArrayDOF(g.dm_ten(), S, &sa);
      DMDAVecRestoreArrayRead(g.dm_cell(), kappa, &k);
    }
    MatMult(m.C, T, Cf);
    const double eC = rel_diff(Cf, f);
    PetscInt nzB, nzC;
    MatInfo info;
    MatGetInfo(m.B, MAT_GLOBAL_SUM, &info);
    nzB = static_cast<PetscInt>(info.nz_used);
    MatGetInfo(m.C, MAT_GLOBAL_SUM, &info);
    nzC = static_cast<PetscInt>(info.nz_used);
    PetscPrintf(PETSC_COMM_WORLD,
                "%s: |B u + d0 - D(u)| / |D| = %.1e (|d0| = %.3g 1/s, %d nonzeros), "
                "|C T - div T| / |div T| = %.1e (%d nonzeros)\n",
                s.name, eB, nd0, static_cast<int>(nzB), eC, static_cast<int>(nzC));
    EXPECT_LT(eB, 1e-13) << s.name;
    EXPECT_LT(eC, 1e-13) << s.name;
    // The moving lid puts its wall velocity into d0: 0.3 m/s over half a cell.
    if (!s.periodic) EXPECT_NEAR(nd0, 0.125 * 2 * 0.3 / (0.5 * 0.2 / 11), 1e-9);
    else EXPECT_EQ(nd0, 0.0);
  }
}

// The plastic force is minus the adjoint of the strain rate, u . C T = -T : W B u summed, on
// free-slip and periodic walls to round-off; the no-slip and Navier walls break it, by the
// amounts printed.
TEST(PlasticMatrices, ForceIsMinusTheAdjointOfTheStrainRate) {
  struct Case {
    const char* name;
    bool periodic;
    gf::WallType bottom, top;
    bool exact;
  };
  const Case cases[] = {{"free slip all round", false, gf::WallType::FreeSlip, gf::WallType::FreeSlip, true},
                        {"periodic, free slip", true, gf::WallType::FreeSlip, gf::WallType::FreeSlip, true},
                        {"no-slip bottom", true, gf::WallType::NoSlip, gf::WallType::FreeSlip, false},
                        {"Navier bottom", true, gf::WallType::Navier, gf::WallType::FreeSlip, false}};
  for (const Case& c : cases) {
    Grid g(PETSC_COMM_WORLD, 16, 10, 0.32, 0.2, c.periodic);
    gf::Boundaries bc;
    bc.bottom.type = c.bottom;
    bc.bottom.eta_b = 20.0;
    bc.top.type = c.top;
    gf::momentum::Predictor pred(g, bc, 1e-10);
    Field eta(g.dm_cell(), "eta"), vel(g.dm_vel(), "vel"), T(g.dm_ten(), "T"),
        WBu(g.dm_ten(), "WBu"), CT(g.dm_vel(), "CT");
    fill_scalar(g, eta, 0.5, 1.0);
    gf::momentum::PlasticMatrices m;
    gf::momentum::assemble_plastic_matrices(g, pred, eta, m);
    fill_vel(g, vel);
    fill_ten(g, T, 2);
    MatMult(m.B, vel, WBu);
    {  // W: the off-diagonal component counts twice in S : D
      const gf::Box& b = g.box();
      PetscScalar*** w;
      DMDAVecGetArrayDOF(g.dm_ten(), WBu, &w);
      for (PetscInt j = b.ys; j < b.ye(); ++j)
        for (PetscInt i = b.xs; i < b.xe(); ++i) w[j][i][1] *= 2;
      DMDAVecRestoreArrayDOF(g.dm_ten(), WBu, &w);
    }
    MatMult(m.C, T, CT);
    double force_power, stress_power, scale_a, scale_b;
    VecDot(vel, CT, &force_power);
    VecDot(T, WBu, &stress_power);
    VecNorm(CT, NORM_2, &scale_a);
    VecNorm(vel, NORM_2, &scale_b);
    const double defect = std::abs(force_power + stress_power) / (scale_a * scale_b);
    // The matrices themselves: |C + B^T W| relative to |C| (Frobenius).
    Mat Bt, sum;
    MatTranspose(m.B, MAT_INITIAL_MATRIX, &Bt);
    Vec wdiag;  // W on the columns of B^T (the dm_ten layout)
    MatCreateVecs(Bt, &wdiag, nullptr);
    {
      const gf::Box& b = g.box();
      PetscScalar*** w;
      VecSet(wdiag, 1.0);
      DMDAVecGetArrayDOF(g.dm_ten(), wdiag, &w);
      for (PetscInt j = b.ys; j < b.ye(); ++j)
        for (PetscInt i = b.xs; i < b.xe(); ++i) w[j][i][1] = 2;
      DMDAVecRestoreArrayDOF(g.dm_ten(), wdiag, &w);
    }
    MatDiagonalScale(Bt, nullptr, wdiag);
    MatDuplicate(m.C, MAT_COPY_VALUES, &sum);
    MatAXPY(sum, 1.0, Bt, DIFFERENT_NONZERO_PATTERN);
    double nsum, nC;
    MatNorm(sum, NORM_FROBENIUS, &nsum);
    MatNorm(m.C, NORM_FROBENIUS, &nC);
    PetscPrintf(PETSC_COMM_WORLD,
                "%s: |u.CT + T:WBu| / (|CT| |u|) = %.1e, |C + B^T W| / |C| = %.1e\n", c.name,
                defect, nsum / nC);
    if (c.exact) {
      EXPECT_LT(defect, 1e-13) << c.name;
      EXPECT_LT(nsum / nC, 1e-13) << c.name;
    } else {
      EXPECT_GT(nsum / nC, 1e-3) << c.name << ": the wall terms became adjoint; say so in the header";
    }
    VecDestroy(&wdiag);
    MatDestroy(&sum);
    MatDestroy(&Bt);
  }
}
