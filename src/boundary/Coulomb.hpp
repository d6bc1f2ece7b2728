#pragma once
// Coulomb friction of the granular phase on the walls (section 2.2): where the granular phase
// touches a wall with friction angle alpha_b, the tangential traction is -kappa_b s_t with the
// wall yield stress
//   kappa_b = tan(alpha_b) (-T_n)^+                                   (eq. 22)
// and the direction s_t, |s_t| <= 1, fixed by the projection of the wall line of eq. 30/31,
//   s_t <- P_b(s_t + r_b kappa_b u_t + theta (s_t^n - s_t)),          (eq. 30, relaxed as eq. 31)
// so that the material sticks (u_t = 0, |s_t| < 1: the wall stress is below the threshold,
// eq. 23) or slides (|s_t| = 1, eq. 22). Where air touches the wall, the wall's own condition
// (boundary/Boundary.hpp) applies.
//
// Wall storage in a dm_vel Vec (kappa_b, s_t): the bottom / top wall value of the u-face (i, 0) /
// (i, ny-1) in component u at (i, 0) / (i, ny-1); the left / right wall value of the v-face
// (0, j) / (nx-1, j) in component v at (0, j) / (nx-1, j) (none with periodic x). Faces without
// Coulomb friction or not granular hold 0.
#include <petscvec.h>

#include <algorithm>
#include <array>

#include "boundary/Boundary.hpp"
#include "boundary/Gate.hpp"
#include "boundary/SideWalls.hpp"
#include "grid/Grid.hpp"

namespace gf::boundary {

// P_b of eq. 30 on the tangential (scalar, in 2D) wall stress direction.
inline double project_b(double s) { return std::clamp(s, -1.0, 1.0); }

// Where the granular phase touches each frictional wall (index: side left, right, bottom, top):
// the length (m) where it sticks (|s_t| < 1, eq. 23) and where it slides (|s_t| = 1, eq. 22);
// per metre of depth, N/m: the granular normal load carried by the wall, sum of (-T_n)^+ over
// its Coulomb faces, and the friction force sum kappa_b s_t (signed, along +x on the bottom and
// top, +y on the side walls).
struct WallContact {
  std::array<double, 4> stick_m{0, 0, 0, 0}, slide_m{0, 0, 0, 0};
  std::array<double, 4> normal_N{0, 0, 0, 0}, friction_N{0, 0, 0, 0};
  SideContact side;  // the side walls of a channel (boundary/SideWalls.hpp)
  // The gate (boundary/Gate.hpp), N/m: the grains' normal load on it and its friction on them
  // (+y), both sides together.
  double gate_normal_N = 0, gate_friction_N = 0;
  // m, the gate's lower edge b(t) (above the domain's top once it has left); -1: no gate.
  double gate_bottom_m = -1;
};

class CoulombWalls {
 public:
  CoulombWalls(const Grid& g, const Boundaries& bc);
  ~CoulombWalls();
  CoulombWalls(const CoulombWalls&) = delete;
  CoulombWalls& operator=(const CoulombWalls&) = delete;

  // Coulomb friction coefficient tan(alpha_b) per wall, in the order left, right, bottom, top
  // (0 = none). A wall face is granular where phi (the mean of its two cells) < support, m (0:
  // the sign of phi, the paper; eps: the smeared band too, rheology.yield_support = "mass").
  void set_friction(const std::array<double, 4>& tan_alpha_b, double support = 0) {
    tan_b_ = tan_alpha_b;
    support_ = support;
  }
  bool active() const;  // some wall has friction (the gate's included)
  // The gate (not owned; null: none). Its Coulomb faces are the v-faces (i_g - 1, j) and
  // (i_g, j) on either side of its covered nodes (i_g, j), stored in the same Vecs as the walls'
  // (component v at those faces: interior faces, which no wall uses; the gate is at least two
  // cells from the left and right walls, setup/Checks.cpp).
  void set_gate(const Gate* gate) { gate_ = gate; }
  bool gate_face(const PetscScalar* const* ph, PetscInt i, PetscInt j) const;
  const Boundaries& conditions() const { return bc_; }
  // The level set of the current step (global Vec): which wall faces are granular.
  void set_phase(Vec phi);
  // The normal load on a wall from the wall cells' own weight (interface.method = "clsvof"):
  // -T_n on the wall = -T_n at the centre of the cell next to it plus the weight of the half
  // cell between that centre and the wall, rho_c |g . n| h / 2 (rho: global dm_cell Vec of the
  // step), instead of the linear extrapolation from the first two cells. With a sharp density
  // a granular film thinner than a cell lies in the half cell below its centre: the centre's
  // pressure carries half the film's weight, the extrapolation 3/4 of it (the second cell is
  // air), and a film on a 20 degree plane with a 25.5 degree wall then slid (0.75 tan 25.5 =
  // 0.358 < tan 20 = 0.364); the half cell's weight gives it its whole load. For a resolved
  // layer at rest both are the hydrostatic load.
  void set_wall_weight(Vec rho, const std::array<double, 2>& gravity);

  // The ghosted phi of set_phase, open for reading for the scope of the object (null if no
  // phase was set: then no face is a Coulomb face).
  class Phase {
   public:
    explicit Phase(const CoulombWalls& w);
    ~Phase();
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;
    const PetscScalar* const* array() const { return a_; }

   private:
    const CoulombWalls& w_;
    const PetscScalar** a_ = nullptr;
  };
  // Is the wall face granular and frictional? side: 0 left, 1 right, 2 bottom, 3 top; (i, j) the
  // cell whose face it is; ph: Phase::array().
  bool coulomb_face(const PetscScalar* const* ph, int side, PetscInt i, PetscInt j) const;

  // Ghosted copies of p, kappa and eta for yield(), which the fixed point calls in every
  // iteration with the same three: made once per step, used until clear_cache().
  void cache_inputs(Vec p, Vec kappa, Vec eta);
  void clear_cache() { cached_ = false; }
  // kappa_b = tan(alpha_b) (-T_n)^+ (eq. 22), -T_n = p^n - 2 eta D_nn - kappa S_nn at the cells
  // next to the wall (the normal stress on the wall, with the current D(u~) and S: it is
  // updated in every iteration of the fixed point, as kappa_b^{n+1} in eq. 31).
  void yield(Vec p, Vec S, Vec kappa, Vec D, Vec eta, Vec kappa_b);
  // s_t <- P_b(s_t + r_b kappa_b u_t + theta (s_t^n - s_t)) on the granular Coulomb faces
  // (eq. 31), r_b = r_factor (rho a0 h / dt + 2 eta / h) / kappa_b^2. Returns max |change|
  // (collective).
  double update(Vec u_tilde, Vec kappa_b, Vec s_wall, Vec s_wall_n, Vec rho, Vec eta,
                double a0_over_dt, double theta, double r_factor) const;
  // The stiffness of the first face velocity against a wall traction, Pa s/m: inertia
  // rho a0 h / dt and viscosity 2 eta / h (h the spacing normal to the wall). r_b kappa_b^2 =
  // r_factor times it (update; the exact step's c_b kappa_b, momentum/NewtonPlastic.cpp).
  static double stiffness(double rho, double eta, double a0_over_dt, double h) {
    return rho * a0_over_dt * h + 2.0 * eta / h;
  }
  // Collective.
  WallContact contact(Vec s_wall, Vec kappa_b) const;

 private:
  const Grid& g_;
  Boundaries bc_;
  std::array<double, 4> tan_b_{0, 0, 0, 0};  // left, right, bottom, top
  const Gate* gate_ = nullptr;
  double tan_g() const { return gate_ ? gate_->params().tan_g : 0.0; }
  double support_ = 0;                       // m, a wall face is granular where phi < this
  Vec lphi_ = nullptr;                       // local phi of the current step (granular faces)
  bool have_phase_ = false;
  bool cached_ = false;
  Vec lwp_ = nullptr, lwk_ = nullptr, lwe_ = nullptr;  // cache_inputs
  Vec lrho_ = nullptr;                         // set_wall_weight: ghosted rho
  std::array<double, 2> grav_{0, 0};           // m/s^2
  bool weight_ = false;
};

}  // namespace gf::boundary
