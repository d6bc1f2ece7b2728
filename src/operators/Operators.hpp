#pragma once
// Discrete operators on the MAC grid (pure functions of local ghosted arrays).
// Index conventions: see grid/Grid.hpp. All loops run over the owned range of Box.
#include "grid/Grid.hpp"

namespace gf::ops {

// Density on the x-face (i, j) (left face of cell i) and y-face (i, j) (bottom face of cell j):
// arithmetic mean of the two adjacent cells, the same in the prediction (eq. 31) and the
// projection (eq. 32) so that the discrete balance of a fluid at rest is exact.
inline double rho_xface(const PetscScalar* const* rho, PetscInt i, PetscInt j) {
  return 0.5 * (rho[j][i - 1] + rho[j][i]);
}
inline double rho_yface(const PetscScalar* const* rho, PetscInt i, PetscInt j) {
  return 0.5 * (rho[j - 1][i] + rho[j][i]);
}

// Conservative convection div(u (x) u) at the faces: fluxes a q at the flux points, with the
// advecting velocity a the mean of the two neighbouring faces and the transported component q
// reconstructed from the upwind side by MUSCL with van Leer's limiter (second order in smooth
// regions, no new extrema). Plain central differences (energy conserving) let the air blow up
// next to a 1000:1 density jump at the wall impact of a dam break; upwinding damps that. vel: local array with ghosts filled (fill_velocity_ghosts); out: owned
// faces of a global dm_vel array. Wall faces get 0.
void convection(const Box& b, const Vel* const* vel, Vel** out);

// Divergence (u_{i+1} - u_i)/hx + (v_{j+1} - v_j)/hy at the owned cells, 1/s.
void divergence(const Box& b, const Vel* const* vel, PetscScalar** div);

}  // namespace gf::ops
