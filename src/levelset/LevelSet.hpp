#pragma once
// The level-set module of section 3.1: transport of phi (eq. 26) by a finite-volume WENO5
// scheme with TVD-RK3 in time, redistancing after Min (2010), and the phase properties derived
// from phi (density, eq. 25, and the harmonic-mean viscosity with the height fraction theta).
//
// Conventions (see grid/Grid.hpp): phi is cell centred on grid.dm_cell(), a signed distance in
// metres, phi > 0 in the air and phi < 0 in the granular phase. Velocities are MAC face values
// on grid.dm_vel(). Ghost cells OUTSIDE the physical domain are never read for phi: near a wall
// every stencil drops in order instead ("reducing the order of the schemes in the neighborhood
// of a boundary without adding ghost points", section 3.1).
// With a periodic x direction (Box::periodic_x) there is no wall in x: the x stencils keep
// their full order and read the wrapped ghosts filled by the ghost exchange.
#include <petscdmda.h>

#include <vector>

#include "grid/Grid.hpp"

namespace gf::levelset {

// ---------------------------------------------------------------------------------------------
// 1. Transport, eq. 26: d(phi)/dt + div(u phi) = 0.

// Finite-volume right-hand side rhs = -div(u phi) on the owned cells of b. The flux through a
// face is (face velocity) x (upwind WENO5 reconstruction of phi at the face, Jiang & Shu 1996).
// Where the five-cell stencil would leave the domain it drops to WENO3 (three cells) and, at the
// face next to a wall when the flow leaves the wall, to first-order upwind. Wall faces carry no
// flux (u.n = 0, eq. 20).
//  phi: LOCAL (ghosted, width >= 3) array of dm_cell, after DMGlobalToLocal;
//  vel: LOCAL array of dm_vel after DMGlobalToLocal and fill_velocity_ghosts();
//  rhs: GLOBAL array of dm_cell (only owned entries are written), 1/s * m.
void weno5_rhs(const Box& b, const PetscScalar* const* phi, const Vel* const* vel,
               PetscScalar** rhs);

// One explicit step of eq. 26 with a fixed face velocity: the three-stage TVD (Shu & Osher 1988)
// Runge-Kutta scheme. Owns its work vectors (no allocation per step). Stability: the usual
// advective CFL, dt * max(|u|/hx + |v|/hy) <= ~1 (see max_cfl_dt below).
class Advector {
 public:
  explicit Advector(const Grid& g);
  ~Advector();
  Advector(const Advector&) = delete;
  Advector& operator=(const Advector&) = delete;

  // phi: global Vec on dm_cell, advanced in place from t to t + dt; vel: global Vec on dm_vel
  // (divergence free for the scheme to be conservative of the granular volume).
  void step(Vec phi, Vec vel, double dt);

 private:
  const Grid& g_;
  Vec phi_loc_ = nullptr, vel_loc_ = nullptr;  // ghosted copies
  Vec stage_ = nullptr, rhs_ = nullptr;        // global work vectors
  void eval_rhs(Vec phi);                      // rhs_ = -div(u phi) with vel_loc_ ready
};

// Largest dt with dt * max over faces (|u|/hx + |v|/hy) <= cfl (collective).
double max_cfl_dt(const Grid& g, Vec vel, double cfl);

// ---------------------------------------------------------------------------------------------
// 2. Redistancing (Min 2010, "On reinitializing level set functions", JCP 229:2764-2772):
//   d(phi)/dtau + sgn(phi0) (|grad phi| - 1) = 0,
// ENO2 one-sided differences with the Godunov Hamiltonian, TVD-RK2 in pseudo time, and the
// subcell fix: in cells where phi0 changes sign towards a neighbour, the one-sided difference
// uses the value 0 at the interface, located by quadratic (or linear) ENO interpolation of phi0,
// so that the zero level does not move. At walls the missing one-sided difference is dropped
// (no ghost extrapolation) and the ENO correction falls to first order.
class Redistancer {
 public:
  // iterations: pseudo-time steps per run(); cfl: dtau / h (<= 0.5 recommended).
  Redistancer(const Grid& g, int iterations, double cfl);
  ~Redistancer();
  Redistancer(const Redistancer&) = delete;
  Redistancer& operator=(const Redistancer&) = delete;

  // Stop early once max |phi^{k+1} - phi^k| < tol (m) over the cells with |phi| < band (m;
  // default 0 = 3 max(hx, hy)), the band where the properties are evaluated. tol = 0 (default):
  // always do all the iterations. (Far from the interface the pseudo-time solution needs
  // ~distance/(cfl h) iterations to settle, so a domain-wide criterion would rarely stop.)
  // Walls: false (default) = a one-sided difference that would need a cell beyond a wall is
  // dropped; true = phi is extrapolated linearly beyond the wall (levelset.redistance_wall =
  // "extrapolate"), which keeps an interface's angle with the wall (see Redistance.cpp).
  void set_wall_extrapolation(bool on) { wall_extrap_ = on; }
  void set_tolerance(double tol, double band = 0) {
    tol_ = tol;
    band_ = band;
  }
  // Redistances phi (global Vec on dm_cell) in place; returns the iterations done (collective).
  int run(Vec phi);
  // How far phi is from a signed distance where the properties see it: max | |grad phi| - 1 |
  // over the owned cells with |phi| < 3 max(hx, hy), grad phi by central differences (one-sided
  // next to a wall). Collective. An exact distance gives 0 up to the kinks of its medial axis
  // (1 - cos(a/2) for two fronts meeting at an angle a: 0.009 at the 15 deg slopes of a pile,
  // 0.29 at a right-angled corner).
  double distance_defect(Vec phi);

 private:
  const Grid& g_;
  int iters_;
  double cfl_;
  double tol_ = 0, band_ = 0;
  bool wall_extrap_ = false;
  int last_iters_ = 0;
  Vec loc_ = nullptr;                   // ghosted work copy
  Vec stage_ = nullptr, rhs_ = nullptr;  // global work vectors
  // Per owned cell, fixed during one run() (from phi0): sign, local pseudo-time step and the
  // distances to the interface towards the four neighbours (< 0: no sign change that way).
  std::vector<double> sgn_, dtau_, dxm_, dxp_, dym_, dyp_;
  // phi into loc_ with its ghosts; the array is read-only until restored from loc_.
  const PetscScalar* const* ghosted(Vec phi);
  void prepare(Vec phi0);
  void eval_rhs(Vec phi);  // rhs_ = -sgn(phi0) (|grad phi| - 1) * dtau (an increment)
};

// ---------------------------------------------------------------------------------------------
// 3. Properties (section 3.1).

// Height fraction theta = int_K phi^+ / int_K |phi| (the AIR fraction: 1 in air, 0 in the
// granular phase) with phi bilinearly interpolated from cell centres (linearly extrapolated from
// in-domain centres in the half cells along the walls) and integrated exactly where it keeps one
// sign and by 8x8 midpoint sub-sampling per bilinear patch where it changes sign.
//  _cell: K = cell (i, j);
//  _node: K = dual cell of node (i, j) at (i hx, j hy), 0 <= i <= nx, 0 <= j <= ny, clipped to
//         the domain at walls (with periodic x, node 0 is interior and its K wraps).
// phi_local: LOCAL (ghosted) array; the stencil is cells i-1..i+1 / i-1..i.
double height_fraction_cell(const Box& b, const PetscScalar* const* phi_local, PetscInt i,
                            PetscInt j);
double height_fraction_node(const Box& b, const PetscScalar* const* phi_local, PetscInt i,
                            PetscInt j);

// Harmonic mean of the two viscosities weighted by the air fraction theta:
//   1/eta = theta/eta_air + (1 - theta)/eta_gran.
// NOTE: the paper prints 1/eta = theta/eta_s + (1 - theta)/eta_f, which with its own theta
// (the phi^+ fraction, phi > 0 = air) would give the air (theta = 1) the granular viscosity eta_s;
// the consistent formula, used here, swaps the two.
double harmonic_viscosity(double theta, double eta_air, double eta_gran);

struct Props {
  double rho_air, rho_gran;  // kg/m^3
  double eta_air, eta_gran;  // Pa s
  double eps;                // half width of the regularised Heaviside, m
};

// Cell-centred rho (eq. 25, regularised Heaviside) and eta (harmonic mean above); with
// eta_node (a dm_cell Vec), also eta at every node (i hx, j hy) the rank owns, stored at (i, j),
// from the height fraction of the node's dual cell.
void update_properties(const Grid& g, Vec phi, const Props& pr, Vec rho, Vec eta,
                       Vec eta_node = nullptr);

// The same harmonic means with a granular viscosity that varies from cell to cell (the mu(I)
// viscosity, eq. 11): eta at the cells from eta_gran there; eta_node at the interior nodes
// (1 <= i < nx, 0 <= i < nx with periodic x; 1 <= j < ny) from the mean eta_gran of the node's
// four cells. phi = nullptr: one phase (every height fraction 0).
void mix_viscosity(const Grid& g, Vec phi, double eta_air, Vec eta_gran, Vec eta, Vec eta_node);

// The granular volume fraction 1 - H_eps(phi) of each cell (eq. 25), into c (dm_cell).
void granular_fraction(const Grid& g, Vec phi, double eps, Vec c);

// Where the yield stress and the Coulomb wall friction act (rheology::yield_stress): support = 0,
// the granular phase phi < 0 (the paper: kappa = 0 in the air, eq. 18), weight 1; support = eps,
// wherever eq. 25 gives the cell granular mass (phi < eps, rheology.yield_support = "mass"),
// weighted by its granular fraction 1 - H_eps(phi). -1 elsewhere. Into w (dm_cell).
void yield_support(const Grid& g, Vec phi, double support, Vec w);

// ---------------------------------------------------------------------------------------------
// 4. Diagnostics (collective).

// Granular area sum (1 - H_eps(phi_ij)) hx hy, m^2 per unit depth.
double granular_area(const Grid& g, Vec phi, double eps);

// L1 interface error: the area of the symmetric difference between {phi < 0} and
// {phi_exact < 0}, int |H_0(phi) - H_0(phi_exact)| dA (m^2), both fields bilinearly interpolated
// from cell centres and sub-sampled 8x8 per patch in cells where either changes sign.
// Divide by the interface length for the "average interface displacement" (m).
double interface_l1_error(const Grid& g, Vec phi, Vec phi_exact);

}  // namespace gf::levelset
