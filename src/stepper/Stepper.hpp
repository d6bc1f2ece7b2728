#pragma once
// One time step of the two-phase model, in the order of the paper (sections 3.1-3.3):
//   1. phi^{n+1} from eq. 26 with the solenoidal u^n (WENO5 + TVD-RK3), redistanced when due
//      (levelset/Interface.hpp);
//   2. the state derived from phi^{n+1} and p^n: rho^{n+1}, eta^{n+1} (eq. 25, harmonic means with
//      the height fraction; the mu(I) viscosity of eq. 11), the yield stress kappa (eqs. 15,
//      18-19), the wall yield kappa_b (eq. 22) and the granular mask (update_derived);
//   3. prediction (eq. 31): explicit terms, then one implicit viscous solve for u~, or, with a
//      yield stress or wall friction, the fixed point of eq. 31 (momentum/FixedPoint.hpp);
//   4. projection (eq. 32): u^{n+1}, p^{n+1}.
// This is the only code that calls all the physics layers; diagnostics and output live in sim/.
#include <array>
#include <functional>
#include <memory>
#include <utility>

#include "boundary/Boundary.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "interface/Interface.hpp"
#include "momentum/FixedPoint.hpp"
#include "momentum/NewtonPlastic.hpp"
#include "momentum/Momentum.hpp"
#include "rheology/Rheology.hpp"
#include "stepper/TimeStepper.hpp"

namespace gf {
namespace projection {
class Projector;
}

struct PhysicsConfig {
  double rho_gran = 1550, eta_gran = 0.5;  // kg/m^3, Pa s
  double rho_air = 1.2, eta_air = 1.8e-5;  // kg/m^3, Pa s
  std::array<double, 2> gravity{0.0, -9.81};  // m/s^2
  bool levelset = true;       // false: one phase (the "granular" values everywhere)
  double eps = 0;             // m, half-width of the smeared Heaviside (eq. 25)
  levelset::RedistanceConfig redistance;
  Boundaries bc;
  double pressure_rtol = 1e-10, viscous_rtol = 1e-10;
  bool initial_pressure_hydrostatic = false;  // initial.pressure = "hydrostatic"
  rheology::Params rheo;                       // yield stress, viscosity law, fixed point
  momentum::FixedPointOptions fp;              // acceleration, monitor, local solves
  bool newton = false;                         // rheology.solver = "newton"
  bool newton_coupled = false;                 // ... with the pressure (rheology.newton_pressure)
  momentum::ExactStepOptions newton_opt;       // its tolerance (tol) and cap (max_outer)
  // m: the yield stress and the Coulomb wall friction act where phi < yield_support (0: the
  // granular phase, the paper; eps: wherever eq. 25 gives granular mass,
  // rheology.yield_support = "mass").
  double yield_support = 0;
  // interface.method (interface/Interface.hpp): the paper's level set, or CLSVOF with the
  // momentum transported by the mass fluxes of the volume fraction.
  interface::Method interface_method = interface::Method::LevelSet;
  vof::Normals normals = vof::Normals::LevelSet;
  std::array<double, 4> wall_tan_b{0, 0, 0, 0};  // Coulomb tan(alpha_b): left, right, bottom, top
  boundary::SideWallParams side;  // the side walls of a channel (boundary.side_walls)
  boundary::GateParams gate;      // the gate of the dam break (boundary.gate)
};

class Stepper : public TimeStepper {
 public:
  Stepper(const Grid& g, const PhysicsConfig& cfg);
  ~Stepper() override;

  const ModelTraits& traits() const override { return traits_; }
  // Properties at t = 0 and the initial (hydrostatic-like) pressure of the fluid at rest.
  void initialize(State& s) override;
  // rho and eta come from the checkpoint; rebuilds the phase, the nodal viscosity of a one-phase
  // run and the pressure matrix. Everything else the stepper holds is rebuilt inside each step
  // (kappa, kappa_b, the viscous matrix, the Anderson history).
  void resume(State& s) override;
  StepStats step(State& s, double dt) override;
  void derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) override;
  Vec kappa() const override { return kappa_; }
  boundary::WallContact wall_contact(const State& s) const override;
  // initial.stress = "equilibrium", after initialize(): pseudo-steps of length dt from rest,
  // each one's velocity discarded (phi, t and the step count put back) and its S, s_t and p
  // kept, until speed(s) after a step (the granular speed: the air, whose density varies across
  // the interface band, has no equilibrium at rest) is below tol (m/s) or after max_steps.
  // Returns the pseudo-steps taken and the speed after the last one. Collective.
  std::pair<int, double> equilibrate(State& s, double dt, int max_steps, double tol,
                                     const std::function<double(const State&)>& speed) override;

 private:
  const Grid& g_;
  PhysicsConfig cfg_;
  ModelTraits traits_;
  std::unique_ptr<interface::Interface> interface_;
  std::unique_ptr<momentum::Predictor> predictor_;
  std::unique_ptr<projection::Projector> projector_;
  std::unique_ptr<momentum::FixedPoint> fixed_point_;  // a yield stress or wall friction
  std::unique_ptr<momentum::NewtonPlastic> newton_;    // ... solved by Newton (rheology.solver)
  std::unique_ptr<boundary::Gate> gate_;  // boundary.gate (null: none)
  bool gate_hold_ = false;                // equilibrate(): the gate stays where it is at t = 0
  double assembled_a0dt_ = -1;  // a0/dt of the assembled viscous matrix, 1/s
  long long mu_i_floor_cells_ = 0, mu_i_cap_cells_ = 0;
  Vec kappa_ = nullptr, kappa_b_ = nullptr, D_ = nullptr, rhs0_ = nullptr, p_hyd_ = nullptr,
      gran_ = nullptr, eta_s_ = nullptr, support_ = nullptr, granular_ = nullptr;
  // rho and eta for the augmentation r of the cell projection: their minimum over the cell and
  // its 8 neighbours (rheology::neighbourhood_min), refreshed with the properties.
  Vec rho_r_ = nullptr, eta_r_ = nullptr;
  Vec eta_node_ = nullptr, u_tilde_ = nullptr;
  Vec u_star_ = nullptr;  // clsvof: u^n transported with the mass fluxes (Predictor::transport)
  Vec u_half_ = nullptr;  // clsvof: the velocity that carries the mass, u^{n+1/2} extrapolated
  Vec force_ = nullptr, zero_cell_ = nullptr, zero_vel_ = nullptr;  // dissipation()
  // The side walls (boundary/SideWalls.hpp): their friction bound k (N/m^3) and the air's drag
  // (Pa s/m^2), both per cell; null without side walls.
  Vec kappa_side_ = nullptr, drag_ = nullptr;
  // The granular fraction of each cell (1 - H_eps(phi), or c; 1 in a one-phase run) into gran_.
  void granular_fraction(State& s);
  // Whether the momentum is transported with the mass fluxes of the volume fraction.
  bool consistent() const { return interface_ && interface_->conservative(); }
  // The phase the Coulomb walls and the granular mask read (phi's sign convention).
  Vec phase(State& s) { return interface_ ? interface_->phase(s) : s.phi.vec(); }

  // Step 1: the interface to t^{n+1} (phi, and with clsvof the volume fraction).
  void advance_interface(State& s, double dt, bool first, StepStats& st);
  // Step 3's explicit part into rhs0_ (with clsvof after the momentum's transport into u_star_).
  void explicit_terms(State& s, const momentum::TimeCoeffs& c, double dt);
  // Step 2: everything the coming step derives from phi^{n+1}, p^n and u^n. props_change: the
  // properties change (two phases, mu(I), the first step).
  void update_derived(State& s, bool props_change);
  // rho, eta (cells) and eta at the nodes from phi, and the mu(I) viscosity.
  void update_properties(State& s);
  void mu_i_viscosity(State& s);
  // kappa (eqs. 15, 18-19) from phi^{n+1} and p^n, kappa_b (eq. 22) from the state at t^n, and
  // the granular mask of the fixed point.
  void update_yield(State& s);
  // Step 3 after the explicit terms: u~ from one viscous solve or the fixed point of eq. 31.
  void predict(State& s, double a0dt, double dt, StepStats& st);
  // Step 4: the projection, then t^{n+1}.
  void project(State& s, bool props_change, double a0, double dt, StepStats& st);
  // The energy the step dissipated (StepStats::diss_*): the power of the viscous operator and
  // of the plastic and wall-friction forces of eq. 31 at u^{n+1}, times dt.
  void dissipation(State& s, double dt, StepStats& st);
};

}  // namespace gf
