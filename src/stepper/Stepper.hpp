#pragma once
// One time step of the two-phase model, in the order of the paper (sections 3.1-3.3):
//   1. phi^{n+1} from eq. 26 with the solenoidal u^n (WENO5 + TVD-RK3), redistanced every N steps
//      (or every T seconds of simulated time);
//   2. rho^{n+1}, eta^{n+1} from phi^{n+1} (eq. 25, harmonic mean with the height fraction);
//   3. prediction (eq. 31): explicit terms, then the implicit viscous solve for u~
//      (the fixed point with the plastic stress S plugs in here: it only changes the rhs);
//   4. projection (eq. 32): u^{n+1}, p^{n+1}.
// This is the only code that calls all the layers; diagnostics and output live in sim/.
#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "boundary/Boundary.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "momentum/Momentum.hpp"
#include "rheology/Rheology.hpp"

namespace gf {
namespace levelset {
class Advector;
class Redistancer;
}  // namespace levelset
namespace momentum {
class Predictor;
}
namespace projection {
class Projector;
}

enum class PrescribedFlow { None, Rotation, SingleVortex };

struct PhysicsConfig {
  double rho_gran = 1550, eta_gran = 0.5;  // kg/m^3, Pa s
  double rho_air = 1.2, eta_air = 1.8e-5;  // kg/m^3, Pa s
  std::array<double, 2> gravity{0.0, -9.81};  // m/s^2
  bool levelset = true;       // false: one phase (the "granular" values everywhere)
  double eps = 0;             // m, half-width of the smeared Heaviside (eq. 25)
  int redistance_every = 5;   // steps, 0 = never
  double redistance_tol = 0;  // > 0: only when max | |grad phi| - 1 | near phi = 0 exceeds it
  double redistance_interval = 0;  // s; > 0: in the step reaching each multiple of it (not by
                                   // redistance_every)
  bool redistance_wall_extrapolate = false;  // levelset.redistance_wall = "extrapolate"
  int redistance_iters = 10;
  double redistance_cfl = 0.5;
  Boundaries bc;
  double pressure_rtol = 1e-10, viscous_rtol = 1e-10;
  int viscous_local_margin = 0;  // cells; > 0: local solves in the fixed point (begin_local)
  bool initial_pressure_hydrostatic = false;  // initial.pressure = "hydrostatic"
  rheology::Params rheo;                       // yield stress, viscosity law, fixed point
  std::array<double, 4> wall_tan_b{0, 0, 0, 0};  // Coulomb tan(alpha_b): left, right, bottom, top
  PrescribedFlow prescribed = PrescribedFlow::None;
  double omega = 0, cx = 0, cy = 0, period = 1;  // rad/s, m, m, s
};

struct StepStats {
  int visc_its = 0, pres_its = 0;  // KSP iterations: viscous (all fixed-point iterations), pressure
  int visc_polish_its = 0;         // of them, the full solve closing local solves (0: none missed)
  int fp_iters = 0;                // fixed-point iterations of eq. 31
  double fp_change = 0;            // last change of S and s_t (dimensionless)
  bool fp_converged = false;       // met fp_tol (or fp_tol_u)
  bool fp_capped = false;          // stopped at fp_max_iter without reaching fp_tol
  long long mu_i_floor_cells = 0;  // granular cells where the mu(I) viscosity is at eta_min
  long long mu_i_cap_cells = 0;    // ... and at eta_max (rheology.eta_min / eta_max)
  bool redistanced = false;
  bool pres_fallback = false;      // the pressure solve was made again with GMRES (CG broke down)
};

class Stepper {
 public:
  Stepper(const Grid& g, const PhysicsConfig& cfg);
  ~Stepper();

  // Properties at t = 0 and the initial (hydrostatic-like) pressure of the fluid at rest.
  void initialize(State& s);
  // Instead of initialize() when s was loaded from a checkpoint (rho and eta included):
  // rebuilds what the stepper keeps between steps from s alone (phase, nodal viscosity, the
  // pressure matrix), without touching s. Everything else the stepper holds is rebuilt inside each
  // step (kappa, kappa_b, the viscous matrix, the Anderson history), so the next step is
  // bit-for-bit the step the uninterrupted run takes.
  void resume(State& s);
  // Advances s from t^n to t^n + dt.
  StepStats step(State& s, double dt);
  // Whether the step from s.t of length dt redistances phi: every redistance_every steps, or,
  // with redistance_interval > 0, in the step that reaches each multiple of the interval.
  bool redistance_due(const State& s, double dt) const;
  // initial.stress = "equilibrium", after initialize(): pseudo-steps of length dt from rest,
  // each one's velocity discarded (phi, t and the step count put back) and its S, s_t and p
  // kept, until speed(s) after a step (the granular speed: the air, whose density varies across
  // the interface band, has no equilibrium at rest) is below tol (m/s) or after max_steps.
  // Returns the pseudo-steps taken and the speed after the last one. Collective.
  std::pair<int, double> equilibrate(State& s, double dt, int max_steps, double tol,
                                     const std::function<double(const State&)>& speed);
  // rho, eta (cells) and eta at the nodes from phi (step 2); public for diagnostics and tests.
  void update_properties(State& s);
  // Sets s.vel to the prescribed velocity at time t (level-set-only runs).
  void prescribe_velocity(State& s, double t);

  Vec eta_node() const { return eta_node_; }
  Vec kappa() const { return kappa_; }
  // Lengths (m) of granular contact sticking / sliding on each frictional wall (left, right,
  // bottom, top), from the last step's s_t and kappa_b; zeros without wall friction. Collective.
  momentum::Predictor::WallContact wall_contact(const State& s) const;
  // Output fields: |D(u^n)| (1/s), |S| and the yielded mask (1 where |S| >= 1 - 1e-12, i.e. the
  // material flows; 0 where rigid), all cell centred (dm_cell).
  void derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded);
  const PhysicsConfig& config() const { return cfg_; }

 private:
  const Grid& g_;
  PhysicsConfig cfg_;
  std::unique_ptr<levelset::Advector> advector_;
  std::unique_ptr<levelset::Redistancer> redistancer_;
  std::unique_ptr<momentum::Predictor> predictor_;
  std::unique_ptr<projection::Projector> projector_;
  double assembled_a0dt_ = -1;  // a0/dt of the assembled viscous matrix, 1/s
  bool plastic_ = false;
  long long mu_i_floor_cells_ = 0, mu_i_cap_cells_ = 0;
  bool fp_monitor_ = false;
  PetscReal reset_ratio_ = 1.0;
  Vec rhs0_mon_ = nullptr;  // previous u~ for -fp_monitor
  Vec gS_ = nullptr, gW_ = nullptr;
  // The node copy of S (rheology.plastic_grid = "cell_node"): D(u~) there, S_node^n, G(x).
  Vec Dn_ = nullptr, Sn_n_ = nullptr, gSn_ = nullptr;  // G(x) of the fixed point: projected S and s_t
  std::unique_ptr<class Anderson> anderson_;  // a yield stress or wall friction: the fixed point of eq. 31 runs
  Vec kappa_ = nullptr, kappa_b_ = nullptr, D_ = nullptr, S_n_ = nullptr, sw_n_ = nullptr,
      rhs0_ = nullptr, p_hyd_ = nullptr, gran_ = nullptr, eta_s_ = nullptr;
  // rho and eta for the augmentation r of the cell projection: their minimum over the cell and
  // its 8 neighbours (rheology::neighbourhood_min), refreshed with the properties.
  Vec rho_r_ = nullptr, eta_r_ = nullptr;
  void update_yield(State& s);
  void mu_i_viscosity(State& s);
  // The entries of (S, s_t[, S_node]) that can be non-zero in this step's fixed point, as local
  // indices per block (Anderson::set_active): S where kappa > 0 or S^n != 0, s_t on the wall
  // faces (or where s_t^n != 0), the node copy everywhere.
  std::vector<std::vector<PetscInt>> anderson_active(bool node) const;
  // Limits the plastic terms and D(u~) of this step's fixed point to the cells with kappa > 0
  // or phi < 0, widened by 2 cells (Predictor::set_plastic_region); collective.
  void set_plastic_region(const State& s);
  // The rows of a dm_vel global Vec (local indices, ascending) of the cells with kappa > 0 or
  // phi < 0 widened by margin cells (a box in the cell indices), for Predictor::begin_local.
  std::vector<PetscInt> local_rows(const State& s, int margin) const;
  Vec eta_node_ = nullptr, rhs_ = nullptr, u_tilde_ = nullptr, lphi_ = nullptr;
};

}  // namespace gf
