#pragma once
// The plastic part of eq. 31 as sparse matrices, the building blocks of a Newton-type solver of
// each step's plastic problem (issue 19: A u~ + C kappa P(S + c B u~) = b, with the pressure
// gradient and div u = 0 beside it in a coupled step):
//
//   D(u)        = B u + d0      the cell strain rate of Predictor::strain_rate (Dxx, Dxy, Dyy;
//                               d0 the moving walls' part, zero on walls at rest),
//   div(kappa S) = C (kappa S)  the divergence of the plastic stress of Predictor::add_plastic
//                               on the faces, without the Coulomb wall tractions (eq. 30 has
//                               its own projection; they enter with kappa_b s_t).
//
// Both are assembled by probing the two kernels with colour vectors (one colour per residue of
// the face or cell index modulo 3 in each direction, widened at the periodic seam), not by a
// second copy of their stencils: the matrices are the kernels' discretisation exactly, walls,
// Navier slip, the gate's covered nodes and the Coulomb walls' phase (set_phase) included, and
// stay so when a kernel changes. A probe response that no face (or cell) of its colour in the
// stencil can explain is a changed stencil and throws.
//
// On free-slip, periodic and Coulomb walls C = -B^T W with W = diag(1, 2, 1) (the symmetric
// tensor's S:D = Sxx Dxx + 2 Sxy Dxy + Syy Dyy): the plastic force is the exact adjoint of the
// strain rate, the discrete form of the virtual power of the plastic stress, so the step's
// plastic problem is a convex minimisation. The no-slip walls' extrapolated shear stress
// (add_plastic) and the Navier walls' shear rate (strain_rate) are not adjoint to each other
// (tests/unit/momentum/test_plastic_matrices_mpi.cpp measures by how much).
#include <petscmat.h>

#include "grid/Grid.hpp"
#include "momentum/Momentum.hpp"

namespace gf::momentum {

struct PlasticMatrices {
  Mat B = nullptr;  // dm_ten global Vec <- dm_vel global Vec, 1/m
  Vec d0 = nullptr;  // dm_ten global Vec, 1/s
  Mat C = nullptr;  // dm_vel global Vec <- dm_ten global Vec, 1/m
  PlasticMatrices() = default;
  ~PlasticMatrices();
  PlasticMatrices(const PlasticMatrices&) = delete;
  PlasticMatrices& operator=(const PlasticMatrices&) = delete;
};

// Assembles B, d0 and C for the current state of pred (boundaries, gate, Coulomb phase); eta is
// the cell viscosity strain_rate reads on Navier walls. Clears pred's plastic region (the
// matrices cover every cell). Without the node copy of S (rheology.plastic_grid = "cell").
// Collective; replaces what out held.
void assemble_plastic_matrices(const Grid& g, Predictor& pred, Vec eta, PlasticMatrices& out);

}  // namespace gf::momentum
