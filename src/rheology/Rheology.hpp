#pragma once
// The viscoplastic rheology of sections 2.1-2.2 and 3.2, in the generic form of eqs. 16-19:
//   T' = 2 eta D(u) + kappa S,   S = P(S + r kappa D(u))   (eq. 29, any r > 0),
// with the yield stress kappa: 0 in air (eq. 18), tau_y (Bingham), tan(alpha) p^+ (Drucker-
// Prager, eq. 19) or tan(alpha) p_hyd (hydrostatic variant, eq. 15); and eta: constant, or the
// mu(I) viscosity of eq. 11. The plastic tensor S is traceless and symmetric; in the plane it is
// (Sxx, Sxy, Syy = -Sxx). Norms are the paper's modified Frobenius norm
//   |L|^2 = 1/2 sum_ij L_ij^2 = Lxx^2 + Lxy^2   (traceless 2D tensor).
// This module knows nothing of the level set: the granular region comes in as a field (the
// yield-stress support of yield_stress below), computed from phi by levelset/.
#include <petscdmda.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "grid/Grid.hpp"

namespace gf::rheology {

enum class Yield { None, Bingham, DruckerPrager, Hydrostatic };
enum class Viscosity { Constant, MuI };

struct Params {
  Yield yield = Yield::None;
  double tau_y = 0;        // Pa, Bingham
  double tan_alpha = 0;    // internal friction mu_s = tan(alpha)
  Viscosity viscosity = Viscosity::Constant;
  double mu_inf = 0.73, I0 = 0.279, d = 0;  // eq. 11; d in m
  double eta_min = 1e-3, eta_max = 1.2;      // Pa s: floor and cap of the mu(I) viscosity
  double r_factor = 1;     // r = r_factor (2 eta + rho a0 h^2/dt) / kappa^2 (see r_local)
  // S also at the nodes (rheology.plastic_grid = "cell_node"): half of the plastic stress from
  // the cell copy (shear rate = mean of the four node rates), half from the node copy (normal
  // rate = mean of the adjacent cells').
  bool node_copy = false;
  double theta_per_dt = 10;  // 1/s: theta = theta_per_dt dt (section 4.1.3), capped at 0.5
  double fp_tol = 1e-6;    // stop when max |S_{k+1} - S_k| and |s_{k+1} - s_k| fall below
  // m/s; > 0: also stop when the velocity u~ of eq. 31 changes by less than this in one
  // iteration (its modes that do not move u converge at the rate 1 - theta only).
  double fp_tol_u = 0;
  int fp_max_iter = 50;
  bool active() const { return yield != Yield::None; }
};

// P of eq. 29 on a traceless symmetric tensor (Sxx, Sxy): the projection on the unit ball of
// the modified Frobenius norm.
inline void project(double& sxx, double& sxy) {
  const double n = std::sqrt(sxx * sxx + sxy * sxy);
  if (n > 1.0) {
    sxx /= n;
    sxy /= n;
  }
}
// The mu(I) viscosity of eq. 11 from |D| (the paper's norm, 1/s) and p (Pa), clipped to
// [eta_min, eta_max] (a floor keeps the viscous operator well posed where p -> 0 and |D| is
// large; a cap where |D| -> 0 and the model viscosity grows without bound).
inline double mu_i_viscosity(const Params& pr, double Dnorm, double p, double rho_s) {
  const double pp = std::max(p, 0.0);
  const double den = 2.0 * Dnorm + pr.I0 * std::sqrt(pp) / (pr.d * std::sqrt(rho_s));
  const double eta = den > 0 ? (pr.mu_inf - pr.tan_alpha) * pp / den : pr.eta_max;
  return std::clamp(eta, pr.eta_min, pr.eta_max);
}

// The augmentation parameter r of eqs. 29 and 31 at a point. Any r > 0 has the same fixed point
// in eq. 29 (theta = 0), not in eq. 31: with the relaxation theta (S^n - S), a converged step
// inside the yield surface has r kappa D = theta (S - S^n): it deforms like an elastic solid
// whose stiffness grows with r / theta (test
// Rheology.RelaxedProjectionFixedPointDependsOnROverTheta). The iteration
// S <- P(S + r kappa D(u~(S))) contracts fastest when r kappa^2 matches the inverse of the
// compliance of D(u~) to the stress kappa S at the grid scale, which is of order
// 1 / (2 eta + rho a0 h^2 / dt) (viscous and inertial parts of the prediction operator).
inline double r_local(const Params& pr, double kappa, double eta, double rho_a0_h2_dt) {
  return kappa > 0 ? pr.r_factor * (2.0 * eta + rho_a0_h2_dt) / (kappa * kappa) : 0.0;
}

// out = the minimum of `in` over each cell and its 8 neighbours (those inside the domain; across
// a periodic x seam too). The stress kappa S of a cell acts, through the faces and nodes around
// it, on faces whose density and viscosity are those of its neighbours: at the interface those
// are the air's, 1000 times lighter, and an r built from the cell's own rho makes the cell's S
// overshoot and flip sign from one iteration to the next (measured with levelset.eps_cells = 1:
// 2/3 of the case A steps and the Coulomb block's fixed point stuck at a change of 2). r takes
// the lightest, most compliant neighbour instead. Both on dm_cell; collective.
void neighbourhood_min(const Grid& g, Vec in, Vec out);

// p_hyd of eq. 15 at the cell centres: rho_s |g_y| times the granular thickness above the point
// in its column, int_y^{Ly} c(x, s) ds, with c the granular fraction (1 - H_eps(phi)) of the
// cells, so that where the column is all granular below its top, p_hyd = rho_s |g| (top - y).
// Columns are split across ranks in y: each rank sums its rows, and the partial sums of the
// ranks above are added by an exclusive scan over the ranks of the same process column.
// c: global dm_cell Vec; out: global dm_cell Vec (Pa).
void hydrostatic_pressure(const Grid& g, Vec c, double rho_s, double g_abs, Vec out);

}  // namespace gf::rheology

namespace gf::rheology {

// One projection of the fixed point of eq. 31 on the cells:
//   S <- P(S + r kappa D(u~) + theta (S^n - S)),  r = r_local(...) per cell.
// S, S_n, D: dm_ten (xx, xy, yy); kappa, rho, eta: dm_cell. Where kappa = 0 (air) S is set to 0.
// Returns max over cells of |S_new - S| (modified Frobenius norm; collective).
double update_plastic(const Grid& g, const Params& pr, Vec S, Vec S_n, Vec kappa, Vec D, Vec rho,
                      Vec eta, double a0_over_dt, double theta);

// The same projection on the node copy of S (rheology.plastic_grid = "cell_node"): S, S_n, D
// on dm_node; kappa, rho, eta (dm_cell) taken at a node as the mean of the cells around it.
// r is r_local with these means. Returns max |S_new - S| (collective).
double update_plastic_node(const Grid& g, const Params& pr, Vec S, Vec S_n, Vec kappa, Vec D,
                           Vec rho, Vec eta, double a0dt, double theta);
// P on every node of the node copy, and 0 where the node's kappa is 0.
void project_field_node(const Grid& g, Vec S, Vec kappa);

// The yield stress kappa at the cell centres (eqs. 18-19). `support` says where it acts and with
// what weight (levelset::yield_support): a cell with support < 0 has none (air, eq. 18); a cell
// with support >= 0 has tan(alpha) p^+ (dp, eq. 19) or tan(alpha) p_hyd (hp, eq. 15), or the
// Bingham tau_y times its support, the cell's granular volume fraction where the yield stress
// follows the mass (rheology.yield_support = "mass"; 1 in the paper's sharp support). Bingham
// fractions below 1e-9 count as none (r ~ 1/kappa^2).
// p: the latest pressure p^n; p_hyd: only read for Yield::Hydrostatic.
void yield_stress(const Grid& g, const Params& pr, Vec support, Vec p, Vec p_hyd, Vec kappa);

// The mu(I) viscosity of eq. 11 at the cell centres from D (dm_ten, the deviatoric part taken
// here) and p (dm_cell), into eta_s (dm_cell): the granular phase's own viscosity, before its
// harmonic mean with the air (levelset::mix_viscosity).
void mu_i_viscosity(const Grid& g, const Params& pr, Vec D, Vec p, double rho_s, Vec eta_s);

// P applied to every cell of S (dm_ten), and S = 0 where kappa = 0: keeps an extrapolated
// iterate (Anderson) inside the set |S| <= 1 of eq. 29.
void project_field(const Grid& g, Vec S, Vec kappa);

// |L| of a dm_ten field at the cell centres (modified Frobenius norm), into a dm_cell Vec.
void tensor_norm(const Grid& g, Vec L, Vec out);

// The yielded mask of the output (dm_cell): 1 where the material flows (no yield stress,
// kappa <= 0, or |S| >= 1 - 1e-9: on the yield surface), 0 where it is rigid. Snorm: |S|.
void yielded_mask(const Grid& g, Vec Snorm, Vec kappa, Vec yielded);

}  // namespace gf::rheology
