#pragma once
// Discrete operators on the MAC grid (pure functions of local ghosted arrays).
// Index conventions: see grid/Grid.hpp. All loops run over the owned range of Box.
#include <petscvec.h>

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

// The momentum transport of one step that is consistent with the mass transport of a
// direction-split volume-of-fluid step (vof/Vof.hpp, Weymouth & Yue 2010), for the MAC grid:
// the momentum of each face's control volume (half of each of its two cells) moves with the
// mass fluxes that move the density there (Rudman 1998, Int. J. Numer. Meth. Fluids
// 28:357-378; for staggered grids Arrufat, Crialesi-Esposito, Fuster et al. 2021, Comput.
// Fluids 215:104785). In cell-volume units (mass per hx hy):
//   the mass flux through a face         M = rho_air s + (rho_gran - rho_air) F,
//     s = u dt / h the face's CFL number, F the granular volume flux of that face's sweep;
//   the dilatation mass of a cell        D = (rho_air + (rho_gran - rho_air) c_c) sum of ds,
//     ds = s_{i+1/2} - s_{i-1/2} of each sweep (the c_c terms of the fraction, and their air
//     part; their sum is c_c dt div u, 0 for a solenoidal u),
// so that a cell's density goes from rho(c_a) to rho(c_b) = rho(c_a) - (net outflow of M) + D
// exactly, rho(c) = rho_air + (rho_gran - rho_air) c. A face's control volume has the density
// rho_f = the mean of its two cells' (ops::rho_xface, rho_yface: the same as the prediction and
// the projection), its sides' mass fluxes are the means of the two face fluxes they straddle,
// and its dilatation the mean of its cells', so that rho_f(c_b) = rho_f(c_a) - (its net side
// outflow) + D_f exactly. The momentum follows with the same fluxes,
//   rho_f(c_b) q' = rho_f(c_a) q - sum (M_side q_side) + D_f q,
// q_side upwind of the side's mass flux (MUSCL with van Leer's limiter, as convection(), the
// correction limited where the upwind control volume's M / rho_b is large; see the .cpp). A
// uniform q therefore stays uniform across any density jump: the momentum jump travels with
// the density jump. The update is unsplit (both sweeps' fluxes at once, from q): split into two
// sweeps like the fraction, the momentum of a solenoidal single-phase flow gains energy at
// O(dt^2) per step (measured: +3e-4 per step in a solid-body rotation at CFL 0.5, where the
// unsplit update loses 4e-4), since the sweeps' 1-D dilatations act on different velocities.
//  adv: the advecting face velocity (local, fill_velocity_ghosts); c_a, c_b: the volume fraction
//  before and after the step, cc: c_c (local dm_cell); F: the sweeps' fluxes (local dm_vel, .u
//  of the x sweep, .v of the y sweep); q: the transported velocity (local, ghosts filled); out:
//  owned faces of a global dm_vel array (walls 0).
void momentum_transport(const Box& b, double dt, double rho_air, double rho_gran,
                        const Vel* const* adv, const PetscScalar* const* c_a,
                        const PetscScalar* const* c_b, const PetscScalar* const* cc,
                        const Vel* const* F, const Vel* const* q, Vel** out);

// Divergence (u_{i+1} - u_i)/hx + (v_{j+1} - v_j)/hy at the owned cells, 1/s.
void divergence(const Box& b, const Vel* const* vel, PetscScalar** div);

// Shifts p (dm_cell) by a constant so that its mean on the top boundary y = Ly, extrapolated
// from the last two rows of cells, is zero: the pressure level of the projection
// (projection/Projection.hpp) and of the exact plastic step with the pressure. Collective.
void set_pressure_level(const Grid& g, Vec p);

}  // namespace gf::ops
