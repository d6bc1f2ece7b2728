#pragma once
// Scalar flow diagnostics: what the time loop logs each step and what summary.json reports.
// All functions are collective on the grid's communicator and return the same value on every
// rank. They read the state only.
//
// Exact definitions (hx, hy the cell sizes; u_{i,j} the x-velocity on the left face of cell
// (i, j), v_{i,j} the y-velocity on its bottom face; the wall faces u_{0,j}, u_{nx,j},
// v_{i,0}, v_{i,ny} are zero by eq. 20 whatever the stored value):
//   cell-centre velocity   uc = (u_{i,j} + u_{i+1,j}) / 2,   vc = (v_{i,j} + v_{i,j+1}) / 2
//   max_speed            = max_cells sqrt(uc^2 + vc^2)                                   [m/s]
//   kinetic_energy       = sum_cells 1/2 rho_{ij} ( (u_{i,j}^2 + u_{i+1,j}^2) / 2
//                                                 + (v_{i,j}^2 + v_{i,j+1}^2) / 2 ) hx hy  [J/m]
//   max_divergence       = max_cells |(u_{i+1,j} - u_{i,j}) / hx + (v_{i,j+1} - v_{i,j}) / hy|
//                                                                                          [1/s]
//   granular_volume      = sum_cells (1 - H_eps(phi_{ij})) hx hy                          [m^2/m]
//   max_in_granular(f)   = max over cells with phi_{ij} < 0 of f_{ij}; 0 if there is none
//
// The maxima propagate NaN (a NaN anywhere gives NaN on every rank) so that the time loop can
// use them to detect a blown-up run; a plain max would silently skip NaN. The sums propagate
// NaN by arithmetic. Sums are reduced with MPI_SUM, so they agree across rank counts to
// round-off, not bit for bit.
#include <petscvec.h>

#include <array>

#include "grid/Grid.hpp"

namespace gf::diag {

// Largest speed at a cell centre, from face averages (see above), m/s. `vel` on dm_vel.
double max_speed(const Grid& g, Vec vel);

// Kinetic energy per metre of depth, J/m. `vel` on dm_vel, `rho` (kg/m^3) on dm_cell.
// u^2 is the mean of the squares of the two faces, not the square of the mean: this is the
// face-based MAC energy with face density interpolated from the cells, and unlike the square
// of the mean it cannot hide an odd-even (checkerboard) velocity mode.
double kinetic_energy(const Grid& g, Vec vel, Vec rho);

// Largest absolute discrete divergence over all cells, 1/s: the quantity the projection
// (eq. 32) drives to the solver tolerance. `vel` on dm_vel.
double max_divergence(const Grid& g, Vec vel);

// Area of the granular phase per metre of depth, m^2/m, with the smoothed Heaviside of
// section 3.1 (levelset::heaviside): the volume that mass conservation checks compare.
double granular_volume(const Grid& g, Vec phi, double eps);

// Largest value of the cell field `field` over the granular cells (phi < 0), e.g. the
// viscosity or the pressure in the pile; 0 when no cell is granular. Both on dm_cell.
double max_in_granular(const Grid& g, Vec field, Vec phi);

// Mean velocity of the granular phase, sum (1 - H_eps(phi)) u_c / sum (1 - H_eps(phi)) over the
// cells (cell-centred velocity as in max_speed), m/s: the velocity of a rigid granular block.
// {0, 0} if there is no granular cell.
std::array<double, 2> granular_mean_velocity(const Grid& g, Vec vel, Vec phi, double eps);

// The same weighted by a granular volume fraction field (dm_cell, 0..1): the conserved c of
// interface.method = "clsvof".
std::array<double, 2> granular_mean_velocity(const Grid& g, Vec vel, Vec fraction);

// Potential energy per metre of depth in the gravity field g, J/m:
//   -sum_cells rho_{ij} (g_x x_i + g_y y_j) hx hy   (x_i, y_j the cell centres),
// the energy that the kinetic energy and the dissipation of the energy budget are measured
// against (diagnostics.csv potential_energy).
double potential_energy(const Grid& g, Vec rho, const std::array<double, 2>& gravity);

// A cell of the grid, for failure messages ("where"); i < 0 means none.
struct CellIndex {
  PetscInt i = -1, j = -1;
  bool found() const { return i >= 0; }
};

// The first cell (lowest j, then lowest i) where `field`, a global Vec of a grid DM (any dof),
// holds a NaN or an infinity in any component; none if the field is finite. Collective.
CellIndex first_nonfinite(const Grid& g, Vec field);

// max_speed and the cell where it is reached (the first such cell, as above).
struct SpeedAt {
  double speed = 0;  // m/s
  CellIndex at;
};
SpeedAt max_speed_at(const Grid& g, Vec vel);

}  // namespace gf::diag
