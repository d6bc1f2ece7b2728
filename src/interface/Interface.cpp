#include "interface/Interface.hpp"

#include "core/Error.hpp"
#include "core/Profile.hpp"

namespace gf::interface {

namespace {
constexpr int kInitialRebuilds = 20;
}  // namespace

Interface::Interface(const Grid& g, const Config& cfg) : g_(g), cfg_(cfg) {
  if (conservative()) {
    phi_adv_ = std::make_unique<levelset::Advector>(g);
    vof_ = std::make_unique<vof::Advector>(g);
  } else {
    ls_ = std::make_unique<levelset::InterfaceStage>(g, cfg.redistance);
  }
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &phase_));
}

Interface::~Interface() { VecDestroy(&phase_); }

void Interface::initialize(State& s) const {
  if (!conservative()) return;
  // The rebuild takes its normals from phi itself: from the exact distance of the initial shape
  // the first rebuild moves the PLIC lines of sharp corners and thin wedges (a pile's toe: by
  // 0.24 h in the first step, c unchanged), the following ones by less and less. Repeated
  // until phi is its own rebuild, phi at rest then stays put from the first step.
  Vec prev;
  GF_PETSC(VecDuplicate(s.phi, &prev));
  for (int k = 0; k < kInitialRebuilds; ++k) {
    GF_PETSC(VecCopy(s.phi, prev));
    vof::rebuild_distance(g_, s.frac, s.phi, cfg_.normals);
    GF_PETSC(VecAXPY(prev, -1.0, s.phi));
    PetscReal d;
    GF_PETSC(VecNorm(prev, NORM_INFINITY, &d));
    if (d < 1e-12 * g_.hx()) break;
  }
  VecDestroy(&prev);
}

bool Interface::advance(State& s, Vec vel, double dt) {
  if (!conservative()) return ls_->advance(s.phi, vel, s.t, s.step, dt);  // eq. 26
  prof::Scope ps(prof::Advect);
  // CLSVOF (Sussman & Puckett 2000, section 3): c by the conservative sweeps with the normals
  // of phi^n (the distance to c^n's interface), phi by eq. 26 beside it, then phi^{n+1} rebuilt
  // as the distance to the interface of c^{n+1} with the normals of the advected phi.
  vof_->step(s.frac, vel, s.phi, dt, s.step, cfg_.normals);
  phi_adv_->step(s.phi, vel, dt);
  vof::rebuild_distance(g_, s.frac, s.phi, cfg_.normals);
  return false;
}

void Interface::properties(const State& s, Vec rho, Vec eta, Vec eta_node) const {
  const auto& pr = cfg_.props;
  if (conservative())
    vof::update_properties(g_, s.frac, pr.rho_air, pr.rho_gran, pr.eta_air, pr.eta_gran, rho,
                           eta, eta_node);
  else
    levelset::update_properties(g_, s.phi, pr, rho, eta, eta_node);  // eq. 25
}

void Interface::mix_viscosity(const State& s, double eta_air, Vec eta_gran, Vec eta,
                              Vec eta_node) const {
  if (conservative())
    vof::mix_viscosity(g_, s.frac, eta_air, eta_gran, eta, eta_node);
  else
    levelset::mix_viscosity(g_, s.phi, eta_air, eta_gran, eta, eta_node);
}

void Interface::granular_fraction(const State& s, Vec out) const {
  if (conservative())
    GF_PETSC(VecCopy(s.frac, out));
  else
    levelset::granular_fraction(g_, s.phi, cfg_.props.eps, out);
}

void Interface::yield_support(const State& s, Vec w) const {
  if (conservative())
    vof::yield_support(g_, s.frac, w);
  else
    levelset::yield_support(g_, s.phi, cfg_.yield_support, w);
}

Vec Interface::phase(const State& s) {
  if (conservative())
    vof::phase_field(g_, s.frac, phase_);
  else
    GF_PETSC(VecCopy(s.phi, phase_));
  return phase_;
}

double Interface::volume(const State& s) const {
  return conservative() ? vof::volume(g_, s.frac)
                        : levelset::granular_area(g_, s.phi, cfg_.props.eps);
}

}  // namespace gf::interface
