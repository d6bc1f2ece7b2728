#pragma once
// Friction on the two side walls of a channel of width W (issue 21; the paper, section 4.2.2,
// names it as missing). The model is 2D in the (x, y) plane of the channel's axis; the side
// walls are the planes z = +-W/2. Averaged over the width, their tangential stress enters the
// 2D momentum equation as a body force (N/m^3)
//   f = -k s,   k = (2/W) tan(alpha_w) K p^+ c,   |s| <= 1,
// with s the direction of the friction, fixed by the same projection as the bottom wall's
// (eqs. 22-23, 30, relaxed as eq. 31), now on the unit disc:
//   s <- P(s + r k U + theta (s^n - s)),
// so that the grains stick (U = 0, |s| < 1) or slide against the velocity U (s = U/|U|). The
// normal stress on a side wall is K p: in the plane model the out-of-plane deviatoric stress is
// zero (D_zz = 0 for a 2D incompressible flow, and S is a 2 x 2 deviator), so sigma_zz = -p and
// K = 1 (boundary.side_walls.earth_pressure). That is the closure of Jop, Forterre & Pouliquen,
// J. Fluid Mech. 541 (2005) 167, for heap flows between side walls (normal stress on the walls =
// the pressure), and Taberlet et al., Phys. Rev. Lett. 91 (2003) 264301, take the same
// isotropic stress. c is the cell's granular fraction (the share of the wall the grains touch).
// In a rigid zone p is not fixed by the mechanics: with the in-plane deviator S carrying part of
// the load, p = -(sigma_xx + sigma_yy)/2 lies anywhere between the yield limits (a block with
// free ends has sigma_xx ~ 0 and p ~ half the overburden: measured 0.66 of it on
// cases/verify/coulomb_block.toml). boundary.side_walls.normal_stress = "hydrostatic" takes
// instead K p_hyd, the weight of the grains above (rheology::hydrostatic_pressure, as the
// yield stress of eq. 15), the closure of depth-averaged channel models; it does not depend on
// how a rigid zone's stress is split.
//
// Discretisation. k, s and the velocity U they act on live at the cell centres: U = I u, the mean
// of the two x-faces and of the two y-faces of the cell (grid/Local.hpp cell_centre_velocity),
// and the force on a face is the transpose, -I^T (k s): the mean of k s over the face's two
// cells. The pair is adjoint, so the force dissipates exactly sum k s . U hx hy = sum k |U| hx hy
// where it slides, and the prediction with the friction is still the minimisation of a convex
// functional (the Coulomb term sum k |I u| hx hy), which the projection solves exactly at its
// fixed point: a block whose friction exceeds its drive gets U = 0 (tests/verification/
// test_side_walls.sh). Storage: k in a dm_cell Vec, s in a dm_vel Vec read as a cell-centred
// vector (component u = s_x, v = s_y of the cell (i, j), not of its faces).
//
// Air on the side walls: Navier slip (eq. 24) with the wall coefficient eta_b, in series with the
// air's shear across the half-width for a parabolic profile between the walls (wall shear
// 6 eta_air U / W for a no-slip channel), i.e. a linear drag (2/W) eta_air eta_b / (eta_air +
// eta_b W/6) (1 - c) U, implicit in the viscous operator (Predictor::set_drag).
#include <petscvec.h>

#include <array>
#include <cmath>

#include "grid/Grid.hpp"

namespace gf::boundary {

struct SideWallParams {
  double width = 0;           // m, W; 0 = no side walls (the paper's 2D model)
  double tan_w = 0;           // tan(alpha_w), the grains on the side walls; 0 = none
  double earth_pressure = 1;  // K: the side walls' normal stress is K p (or K p_hyd)
  bool hydrostatic = false;   // normal_stress = "hydrostatic": K p_hyd, the overburden's weight
  double eta_b = 0;           // Pa s/m, Navier coefficient of the air on the side walls
  double eta_air = 0;         // Pa s, the air's viscosity (its shear across the width)
};

// P of the side-wall friction: the projection onto the unit disc.
inline void project_disc(double& sx, double& sy) {
  const double m = std::hypot(sx, sy);
  if (m > 1.0) {
    sx /= m;
    sy /= m;
  }
}

// Where the granular material sticks to and slides on the side walls: the granular area (m^2 of
// the 2D plane, the sum of c hx hy over the cells with k > 0) that sticks (|s| < 1) and slides
// (|s| = 1); per metre of channel width (the 2D model's depth): the side walls' load
// sum k / tan(alpha_w) hx hy = (2/W) sum K p c hx hy and the friction force -sum k s hx hy (N/m,
// along +x and +y).
struct SideContact {
  double stick_m2 = 0, slide_m2 = 0, normal_N = 0;
  std::array<double, 2> friction_N{0, 0};
};

class SideWalls {
 public:
  SideWalls(const Grid& g, const SideWallParams& p) : g_(g), p_(p) {}

  // The grains rub on the side walls.
  bool active() const { return p_.width > 0 && p_.tan_w > 0; }
  // The air rubs on them.
  bool air_drag() const { return p_.width > 0 && p_.eta_b > 0; }
  const SideWallParams& params() const { return p_; }

  // k = (2/W) tan(alpha_w) K p^+ c (N/m^3) on the cells where support >= 0 (the yield stress's
  // support, rheology::yield_stress), 0 elsewhere. frac: the granular fraction c; p: p^n, or
  // p_hyd with normal_stress = "hydrostatic".
  void yield(Vec frac, Vec support, Vec p, Vec k) const;
  // The air's drag coefficient (Pa s/m^2) per cell, (2/W) eta_air eta_b / (eta_air + eta_b W/6)
  // (1 - c), for Predictor::set_drag.
  void drag(Vec frac, Vec out) const;
  // rhs += -I^T (k s) on the faces (N/m^3).
  void add_force(Vec k, Vec s, Vec rhs) const;
  // s <- P(s + r k I u + theta (s^n - s)) on the cells with k > 0 (s = 0 elsewhere), with
  // r = r_factor (rho a0/dt + 2 eta/(hx hy)) / k^2 (the compliance of a cell's velocity to a body
  // force, as the bottom wall's r_b per unit area). Returns the largest change of the force it
  // makes, max k |change of a component| / k_ref (collective): a cell of a small load k flips
  // its direction with the sign of a velocity at round-off (r k |U| >> 1 for any U there), a
  // change of 2 in s but not in the force; measured on s itself, a tan(alpha_w) = 1e-9 side wall
  // kept the Coulomb block's fixed point from converging and moved its acceleration by 2.6 %.
  double update(Vec u, Vec k, Vec s, Vec s_n, Vec rho, Vec eta, double a0_over_dt, double theta,
                double r_factor, double k_ref) const;
  // The power of the side-wall friction on the velocity u, W per metre of channel width:
  // -sum k s . I u hx hy (<= 0 at the fixed point). Collective.
  double power(Vec u, Vec k, Vec s) const;
  // frac: the granular fraction c of yield(). Collective.
  SideContact contact(Vec k, Vec s, Vec frac) const;

 private:
  const Grid& g_;
  SideWallParams p_;
};

}  // namespace gf::boundary
