#include "stepper/Stepper.hpp"

#include "core/Error.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "momentum/Momentum.hpp"
#include "projection/Projection.hpp"

namespace gf {

Stepper::Stepper(const Grid& g, const PhysicsConfig& cfg) : g_(g), cfg_(cfg) {
  if (cfg_.levelset) {
    advector_ = std::make_unique<levelset::Advector>(g);
    redistancer_ =
        std::make_unique<levelset::Redistancer>(g, cfg_.redistance_iters, cfg_.redistance_cfl);
  }
  if (cfg_.prescribed == PrescribedFlow::None) {
    predictor_ = std::make_unique<momentum::Predictor>(g, cfg_.bc, cfg_.viscous_rtol);
    projector_ = std::make_unique<projection::Projector>(g, cfg_.pressure_rtol);
  }
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &eta_node_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &rhs_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &u_tilde_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lphi_));
}

Stepper::~Stepper() {
  for (Vec* v : {&eta_node_, &rhs_, &u_tilde_, &lphi_}) VecDestroy(v);
}

void Stepper::update_properties(State& s) {
  if (!cfg_.levelset) {
    GF_PETSC(VecSet(s.rho, cfg_.rho_gran));
    GF_PETSC(VecSet(s.eta, cfg_.eta_gran));
    GF_PETSC(VecSet(eta_node_, cfg_.eta_gran));
    return;
  }
  const levelset::Props pr{cfg_.rho_air, cfg_.rho_gran, cfg_.eta_air, cfg_.eta_gran, cfg_.eps};
  levelset::update_properties(g_, s.phi, pr, s.rho, s.eta);
  // Shear stresses live at the nodes: their viscosity is the harmonic mean with the height
  // fraction of the dual cell around the node (section 3.1).
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), s.phi, INSERT_VALUES, lphi_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), s.phi, INSERT_VALUES, lphi_));
  const PetscScalar** phi;
  PetscScalar** en;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &phi));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), eta_node_, &en));
  const Box& b = g_.box();
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double th = levelset::height_fraction_node(b, phi, i, j);
      en[j][i] = levelset::harmonic_viscosity(th, cfg_.eta_air, cfg_.eta_gran);
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), eta_node_, &en));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &phi));
}

void Stepper::prescribe_velocity(State& s, double t) {
  if (cfg_.prescribed == PrescribedFlow::Rotation)
    levelset::rotation_velocity(g_, s.vel, cfg_.omega, cfg_.cx, cfg_.cy);
  else if (cfg_.prescribed == PrescribedFlow::SingleVortex)
    levelset::single_vortex_velocity(g_, s.vel, t, cfg_.period);
}

void Stepper::initialize(State& s) {
  update_properties(s);
  if (cfg_.prescribed != PrescribedFlow::None) {
    prescribe_velocity(s, s.t);
    return;
  }
  // Initial pressure of the fluid at rest: project the field u* = g (one unit of time, a0 = 1)
  // so that p^0 balances gravity in the sense of the discrete projection; then u = 0.
  GF_PETSC(VecSet(u_tilde_, 0.0));
  {
    Vel** u;
    const Box& b = g_.box();
    GF_PETSC(DMDAVecGetArray(g_.dm_vel(), u_tilde_, &u));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        u[j][i].u = i > 0 ? cfg_.gravity[0] : 0.0;
        u[j][i].v = j > 0 ? cfg_.gravity[1] : 0.0;
      }
    GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), u_tilde_, &u));
  }
  GF_PETSC(VecSet(s.p, 0.0));
  projector_->assemble(s.rho);
  projector_->project(u_tilde_, s.p, s.rho, 1.0, 1.0);
}

StepStats Stepper::step(State& s, double dt) {
  StepStats st;
  const bool first = (s.step == 0);
  // 1. Level set, eq. 26, advected by the solenoidal u^n.
  if (cfg_.prescribed != PrescribedFlow::None) prescribe_velocity(s, s.t + 0.5 * dt);
  if (cfg_.levelset) {
    advector_->step(s.phi, s.vel, dt);
    if (cfg_.redistance_every > 0 && (s.step + 1) % cfg_.redistance_every == 0) {
      redistancer_->run(s.phi);
      st.redistanced = true;
    }
  }
  if (cfg_.prescribed != PrescribedFlow::None) {
    s.dt_old = s.dt;
    s.dt = dt;
    s.t += dt;
    ++s.step;
    return st;
  }
  // 2. rho^{n+1}, eta^{n+1} (constant in a one-phase run: then the matrices, and the
  //    preconditioners built on them, are kept from step to step).
  const bool props_change = cfg_.levelset || first;
  if (props_change) update_properties(s);
  // 3. Prediction, eq. 31 (kappa = 0: Newtonian phases).
  const auto c = momentum::TimeCoeffs::make(dt, s.dt, first);
  if (props_change || c.a0 / dt != assembled_a0dt_) {
    predictor_->assemble(s.rho, s.eta, eta_node_, c.a0 / dt);
    assembled_a0dt_ = c.a0 / dt;
  }
  predictor_->explicit_rhs(s.vel, s.vel_old, s.p, s.rho, c, dt, cfg_.gravity, rhs_);
  GF_PETSC(VecCopy(s.vel, u_tilde_));  // initial guess
  st.visc_its = predictor_->solve(rhs_, u_tilde_);
  // 4. Projection, eq. 32.
  if (props_change) projector_->assemble(s.rho);
  st.pres_its = projector_->project(u_tilde_, s.p, s.rho, c.a0, dt);
  GF_PETSC(VecCopy(s.vel, s.vel_old));
  GF_PETSC(VecCopy(u_tilde_, s.vel));
  s.dt_old = s.dt;
  s.dt = dt;
  s.t += dt;
  ++s.step;
  return st;
}

}  // namespace gf
