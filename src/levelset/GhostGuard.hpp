#pragma once
// Internal to levelset/: a guard for the "no ghost points outside the domain" rule.
// DMGlobalToLocal never writes the ghost entries that lie outside the physical domain
// (DM_BOUNDARY_GHOSTED), so filling them with NaN once, when a work vector is created, makes any
// stencil that wrongly reads beyond a wall produce NaN, which the tests detect. With periodic x
// the x ghosts are wrapped copies (Grid.hpp), not outside the domain.
//
// Line: one grid line of n cells, seen by the one-dimensional stencils (WENO, ENO, Godunov),
// periodic or bounded by walls: has(k) says whether cell k may be read (for |k - owned| within
// the ghost width). The y lines are never periodic; the x lines are with Box::periodic_x.
#include <petscdmda.h>

#include <limits>

#include "core/Error.hpp"
#include "grid/Grid.hpp"

namespace gf::levelset::detail {

struct Line {
  PetscInt n;
  bool periodic;
  bool has(PetscInt k) const { return periodic || (k >= 0 && k < n); }
};
inline Line x_line(const Box& b) { return {b.nx, b.periodic_x}; }
inline Line y_line(const Box& b) { return {b.ny, false}; }

inline void poison_outside_ghosts(DM dm, Vec local, const Box& b) {
  PetscInt gxs, gys, gxm, gym, dof;
  GF_PETSC(DMDAGetGhostCorners(dm, &gxs, &gys, nullptr, &gxm, &gym, nullptr));
  GF_PETSC(DMDAGetInfo(dm, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, &dof,
                       nullptr, nullptr, nullptr, nullptr, nullptr));
  PetscScalar* a;
  GF_PETSC(VecGetArray(local, &a));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (PetscInt j = gys; j < gys + gym; ++j)
    for (PetscInt i = gxs; i < gxs + gxm; ++i) {
      const bool inside = b.has_cell_x(i) && j >= 0 && j < b.ny;
      const PetscInt k = ((j - gys) * gxm + (i - gxs)) * dof;
      for (PetscInt c = 0; c < dof; ++c) a[k + c] = inside ? 0.0 : nan;
    }
  GF_PETSC(VecRestoreArray(local, &a));
}

}  // namespace gf::levelset::detail
