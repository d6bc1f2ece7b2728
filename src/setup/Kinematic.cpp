#include "setup/Kinematic.hpp"

#include "core/Error.hpp"
#include "levelset/LevelSet.hpp"
#include "levelset/PrescribedFlow.hpp"
#include "rheology/Rheology.hpp"

namespace gf {

namespace {
interface::Config interface_config(const KinematicConfig& k) {
  interface::Config c;
  c.method = k.method;
  c.redistance = k.redistance;
  c.props = levelset::Props{k.rho_air, k.rho_gran, k.eta_air, k.eta_gran, k.eps};
  c.normals = k.normals;
  return c;
}
}  // namespace

KinematicStepper::KinematicStepper(const Grid& g, const KinematicConfig& cfg)
    : g_(g), cfg_(cfg), interface_(g, interface_config(cfg)) {
  traits_.solves_momentum = false;
  traits_.two_phase = true;
  traits_.eps = cfg_.eps;
  traits_.gravity = {0.0, 0.0};
  traits_.returns_to_start = true;
  traits_.conservative = interface_.conservative();
  traits_.rho_air = cfg_.rho_air;
  traits_.rho_gran = cfg_.rho_gran;
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &kappa_));
  GF_PETSC(VecSet(kappa_, 0.0));
}

KinematicStepper::~KinematicStepper() { VecDestroy(&kappa_); }

void KinematicStepper::prescribe_velocity(State& s, double t) const {
  if (cfg_.flow == PrescribedFlow::Rotation)
    levelset::rotation_velocity(g_, s.vel, cfg_.omega, cfg_.cx, cfg_.cy);
  else
    levelset::single_vortex_velocity(g_, s.vel, t, cfg_.period);
}

void KinematicStepper::initialize(State& s) {
  // The properties of the initial phi, for the diagnostics (kinetic energy, VTK); a kinematic
  // run does not update them.
  interface_.initialize(s);
  interface_.properties(s, s.rho, s.eta, nullptr);
  prescribe_velocity(s, s.t);
}

StepStats KinematicStepper::step(State& s, double dt) {
  StepStats st;
  // The velocity at the middle of the step, then eq. 26 and the redistancing.
  prescribe_velocity(s, s.t + 0.5 * dt);
  st.redistanced = interface_.advance(s, s.vel, dt);
  s.dt_old = s.dt;
  s.dt = dt;
  s.t += dt;
  ++s.step;
  return st;
}

void KinematicStepper::derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) {
  GF_PETSC(VecSet(Dnorm, 0.0));
  rheology::tensor_norm(g_, s.S, Snorm);
  rheology::yielded_mask(g_, Snorm, kappa_, yielded);
}

}  // namespace gf
