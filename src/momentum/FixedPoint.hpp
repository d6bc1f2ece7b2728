#pragma once
// The fixed point of eq. 31: the prediction u~ of a step with a yield stress (Bingham, Drucker-
// Prager, its hydrostatic variant) or Coulomb wall friction. With kappa, kappa_b's inputs and the
// viscous operator A frozen for the step (momentum/Momentum.hpp), each iteration k
//   1. solves A u~ = rhs0 + div(kappa S_k) - kappa_b s_t,k        (the viscous solve, eq. 31)
//   2. projects S_{k+1}   = P  (S_k   + r   kappa   D(u~) + theta (S^n   - S_k))   (eqs. 29, 31)
//               s_t,k+1   = P_b(s_t,k + r_b kappa_b u~_t + theta (s_t^n - s_t,k)) (eqs. 30, 31)
//      with kappa_b = tan(alpha_b) (-T_n)^+ refreshed from the current D(u~) and S (eq. 22),
//      and with the side walls of a channel (boundary/SideWalls.hpp) their friction direction
//               s_side,k+1 = P(s_side,k + r k I u~ + theta (s_side^n - s_side,k)) on the disc
//      (its force -I^T k s_side is in step 1's right-hand side);
//   3. stops when max |S_{k+1} - S_k|, |s_t,k+1 - s_t,k| < fp_tol (or the velocity changes by less
//      than fp_tol_u), after fp_max_iter iterations otherwise (a capped step);
//   4. otherwise accelerates: Anderson mixing of the last iterates (linsolve/Anderson.hpp, depth
//      rheology.anderson_depth; 0 = the paper's plain iteration), re-projected into |S| <= 1,
//      |s_t| <= 1; the history is dropped when the change grows by more than
//      rheology.anderson_reset_ratio from one iteration to the next.
// theta = theta_per_dt dt ("theta = 10 dt", section 4.1.3) makes the map contract with ratio
// (1 - theta) or better. The operator and its preconditioner are the same in every iteration;
// only the right-hand side changes.
//
// Two savings that leave the iterates as they are: the plastic terms and D(u~) are only computed
// on the granular region (cells with kappa > 0 or phi < 0, the `granular` mask) widened by 2
// cells; with solver.viscous_local_margin > 0 the solves from the second iteration on are
// restricted to the granular rows widened by that many cells (Predictor::begin_local), and the
// fixed point ends with one full solve that puts back what the frozen rows missed.
#include <petscvec.h>

#include <memory>
#include <vector>

#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "linsolve/Anderson.hpp"
#include "momentum/Momentum.hpp"
#include "rheology/Rheology.hpp"

namespace gf::momentum {

struct FixedPointOptions {
  int anderson_depth = 5;            // rheology.anderson_depth; 0 = plain (Picard) iteration
  double anderson_reset_ratio = 1.0;  // rheology.anderson_reset_ratio
  bool monitor = false;              // rheology.fp_monitor: a log line per iteration
  int local_margin = 0;              // cells, solver.viscous_local_margin; 0 = full solves
};

struct FixedPointStats {
  int visc_its = 0;         // KSP iterations of all the viscous solves
  int visc_polish_its = 0;  // of them, the full solve closing local solves (0: none missed)
  int iters = 0;            // fixed-point iterations
  double change = 0;        // the last change of S and s_t (dimensionless)
  bool converged = false;   // met fp_tol (or fp_tol_u)
};

// The fields of the step the fixed point reads (derived from the state by the stepper).
struct PlasticInputs {
  Vec kappa;     // dm_cell, Pa: the yield stress of eqs. 15, 18-19
  Vec kappa_b;   // dm_vel wall storage, Pa: the wall yield stress (eq. 22), refreshed here
  Vec rho_r;     // dm_cell: rho and eta for the augmentation r (rheology::neighbourhood_min)
  Vec eta_r;
  Vec granular;  // dm_cell: -1 on the cells with kappa > 0 or phi < 0, 0 elsewhere
  // dm_cell, N/m^3: the side walls' friction bound k (boundary/SideWalls.hpp); null without
  // side walls.
  Vec kappa_side = nullptr;
};

// The rows of a dm_vel global Vec (local indices, ascending) of the cells where `granular` < 0,
// widened by `margin` cells (box dilation): their left and bottom faces' u and v. Collective.
std::vector<PetscInt> granular_rows(const Grid& g, Vec granular, int margin);

class FixedPoint {
 public:
  FixedPoint(const Grid& g, Predictor& pred, const rheology::Params& rheo,
             const FixedPointOptions& opt);
  ~FixedPoint();
  FixedPoint(const FixedPoint&) = delete;
  FixedPoint& operator=(const FixedPoint&) = delete;

  // Solves eq. 31 for u~ (in: the initial guess; out: the prediction), updating s.S, s.s_wall
  // (and s.S_node with the node copy) from S^n, s_t^n in s. rhs0: the explicit part of the
  // right-hand side (Predictor::explicit_rhs); a0dt = a0/dt (1/s); theta the relaxation;
  // step: the number of the step being taken, for the monitor. Collective.
  FixedPointStats solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde, double a0dt,
                        double theta, long long step);

 private:
  const Grid& g_;
  Predictor& pred_;
  rheology::Params rheo_;
  FixedPointOptions opt_;
  std::unique_ptr<linsolve::Anderson> anderson_;
  // S^n, s_t^n; G(x) of the iteration (the projected S and s_t); the node copy's D, S^n, G(x).
  Vec S_n_ = nullptr, sw_n_ = nullptr, gS_ = nullptr, gW_ = nullptr;
  Vec Dn_ = nullptr, Sn_n_ = nullptr, gSn_ = nullptr;
  Vec D_ = nullptr, rhs_ = nullptr, u_prev_ = nullptr;
  // The side walls' s^n and G(x) (dm_vel, cell-centred vectors); null without side walls.
  // Anderson mixes them as the forces they make, z = (k / k_max) s (zx_, zg_), so that the
  // directions of cells with a small load, which flip at no cost in force, do not steer the
  // mixing (SideWalls::update); k_max_: the largest k of the step.
  Vec sd_n_ = nullptr, gSd_ = nullptr, zx_ = nullptr, zg_ = nullptr;
  double k_max_ = 0;
  bool side() const { return sd_n_ != nullptr; }
  // Anderson's blocks in the order of anderson_active(): (S, s_t[, S_node][, s_side]).
  void blocks(State& s, std::vector<Vec>& x, std::vector<Vec>& gx);
  // zx_ = (k / k_max) sx and zg_ = (k / k_max) sg; from_force: sx = zx_ / (k / k_max) (0 where
  // k = 0), before the re-projection into the disc.
  void to_force(Vec k, Vec sx, Vec sg);
  void from_force(Vec k, Vec sx);
  // The entries of (S, s_t[, S_node]) that can be non-zero in this step's fixed point, as local
  // indices per block (Anderson::set_active): S where kappa > 0 or S^n != 0, s_t on the wall
  // faces (or where s_t^n != 0), the node copy everywhere, s_side where kappa_side > 0 or
  // s_side^n != 0.
  std::vector<std::vector<PetscInt>> anderson_active(Vec kappa, Vec kappa_side) const;
  // Limits the plastic terms and D(u~) to the granular cells widened by 2 cells
  // (Predictor::set_plastic_region); collective.
  void set_plastic_region(Vec granular);
  // The rows of a dm_vel global Vec (local indices, ascending) of the granular cells widened by
  // margin cells (a box in the cell indices), for Predictor::begin_local.
  std::vector<PetscInt> local_rows(Vec granular, int margin) const;
  // Step 1 of iteration k: the viscous solve with the current S and s_t (the local solves from
  // k = 2 on); du, umax: the change of u~ and its largest value when they are tracked.
  // Returns the KSP iterations.
  int viscous_solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde, int k, double& du,
                    double& umax);
  // Step 2: G(x) into gS_, gW_ (gSn_): the projections of eq. 31 with kappa_b refreshed.
  // Returns the change max |G(x) - x|.
  double project(State& s, const PlasticInputs& in, Vec u_tilde, double a0dt, double theta);
  // Step 4: Anderson mixing of the iterates into s.S, s.s_wall (s.S_node), re-projected.
  void accelerate(State& s, const PlasticInputs& in);
  // The monitor line of iteration k: the change, the velocity change, and the root-mean-square
  // change of S over the cells where it changed by more than 1e-12 and how many they are.
  void report(long long step, int k, double change, double du, double umax, Vec S) const;
};

}  // namespace gf::momentum
