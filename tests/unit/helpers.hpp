// Helpers of the unit tests: a cell field filled from a function of the cell centre, and a Vec
// of a grid distributed over PETSC_COMM_WORLD compared with the same field computed on a
// PETSC_COMM_SELF grid (the 1-rank reference of the *_mpi tests).
#pragma once

#include <gtest/gtest.h>
#include <petscdmda.h>

#include <algorithm>
#include <cmath>

#include "grid/Grid.hpp"

namespace gf::test {

// v (global, dm_cell) = f(x, y) at the owned cell centres.
template <class F>
void fill_cells(const Grid& g, Vec v, const F& f) {
  const Box& b = g.box();
  PetscScalar** a;
  DMDAVecGetArray(g.dm_cell(), v, &a);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = f(b.xc(i), b.yc(j));
  DMDAVecRestoreArray(g.dm_cell(), v, &a);
}

struct WorldVsSelf {
  double max_abs = 0;  // max |world - self| (infinite if either is not finite)
  double max_ref = 0;  // max |self|
  double rel() const { return max_ref > 0 ? max_abs / max_ref : max_abs; }
};

// world: global Vec of dm (DMDA ordering, any ranks); self: the same grid's Vec on one rank.
inline WorldVsSelf world_vs_self(DM dm, Vec world, Vec self) {
  Vec nat, all;
  VecScatter sc;
  DMDACreateNaturalVector(dm, &nat);
  DMDAGlobalToNaturalBegin(dm, world, INSERT_VALUES, nat);
  DMDAGlobalToNaturalEnd(dm, world, INSERT_VALUES, nat);
  VecScatterCreateToAll(nat, &sc, &all);
  VecScatterBegin(sc, nat, all, INSERT_VALUES, SCATTER_FORWARD);
  VecScatterEnd(sc, nat, all, INSERT_VALUES, SCATTER_FORWARD);
  const PetscScalar *a, *s;
  PetscInt n, m;
  VecGetLocalSize(all, &n);
  VecGetLocalSize(self, &m);
  EXPECT_EQ(n, m);
  VecGetArrayRead(all, &a);
  VecGetArrayRead(self, &s);
  WorldVsSelf r;
  for (PetscInt k = 0; k < std::min(n, m); ++k) {
    r.max_abs = std::max(r.max_abs, std::abs(a[k] - s[k]));
    r.max_ref = std::max(r.max_ref, std::abs(s[k]));
    if (!std::isfinite(a[k]) || !std::isfinite(s[k])) r.max_abs = INFINITY;
  }
  VecRestoreArrayRead(self, &s);
  VecRestoreArrayRead(all, &a);
  VecScatterDestroy(&sc);
  VecDestroy(&all);
  VecDestroy(&nat);
  return r;
}

}  // namespace gf::test
