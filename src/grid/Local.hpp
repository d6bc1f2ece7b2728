#pragma once
// Ghosted read access to a global field: the one helper every layer uses to read values beyond
// its owned range (the face u_{i+1} of the last owned column, a stencil's neighbours).
//
// LocalArray<T> opens a local (ghosted) copy of a global Vec from the DM's pool
// (DMGetLocalVector: no allocation after the first use, so it can be used in every fixed-point
// iteration), scatters the owned values of the neighbours into it (to_local, the ghost exchange
// of grid/Grid.hpp) and exposes the array with global [j][i] indices over the owned range widened
// by the DM's stencil width:
//   T = PetscScalar  a scalar field (dm_cell):           a[j][i]
//   T = Vel          the velocity (dm_vel):              a[j][i].u, a[j][i].v
//   T = PetscScalar* a field with dof > 1 (dm_ten, dm_node): a[j][i][c]
// Ghosts outside the domain (DM_BOUNDARY_GHOSTED) are NOT filled: callers either stay inside the
// domain or, for the velocity, use LocalVelocity below. Objects that keep a local Vec of their
// own between calls (solver work vectors) call to_local directly.
#include <petscdmda.h>

#include <type_traits>

#include "core/Error.hpp"
#include "grid/Grid.hpp"

namespace gf {

static_assert(std::is_same_v<PetscScalar, double>, "granflow assumes real double PETSc");

template <class T>
class LocalArray {
 public:
  LocalArray(DM dm, Vec global) : dm_(dm) {
    GF_PETSC(DMGetLocalVector(dm_, &local_));
    try {
      to_local(dm_, global, local_);
      if constexpr (std::is_pointer_v<T>)
        GF_PETSC(DMDAVecGetArrayDOF(dm_, local_, &a_));
      else
        GF_PETSC(DMDAVecGetArray(dm_, local_, &a_));
    } catch (...) {
      DMRestoreLocalVector(dm_, &local_);
      throw;
    }
  }
  ~LocalArray() {
    // No throwing from a destructor: a failure to restore cannot be acted on here.
    if constexpr (std::is_pointer_v<T>)
      DMDAVecRestoreArrayDOF(dm_, local_, &a_);
    else
      DMDAVecRestoreArray(dm_, local_, &a_);
    DMRestoreLocalVector(dm_, &local_);
  }
  LocalArray(const LocalArray&) = delete;
  LocalArray& operator=(const LocalArray&) = delete;

  const T* operator[](PetscInt j) const { return a_[j]; }
  T** data() { return a_; }
  // The array as the read-only argument of a kernel (const T* const*).
  const T* const* array() const { return a_; }

 private:
  DM dm_;
  Vec local_ = nullptr;
  T** a_ = nullptr;
};

using LocalCells = LocalArray<PetscScalar>;
using LocalDof = LocalArray<PetscScalar*>;

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

}  // namespace gf
