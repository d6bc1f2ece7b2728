#pragma once
// The gate of a dam-break experiment (issue 21): a thin vertical plate at x = x_g that holds the
// column at t <= 0 and is lifted from t = 0 at a constant speed V, leaving the domain through
// its top. The paper does not model it (section 4.1.1: a time shift of -0.03 s, half its lifting
// time, instead).
//
// A moving solid inside the grid, by blocked faces: the plate lies on the column of u-faces
// i_g = round(x_g / hx) (a grid line; the case's x_g is moved to it, `granflow check` says
// where) and covers y in [b(t), H_g], b(t) = V t: H_g, the top of the channel's opening, is
// below the domain's top so that the air above the plate connects both sides (as the open top
// of the channel does) and the pressure keeps one null space; the plate leaves once b >= H_g.
//   * Normal velocity: the aperture a_j of the u-face (i_g, j) is the part of [j hy, (j+1) hy]
//     not covered by the plate. The prediction pins u~ = 0 on a face the plate touches (a
//     penalty on its row of the viscous operator, momentum/Momentum.hpp), and the projection's
//     Poisson problem takes the face's coefficient times a_j, its velocity correction likewise
//     (projection/Projection.hpp): a covered face carries no flux, a partly covered one the
//     pressure-driven flux of its open part (a cut face), so div u = 0 and the volume fraction's
//     fluxes stay exact.
//   * Tangential stress: the nodes (i_g, j) the plate covers are walls for the faces on either
//     side: no shear is carried across (their viscous and plastic couplings are dropped); the
//     air sees Navier slip on the plate (eta_b, eq. 24) moving at V, the grains Coulomb friction
//     on it, kappa_g = tan(alpha_g) (-T_xx)^+ against their velocity relative to the plate,
//     v - V (boundary/Coulomb.hpp, as on the domain's walls, eqs. 22-23, 30).
#include <petscsys.h>

#include <algorithm>
#include <cmath>

#include "grid/Grid.hpp"

namespace gf::boundary {

struct GateParams {
  double x = 0;       // m, the plate's position; 0 = no gate
  double height = 0;  // m, H_g
  double speed = 0;   // m/s, V (0: never lifted)
  double tan_g = 0;   // tan(alpha_g), the grains on the plate; 0 = frictionless
  double eta_b = 1;   // Pa s/m, Navier coefficient of the air on the plate
};

class Gate {
 public:
  Gate(const Grid& g, const GateParams& p) : p_(p), ny_(g.box().ny), hy_(g.box().hy) {
    if (p_.x > 0) i_ = static_cast<PetscInt>(std::lround(p_.x / g.box().hx));
    set_time(0.0);
  }
  bool enabled() const { return i_ > 0; }
  const GateParams& params() const { return p_; }
  // The u-face column of the plate (0: no gate).
  PetscInt face() const { return i_; }
  // The geometry at time t (s): b(t) = V max(t, 0). The plate covers [b(t), H_g]: it rises out
  // of the channel through its open top, which the domain's lid stands for above H_g. Covering
  // [b, b + H_g] instead, its top reached the lid after (Ly - H_g) / V (9 ms in case A) and
  // sealed the air above the column from the air outside: the column then hung in that air's
  // suction (p down to -2 kPa in case B) and no grain left under the rising plate until it had
  // gone.
  void set_time(double t) { bottom_ = p_.speed * std::max(t, 0.0); }
  double bottom() const { return bottom_; }
  double top() const { return p_.height; }
  // Inside the domain at the time set.
  bool present() const { return enabled() && bottom_ < p_.height; }
  // The plate's velocity (+y), m/s.
  double velocity() const { return p_.speed; }
  // The open part (0..1) of the u-face (i, j); 1 off the plate's column.
  double aperture(PetscInt i, PetscInt j) const {
    if (i != i_ || !present()) return 1.0;
    const double lo = j * hy_, hi = (j + 1) * hy_;
    const double covered = std::max(0.0, std::min(hi, p_.height) - std::max(lo, bottom_));
    return std::clamp(1.0 - covered / hy_, 0.0, 1.0);
  }
  // The node (i, j) (an interior node, 1 <= j < ny) is on the plate.
  bool node_blocked(PetscInt i, PetscInt j) const {
    if (i != i_ || !present() || j < 1 || j >= ny_) return false;
    const double y = j * hy_;
    return y >= bottom_ && y <= p_.height;
  }

 private:
  GateParams p_;
  PetscInt i_ = 0;
  PetscInt ny_ = 0;
  double hy_ = 0;
  double bottom_ = 0;
};

}  // namespace gf::boundary
