#pragma once
// Ghosted read access to a global field, shared by the diagnostics and the output writers.
//
// Every measure here needs values one cell beyond the owned range (the face u_{i+1} of the
// last owned column, the right-hand neighbour of a probe stencil), so each opens a local
// (ghosted) copy, scatters the owned values of the neighbours into it and reads the array
// with global [j][i] indices. The local vector comes from the DM's pool (DMGetLocalVector),
// so repeated calls do not allocate.
#include <petscdmda.h>

#include <type_traits>

#include "core/Error.hpp"
#include "grid/Grid.hpp"

namespace gf::diag {

static_assert(std::is_same_v<PetscScalar, double>, "granflow assumes real double PETSc");

// A local copy of `global` (a Vec of `dm`) with its array open, indexed a[j][i] with global
// indices over the owned range widened by the DM's stencil width. Ghosts outside the domain
// (DM_BOUNDARY_GHOSTED) are NOT filled: callers either stay inside the domain or, for the
// velocity, use LocalVelocity below.
template <class T>
class LocalArray {
 public:
  LocalArray(DM dm, Vec global) : dm_(dm) {
    GF_PETSC(DMGetLocalVector(dm_, &local_));
    try {
      GF_PETSC(DMGlobalToLocalBegin(dm_, global, INSERT_VALUES, local_));
      GF_PETSC(DMGlobalToLocalEnd(dm_, global, INSERT_VALUES, local_));
      GF_PETSC(DMDAVecGetArray(dm_, local_, &a_));
    } catch (...) {
      DMRestoreLocalVector(dm_, &local_);
      throw;
    }
  }
  ~LocalArray() {
    // No throwing from a destructor: a failure to restore cannot be acted on here.
    DMDAVecRestoreArray(dm_, local_, &a_);
    DMRestoreLocalVector(dm_, &local_);
  }
  LocalArray(const LocalArray&) = delete;
  LocalArray& operator=(const LocalArray&) = delete;

  const T* operator[](PetscInt j) const { return a_[j]; }
  T** data() { return a_; }

 private:
  DM dm_;
  Vec local_ = nullptr;
  T** a_ = nullptr;
};

using LocalCells = LocalArray<PetscScalar>;

// The ghosted velocity with the wall faces set by fill_velocity_ghosts(): u on faces i = 0 and
// i = nx, v on faces j = 0 and j = ny are zero (eq. 20), so a cell's right/top face can be
// read as v[j][i+1].u / v[j+1][i].v for every owned cell, including i = nx-1 and j = ny-1
// (with periodic x, u on face nx is the wrapped face 0).
class LocalVelocity : public LocalArray<Vel> {
 public:
  LocalVelocity(const Grid& g, Vec vel) : LocalArray<Vel>(g.dm_vel(), vel) {
    fill_velocity_ghosts(g, data());
  }
};

// Cell-centred velocity of cell (i, j): the mean of its two x-faces and of its two y-faces.
// This is the velocity that max_speed, the VTK "u" vector and "speed" all report.
inline void cell_centre_velocity(const LocalVelocity& v, PetscInt i, PetscInt j, double& uc,
                                 double& vc) {
  uc = 0.5 * (v[j][i].u + v[j][i + 1].u);
  vc = 0.5 * (v[j][i].v + v[j + 1][i].v);
}

}  // namespace gf::diag
