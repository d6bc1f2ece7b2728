#pragma once
// What the time loop (sim/) needs of a model: one time step, its start and its restart, and the
// few facts of the model that the loop's time-step choice, diagnostics and checkpoints depend
// on. Two models implement it: the two-phase flow of the paper (stepper/Stepper.hpp) and, at the
// edge, the prescribed flows of the level-set benchmarks (setup/Kinematic.hpp), which only
// transport the interface.
#include <petscvec.h>

#include <array>
#include <functional>
#include <utility>

#include "boundary/Coulomb.hpp"
#include "fields/Fields.hpp"

namespace gf {

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
  // The energy the step dissipated, J per metre of depth (the power of each term at u^{n+1}
  // times dt): by the viscous stresses (with the slip walls), by the plastic stress kappa S
  // (eqs. 29, 31) and by the Coulomb wall friction kappa_b s_t (eqs. 22, 30).
  double diss_viscous = 0, diss_plastic = 0, diss_friction = 0;
};

// The facts of a model the time loop reads.
struct ModelTraits {
  bool solves_momentum = true;  // false: the velocity is prescribed (no gravity time-step limit)
  bool two_phase = true;        // a level set separates the granular phase from the air
  double eps = 0;               // m, half-width of the smeared Heaviside (eq. 25)
  std::array<double, 2> gravity{0.0, -9.81};  // m/s^2
  bool node_copy = false;       // the node copy of S is a prognostic field (checkpointed)
  bool side_walls = false;      // the side walls' friction direction s_side is (checkpointed)
  bool newton = false;          // the exact plastic step: State::vel_pred is (checkpointed)
  // The granular mass is the volume fraction's (interface.method = "clsvof"): State::frac is a
  // prognostic field (checkpointed) and the granular volume is sum c hx hy.
  bool conservative = false;
  double rho_air = 1.2, rho_gran = 1550;  // kg/m^3, the two phases' densities
  // The flow brings the interface back to its start (one turn of a rotation, a reversed
  // vortex): the initial level set is the exact answer, kept for the interface error.
  bool returns_to_start = false;
};

class TimeStepper {
 public:
  virtual ~TimeStepper() = default;
  virtual const ModelTraits& traits() const = 0;
  // The state at t = 0 from the initial phi and velocity (properties, initial pressure).
  virtual void initialize(State& s) = 0;
  // Instead of initialize() when s was loaded from a checkpoint: rebuilds what the model keeps
  // between steps from s alone, so that the next step is bit-for-bit the step the uninterrupted
  // run takes.
  virtual void resume(State& s) = 0;
  // Advances s from t^n to t^n + dt.
  virtual StepStats step(State& s, double dt) = 0;
  // Output fields: |D(u^n)| (1/s), |S| and the yielded mask (1 where |S| >= 1 - 1e-9 or there is
  // no yield stress: the material flows; 0 where rigid), all cell centred (dm_cell).
  virtual void derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) = 0;
  // The yield stress kappa of the last step, Pa (dm_cell).
  virtual Vec kappa() const = 0;
  // Where the granular phase sticks to / slides on the frictional walls (zeros without wall
  // friction). Collective.
  virtual boundary::WallContact wall_contact(const State& s) const { return {}; }
  // initial.stress = "equilibrium" (the two-phase flow only): see Stepper::equilibrate.
  virtual std::pair<int, double> equilibrate(State& s, double dt, int max_steps, double tol,
                                             const std::function<double(const State&)>& speed) {
    return {0, 0.0};
  }
};

}  // namespace gf
