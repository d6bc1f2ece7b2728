#include "stepper/Stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/Error.hpp"
#include "core/Profile.hpp"
#include "levelset/LevelSet.hpp"
#include "projection/Projection.hpp"

namespace gf {

Stepper::Stepper(const Grid& g, const PhysicsConfig& cfg) : g_(g), cfg_(cfg) {
  if (cfg_.levelset) {
    interface::Config ic;
    ic.method = cfg_.interface_method;
    ic.redistance = cfg_.redistance;
    ic.props = levelset::Props{cfg_.rho_air, cfg_.rho_gran, cfg_.eta_air, cfg_.eta_gran, cfg_.eps};
    ic.yield_support = cfg_.yield_support;
    ic.normals = cfg_.normals;
    interface_ = std::make_unique<interface::Interface>(g, ic);
  }
  predictor_ = std::make_unique<momentum::Predictor>(g, cfg_.bc, cfg_.viscous_rtol, cfg_.side);
  projector_ = std::make_unique<projection::Projector>(g, cfg_.pressure_rtol);
  predictor_->walls().set_friction(cfg_.wall_tan_b,
                                   interface_ ? interface_->phase_offset() : cfg_.yield_support);
  if (cfg_.gate.x > 0) {
    gate_ = std::make_unique<boundary::Gate>(g, cfg_.gate);
    predictor_->set_gate(gate_.get());
    projector_->set_gate(gate_.get());
  }
  const boundary::SideWalls& side = predictor_->side_walls();
  if (side.active()) GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &kappa_side_));
  if (side.air_drag()) {
    GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &drag_));
    predictor_->set_drag(drag_);
  }
  const bool plastic = cfg_.rheo.active() || predictor_->walls().active() || side.active();
  if (plastic)
    fixed_point_ = std::make_unique<momentum::FixedPoint>(g, *predictor_, cfg_.rheo, cfg_.fp);
  if (plastic && cfg_.newton)
    newton_ = std::make_unique<momentum::NewtonPlastic>(g, *predictor_, cfg_.rheo,
                                                        cfg_.newton_opt, cfg_.newton_coupled);
  for (Vec* v : {&kappa_, &p_hyd_, &gran_, &eta_s_, &rho_r_, &eta_r_, &support_, &granular_,
                 &eta_node_})
    GF_PETSC(DMCreateGlobalVector(g.dm_cell(), v));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &D_));
  for (Vec* v : {&kappa_b_, &rhs0_, &u_tilde_, &u_star_, &u_half_, &force_, &zero_vel_})
    GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &zero_cell_));
  GF_PETSC(VecSet(zero_vel_, 0.0));
  GF_PETSC(VecSet(zero_cell_, 0.0));
  GF_PETSC(VecSet(kappa_, 0.0));
  GF_PETSC(VecSet(kappa_b_, 0.0));
  traits_.solves_momentum = true;
  traits_.two_phase = cfg_.levelset;
  traits_.eps = cfg_.eps;
  traits_.gravity = cfg_.gravity;
  traits_.node_copy = cfg_.rheo.node_copy;
  traits_.newton = plastic && cfg_.newton;
  traits_.side_walls = side.active();
  traits_.conservative = consistent();
  traits_.rho_air = cfg_.rho_air;
  traits_.rho_gran = cfg_.rho_gran;
}

Stepper::~Stepper() {
  for (Vec* v : {&eta_node_, &u_tilde_, &u_star_, &u_half_, &force_, &zero_cell_, &zero_vel_, &kappa_, &kappa_b_, &D_, &rhs0_, &p_hyd_, &gran_,
                 &eta_s_, &rho_r_, &eta_r_, &support_, &granular_, &kappa_side_, &drag_})
    VecDestroy(v);
}

// ------------------------------------------------------------------------------ the step

StepStats Stepper::step(State& s, double dt) {
  StepStats st;
  const bool first = (s.step == 0);
  // The gate where it is at the end of the step (its covered faces and nodes for the viscous
  // and pressure operators of this step).
  if (gate_) gate_->set_time(gate_hold_ ? 0.0 : s.t + dt);
  // 1. The interface: the level set of eq. 26 with the solenoidal u^n, redistanced when due; or
  //    the conservative volume fraction with phi rebuilt from it (interface/Interface.hpp).
  advance_interface(s, dt, first, st);
  // 2. The derived state: rho^{n+1}, eta^{n+1} (constant in a one-phase run: then the
  //    matrices, and the preconditioners built on them, are kept from step to step), kappa,
  //    kappa_b and the granular mask.
  const bool props_change = cfg_.levelset || first ||
                            cfg_.rheo.viscosity == rheology::Viscosity::MuI || gate_ != nullptr;
  update_derived(s, props_change);
  // 3. Prediction, eq. 31 (kappa = 0: Newtonian phases): the explicit terms, then the implicit
  //    viscous solve or the fixed point.
  const auto c = consistent() ? momentum::TimeCoeffs::transported()
                              : momentum::TimeCoeffs::make(dt, s.dt, first);
  if (props_change || c.a0 / dt != assembled_a0dt_) {
    prof::Scope ps(prof::Assemble);
    predictor_->assemble(s.rho, s.eta, eta_node_, c.a0 / dt);
    assembled_a0dt_ = c.a0 / dt;
  }
  explicit_terms(s, c, dt);
  GF_PETSC(VecCopy(s.vel, u_tilde_));  // initial guess
  predict(s, c.a0 / dt, dt, st);
  // 4. Projection, eq. 32: u^{n+1}, p^{n+1}.
  project(s, props_change, c.a0, dt, st);
  dissipation(s, dt, st);
  return st;
}

void Stepper::advance_interface(State& s, double dt, bool first, StepStats& st) {
  if (!cfg_.levelset) return;
  if (!consistent()) {
    st.redistanced = interface_->advance(s, s.vel, dt);
    return;
  }
  // The volume fraction is carried by u^{n+1/2} = u^n + dt/(2 dt_old) (u^n - u^{n-1}), also
  // solenoidal. The mass must move with the velocity of the middle of the step for the
  // potential energy it releases to match the work of gravity on u^{n+1} in the prediction:
  // with u^n it lags by half a step, and a falling column gains kinetic energy beyond the
  // potential energy it releases (by dt/t: the dam break's first outputs at +20 % with
  // dt = 1e-3 s).
  GF_PETSC(VecCopy(s.vel, u_half_));
  if (!first && s.dt > 0) {
    const double w = 0.5 * dt / s.dt;
    GF_PETSC(VecAXPBYPCZ(u_half_, -w, w, 1.0, s.vel_old, s.vel));
  }
  st.redistanced = interface_->advance(s, u_half_, dt);
}

void Stepper::explicit_terms(State& s, const momentum::TimeCoeffs& c, double dt) {
  if (!consistent()) {
    // BDF2 history, AB2 convection, -grad p^n, gravity.
    predictor_->explicit_rhs(s.vel, s.vel_old, s.p, s.rho, c, dt, cfg_.gravity, rhs0_);
    return;
  }
  // With the volume fraction, the momentum is first transported with its mass fluxes (u*: the
  // convection, consistent with rho^n -> rho^{n+1}) and the step is BDF1 from it.
  const vof::Advector& sw = interface_->sweeps();
  const momentum::MassSweeps m{sw.flux(), sw.c_start(), s.frac, sw.cc(), cfg_.rho_air,
                               cfg_.rho_gran};
  predictor_->transport(u_half_, s.vel, m, dt, u_star_);
  predictor_->explicit_rhs(u_star_, s.vel_old, s.p, s.rho, c, dt, cfg_.gravity, rhs0_);
}

void Stepper::dissipation(State& s, double dt, StepStats& st) {
  const double cell = g_.hx() * g_.hy();
  st.diss_viscous = dt * predictor_->viscous_power(s.vel, s.rho);
  if (!fixed_point_) return;
  // The plastic forces of eq. 31 (Predictor::add_plastic) split in their two parts: the
  // divergence of kappa S (no wall yield) and the Coulomb tractions -kappa_b s_t (no kappa).
  // The power they dissipate is minus their work on u^{n+1}.
  const Vec S_node = cfg_.rheo.node_copy ? s.S_node.vec() : nullptr;
  PetscScalar w;
  GF_PETSC(VecSet(force_, 0.0));
  predictor_->add_plastic(kappa_, s.S, zero_vel_, s.s_wall, force_, S_node);
  GF_PETSC(VecDot(s.vel, force_, &w));
  st.diss_plastic = -dt * w * cell;
  if (predictor_->walls().active()) {
    GF_PETSC(VecSet(force_, 0.0));
    predictor_->add_plastic(zero_cell_, s.S, kappa_b_, s.s_wall, force_, S_node);
    GF_PETSC(VecDot(s.vel, force_, &w));
    st.diss_friction = -dt * w * cell;
  }
  // The side walls' friction: the same power as -I^T (k s) . u on the faces (the pair is
  // adjoint, boundary/SideWalls.hpp).
  if (kappa_side_)
    st.diss_friction -= dt * predictor_->side_walls().power(s.vel, kappa_side_, s.s_side);
}

void Stepper::predict(State& s, double a0dt, double dt, StepStats& st) {
  prof::Scope pfp(prof::FixedPoint);
  if (!fixed_point_) {
    prof::Scope ps(prof::ViscousSolve);
    st.visc_its = predictor_->solve(rhs0_, u_tilde_);
    return;
  }
  const double theta = std::min(0.5, cfg_.rheo.theta_per_dt * dt);
  const momentum::PlasticInputs in{kappa_, kappa_b_, rho_r_, eta_r_, granular_, kappa_side_};
  // rheology.solver = "newton": the step's plastic problem with theta = 0, solved exactly. Its
  // Newton iteration starts from the last step's prediction u~^n rather than u^n: with S^n,
  // that is the point where the last step's problem was solved, so that its first
  // linearisation finds the last step's rigid and yielded cells (u^n, after the projection,
  // has another strain rate). The answer does not depend on the start; the iterations do: case A
  // at n = 16 to 0.6 s, 5,040 instead of 7,981; at n = 32 to 0.3 s, 7,123 instead of 8,019.
  if (newton_ && s.step > 0) GF_PETSC(VecCopy(s.vel_pred, u_tilde_));
  const momentum::FixedPointStats r =
      newton_ ? newton_->solve(s, in, rhs0_, u_tilde_, a0dt)
              : fixed_point_->solve(s, in, rhs0_, u_tilde_, a0dt, theta, s.step + 1);
  if (newton_) GF_PETSC(VecCopy(u_tilde_, s.vel_pred));
  st.visc_its = r.visc_its;
  st.visc_polish_its = r.visc_polish_its;
  st.fp_iters = r.iters;
  st.fp_change = r.change;
  st.fp_converged = r.converged;
  st.fp_capped = !r.converged;
  st.mu_i_floor_cells = mu_i_floor_cells_;
  st.mu_i_cap_cells = mu_i_cap_cells_;
}

void Stepper::project(State& s, bool props_change, double a0, double dt, StepStats& st) {
  if (newton_ && newton_->coupled()) {
    // The exact plastic step solved the pressure with the velocity: u~ is u^{n+1} already.
    projector_->add_increment(newton_->psi(), s.p);
  } else {
    {
      prof::Scope ps(prof::Assemble);
      if (props_change) projector_->assemble(s.rho);
    }
    prof::Scope ps(prof::Pressure);
    st.pres_its = projector_->project(u_tilde_, s.p, s.rho, a0, dt);
    st.pres_fallback = projector_->fell_back();
  }
  GF_PETSC(VecCopy(s.vel, s.vel_old));
  GF_PETSC(VecCopy(u_tilde_, s.vel));
  s.dt_old = s.dt;
  s.dt = dt;
  s.t += dt;
  ++s.step;
}

// ------------------------------------------------------------------------ derived state

void Stepper::update_derived(State& s, bool props_change) {
  prof::Scope ps(prof::Properties);
  if (props_change) {
    update_properties(s);
    predictor_->walls().set_phase(phase(s));
    // A sharp density: the wall load includes the wall cells' own lower half (Coulomb.hpp).
    if (consistent() && predictor_->walls().active())
      predictor_->walls().set_wall_weight(s.rho, cfg_.gravity);
  }
  if (fixed_point_) update_yield(s);
}

void Stepper::update_properties(State& s) {
  if (cfg_.levelset) {
    interface_->properties(s, s.rho, s.eta, eta_node_);  // eq. 25 and the harmonic means
  } else {
    GF_PETSC(VecSet(s.rho, cfg_.rho_gran));
    GF_PETSC(VecSet(s.eta, cfg_.eta_gran));
    GF_PETSC(VecSet(eta_node_, cfg_.eta_gran));
  }
  if (cfg_.rheo.viscosity == rheology::Viscosity::MuI) mu_i_viscosity(s);
  if (drag_) {  // the air's Navier slip on the side walls, in the next assembled operator
    granular_fraction(s);
    predictor_->side_walls().drag(gran_, drag_);
  }
  if (fixed_point_) {
    rheology::neighbourhood_min(g_, s.rho, rho_r_);
    rheology::neighbourhood_min(g_, s.eta, eta_r_);
  }
}

// The mu(I) viscosity of eq. 11 from |D(u^n)| and p^n (explicit in the step, so that the
// viscous operator stays linear and fixed during the fixed point), then the same harmonic
// means with the air as for a constant eta_s.
void Stepper::mu_i_viscosity(State& s) {
  predictor_->strain_rate(s.vel, s.eta, D_);
  rheology::mu_i_viscosity(g_, cfg_.rheo, D_, s.p, cfg_.rho_gran, eta_s_);
  {
    // Granular cells where the declared bounds act (reported in summary.json).
    const Box& b = g_.box();
    const PetscScalar **es, **ph;
    const Vec phv = phase(s);
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), eta_s_, &es));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), phv, &ph));
    long long at_floor = 0, at_cap = 0;
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i)
        if (ph[j][i] < 0 || !cfg_.levelset) {
          if (es[j][i] <= cfg_.rheo.eta_min) ++at_floor;
          if (es[j][i] >= cfg_.rheo.eta_max) ++at_cap;
        }
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), phv, &ph));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), eta_s_, &es));
    mu_i_floor_cells_ = g_.sum(at_floor);
    mu_i_cap_cells_ = g_.sum(at_cap);
  }
  if (cfg_.levelset)
    interface_->mix_viscosity(s, cfg_.eta_air, eta_s_, s.eta, eta_node_);
  else
    levelset::mix_viscosity(g_, nullptr, cfg_.eta_air, eta_s_, s.eta, eta_node_);
}

void Stepper::update_yield(State& s) {
  const bool hydrostatic = cfg_.rheo.yield == rheology::Yield::Hydrostatic;
  const bool side_hyd = kappa_side_ && cfg_.side.hydrostatic;
  // With the air's side-wall drag, update_properties has just filled gran_ from the same phase
  // (the drag exists only in two-phase runs, whose properties change every step).
  if ((hydrostatic || kappa_side_) && !drag_) granular_fraction(s);
  if (hydrostatic || side_hyd) {
    // Granular fraction of each cell (1 - H_eps(phi), or c), weighed by eq. 15.
    const double gabs = std::hypot(cfg_.gravity[0], cfg_.gravity[1]);
    // The weight of the column above acts along the vertical axis: its y-component.
    rheology::hydrostatic_pressure(g_, gran_, cfg_.rho_gran,
                                   std::abs(cfg_.gravity[1]) > 0 ? std::abs(cfg_.gravity[1]) : gabs,
                                   p_hyd_);
  }
  if (cfg_.levelset)
    interface_->yield_support(s, support_);
  else
    levelset::yield_support(g_, s.phi, cfg_.yield_support, support_);
  rheology::yield_stress(g_, cfg_.rheo, support_, s.p, p_hyd_, kappa_);
  // The side walls' friction bound, frozen for the step: their normal stress is K p^n (the plane
  // model has no out-of-plane deviatoric stress), or K p_hyd (the overburden; SideWalls.hpp).
  if (kappa_side_)
    predictor_->side_walls().yield(gran_, support_, side_hyd ? p_hyd_ : s.p.vec(), kappa_side_);
  // The wall yield from the state at t^n; refreshed in every fixed-point iteration.
  predictor_->strain_rate(s.vel, s.eta, D_);
  predictor_->walls().yield(s.p, s.S, kappa_, D_, s.eta, kappa_b_);
  // The granular mask of the fixed point: the cells with kappa > 0 or granular (phi < 0; with
  // the volume fraction, any granular mass).
  const PetscScalar *k, *ph;
  PetscScalar* m;
  PetscInt len;
  const Vec phv = phase(s);
  GF_PETSC(VecGetLocalSize(granular_, &len));
  GF_PETSC(VecGetArrayRead(kappa_, &k));
  GF_PETSC(VecGetArrayRead(phv, &ph));
  GF_PETSC(VecGetArray(granular_, &m));
  for (PetscInt c = 0; c < len; ++c) m[c] = (k[c] > 0 || ph[c] < 0) ? -1.0 : 0.0;
  GF_PETSC(VecRestoreArray(granular_, &m));
  GF_PETSC(VecRestoreArrayRead(phv, &ph));
  GF_PETSC(VecRestoreArrayRead(kappa_, &k));
}

void Stepper::granular_fraction(State& s) {
  if (cfg_.levelset)
    interface_->granular_fraction(s, gran_);
  else
    GF_PETSC(VecSet(gran_, 1.0));
}

// --------------------------------------------------------------- start, restart, outputs

void Stepper::initialize(State& s) {
  if (gate_) gate_->set_time(0.0);  // the column behind its gate
  if (interface_) interface_->initialize(s);
  predictor_->walls().set_phase(phase(s));
  update_properties(s);
  // Initial pressure of the fluid at rest: project the field u* = g (one unit of time, a0 = 1)
  // so that p^0 balances gravity in the sense of the discrete projection; then u = 0.
  GF_PETSC(VecSet(u_tilde_, 0.0));
  {
    Vel** u;
    const Box& b = g_.box();
    GF_PETSC(DMDAVecGetArray(g_.dm_vel(), u_tilde_, &u));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        u[j][i].u = !b.wall_u(i) ? cfg_.gravity[0] : 0.0;
        u[j][i].v = j > 0 ? cfg_.gravity[1] : 0.0;
      }
    GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), u_tilde_, &u));
  }
  GF_PETSC(VecSet(s.p, 0.0));
  projector_->assemble(s.rho);
  projector_->project(u_tilde_, s.p, s.rho, 1.0, 1.0);
  // initial.pressure = "hydrostatic": the weight of each column of cells above the point (the
  // granular column at rest behind its gate, the paper's initial static state), instead of the
  // pressure of a fluid released from rest. The projection above still assembles the matrix.
  if (cfg_.initial_pressure_hydrostatic)
    rheology::hydrostatic_pressure(g_, s.rho, 1.0, std::abs(cfg_.gravity[1]), s.p);
}

void Stepper::resume(State& s) {
  if (gate_) gate_->set_time(s.t);
  predictor_->walls().set_phase(phase(s));
  // rho and eta come from the checkpoint as the last step left them (with mu(I), those of that
  // step's start): recomputing them here would change the diagnostics of a restart that takes
  // no step. What else the stepper keeps between steps is rebuilt: the nodal viscosity of a
  // one-phase run (constant; mu(I) rewrites the interior nodes every step), the pressure matrix
  // (assembled only at the first step of a one-phase run), and the viscous matrix at the next
  // step since assembled_a0dt_ is unset.
  if (!cfg_.levelset) GF_PETSC(VecSet(eta_node_, cfg_.eta_gran));
  projector_->assemble(s.rho);
  assembled_a0dt_ = -1;
}

std::pair<int, double> Stepper::equilibrate(State& s, double dt, int max_steps, double tol,
                                            const std::function<double(const State&)>& measure) {
  Vec phi0, c0;
  GF_PETSC(VecDuplicate(s.phi, &phi0));
  GF_PETSC(VecCopy(s.phi, phi0));
  GF_PETSC(VecDuplicate(s.frac, &c0));
  GF_PETSC(VecCopy(s.frac, c0));
  double speed = std::numeric_limits<double>::infinity();
  int k = 0;
  // The pseudo-steps keep the case's relaxation theta of eq. 31. At the equilibrium S = S^n and
  // theta (S^n - S) vanishes, so theta does not choose it, but it sets the way there: the
  // granular speed after a pseudo-step falls by about 1 - theta per step (0.99 at theta =
  // 10 dt, dt = 1e-3 s); with theta = 0.5 the speeds are larger and do not fall steadily
  // (measured on cases/verify/dp_pile.toml).
  gate_hold_ = true;  // the pseudo-steps hold the column where t = 0 has its gate
  try {
    for (k = 1; k <= max_steps; ++k) {
      step(s, dt);
      speed = measure(s);
      // From rest (u^n = 0) the transport leaves phi (and c) as they were; a redistancing or
      // the rebuild of phi from c would not.
      GF_PETSC(VecCopy(phi0, s.phi));
      GF_PETSC(VecCopy(c0, s.frac));
      GF_PETSC(VecSet(s.vel, 0.0));
      GF_PETSC(VecSet(s.vel_old, 0.0));
      s.t = 0;
      s.dt = s.dt_old = 0;
      s.step = 0;
      if (speed < tol) break;
    }
  } catch (...) {
    gate_hold_ = false;
    VecDestroy(&phi0);
    VecDestroy(&c0);
    throw;
  }
  gate_hold_ = false;
  if (gate_) gate_->set_time(0.0);
  VecDestroy(&phi0);
  VecDestroy(&c0);
  update_properties(s);
  return {std::min(k, max_steps), speed};
}

boundary::WallContact Stepper::wall_contact(const State& s) const {
  boundary::WallContact wc;
  if (predictor_->walls().active()) wc = predictor_->walls().contact(s.s_wall, kappa_b_);
  if (kappa_side_) wc.side = predictor_->side_walls().contact(kappa_side_, s.s_side, gran_);
  if (gate_) wc.gate_bottom_m = gate_->bottom();
  return wc;
}

void Stepper::derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) {
  predictor_->strain_rate(s.vel, s.eta, D_);
  rheology::tensor_norm(g_, D_, Dnorm);
  rheology::tensor_norm(g_, s.S, Snorm);
  rheology::yielded_mask(g_, Snorm, kappa_, yielded);
}

}  // namespace gf
