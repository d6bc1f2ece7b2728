#include "stepper/Stepper.hpp"

#include "core/Profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/Error.hpp"
#include "levelset/Heaviside.hpp"
#include "stepper/Anderson.hpp"
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
    redistancer_->set_wall_extrapolation(cfg_.redistance_wall_extrapolate);
  }
  if (cfg_.prescribed == PrescribedFlow::None) {
    predictor_ = std::make_unique<momentum::Predictor>(g, cfg_.bc, cfg_.viscous_rtol);
    projector_ = std::make_unique<projection::Projector>(g, cfg_.pressure_rtol);
  }
  plastic_ = cfg_.rheo.active() ||
             std::any_of(cfg_.wall_tan_b.begin(), cfg_.wall_tan_b.end(), [](double t) { return t > 0; });
  if (predictor_) predictor_->set_wall_friction(cfg_.wall_tan_b, cfg_.rheo.support);
  // -fp_monitor: print the change of every fixed-point iteration (convergence studies).
  PetscBool mon = PETSC_FALSE;
  GF_PETSC(PetscOptionsGetBool(nullptr, nullptr, "-fp_monitor", &mon, nullptr));
  fp_monitor_ = mon;
  // -fp_anderson_reset_ratio q: the Anderson history is dropped when the change grows by more
  // than the factor q from one iteration to the next (1: at any growth).
  GF_PETSC(PetscOptionsGetReal(nullptr, nullptr, "-fp_anderson_reset_ratio", &reset_ratio_, nullptr));
  // -fp_anderson m: depth of the Anderson acceleration of the fixed point (0 = plain Picard
  // iteration as in the paper). Same fixed point either way.
  PetscInt m = 5;
  GF_PETSC(PetscOptionsGetInt(nullptr, nullptr, "-fp_anderson", &m, nullptr));
  GF_PETSC(DMCreateGlobalVector(g.dm_ten(), &gS_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &gW_));
  const bool node = plastic_ && cfg_.rheo.node_copy;
  if (node)
    for (Vec* v : {&Dn_, &Sn_n_, &gSn_}) GF_PETSC(DMCreateGlobalVector(g.dm_node(), v));
  if (plastic_ && m > 0) anderson_ = std::make_unique<Anderson>(static_cast<int>(m), g.comm());
  if (fp_monitor_ || cfg_.rheo.fp_tol_u > 0) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &rhs0_mon_));
  for (Vec* v : {&kappa_, &p_hyd_, &gran_, &eta_s_, &rho_r_, &eta_r_})
    GF_PETSC(DMCreateGlobalVector(g.dm_cell(), v));
  for (Vec* v : {&D_, &S_n_}) GF_PETSC(DMCreateGlobalVector(g.dm_ten(), v));
  for (Vec* v : {&kappa_b_, &sw_n_, &rhs0_}) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
  GF_PETSC(VecSet(kappa_, 0.0));
  GF_PETSC(VecSet(kappa_b_, 0.0));
  GF_PETSC(DMCreateGlobalVector(g.dm_cell(), &eta_node_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &rhs_));
  GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &u_tilde_));
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lphi_));
}

Stepper::~Stepper() {
  for (Vec* v : {&eta_node_, &rhs_, &u_tilde_, &lphi_, &kappa_, &kappa_b_, &D_, &S_n_, &sw_n_,
                 &rhs0_, &p_hyd_, &gran_, &eta_s_, &rhs0_mon_, &gS_, &gW_, &Dn_, &Sn_n_, &gSn_,
                 &rho_r_, &eta_r_})
    VecDestroy(v);
}

void Stepper::update_properties(State& s) {
  if (!cfg_.levelset) {
    GF_PETSC(VecSet(s.rho, cfg_.rho_gran));
    GF_PETSC(VecSet(s.eta, cfg_.eta_gran));
    GF_PETSC(VecSet(eta_node_, cfg_.eta_gran));
    if (cfg_.rheo.viscosity == rheology::Viscosity::MuI && predictor_) mu_i_viscosity(s);
    if (plastic_) {
      rheology::neighbourhood_min(g_, s.rho, rho_r_);
      rheology::neighbourhood_min(g_, s.eta, eta_r_);
    }
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
  if (cfg_.rheo.viscosity == rheology::Viscosity::MuI && predictor_) mu_i_viscosity(s);
  if (plastic_) {
    rheology::neighbourhood_min(g_, s.rho, rho_r_);
    rheology::neighbourhood_min(g_, s.eta, eta_r_);
  }
}

// The mu(I) viscosity of eq. 11 from |D(u^n)| and p^n (explicit in the step, so that the
// viscous operator stays linear and fixed during the fixed point), then the same harmonic
// means with the air as for a constant eta_s.
void Stepper::mu_i_viscosity(State& s) {
  const Box& b = g_.box();
  predictor_->strain_rate(s.vel, s.eta, D_);
  {
    const PetscScalar*** d;
    const PetscScalar** pa;
    PetscScalar** es;
    GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), D_, &d));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.p, &pa));
    const PetscScalar** ph;
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), eta_s_, &es));
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.phi, &ph));
    long long at_floor = 0, at_cap = 0;  // granular cells where the declared bounds act
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        const double dxx = 0.5 * (d[j][i][0] - d[j][i][2]), dxy = d[j][i][1];
        es[j][i] = rheology::mu_i_viscosity(cfg_.rheo, std::hypot(dxx, dxy), pa[j][i], cfg_.rho_gran);
        if (ph[j][i] < 0 || !cfg_.levelset) {
          if (es[j][i] <= cfg_.rheo.eta_min) ++at_floor;
          if (es[j][i] >= cfg_.rheo.eta_max) ++at_cap;
        }
      }
    mu_i_floor_cells_ = g_.sum(at_floor);
    mu_i_cap_cells_ = g_.sum(at_cap);
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.phi, &ph));
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), eta_s_, &es));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.p, &pa));
    GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), D_, &d));
  }
  Vec les;
  GF_PETSC(DMGetLocalVector(g_.dm_cell(), &les));
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), eta_s_, INSERT_VALUES, les));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), eta_s_, INSERT_VALUES, les));
  GF_PETSC(DMGlobalToLocalBegin(g_.dm_cell(), s.phi, INSERT_VALUES, lphi_));
  GF_PETSC(DMGlobalToLocalEnd(g_.dm_cell(), s.phi, INSERT_VALUES, lphi_));
  const PetscScalar **es, **phi;
  PetscScalar **ec, **en;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), les, &es));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &phi));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), s.eta, &ec));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), eta_node_, &en));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double thc = cfg_.levelset ? levelset::height_fraction_cell(b, phi, i, j) : 0.0;
      ec[j][i] = levelset::harmonic_viscosity(thc, cfg_.eta_air, es[j][i]);
      if (!b.wall_u(i) && j >= 1) {  // interior node: mean of the four surrounding cells
        const double esn = 0.25 * (es[j][i] + es[j][i - 1] + es[j - 1][i] + es[j - 1][i - 1]);
        const double thn = cfg_.levelset ? levelset::height_fraction_node(b, phi, i, j) : 0.0;
        en[j][i] = levelset::harmonic_viscosity(thn, cfg_.eta_air, esn);
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), eta_node_, &en));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), s.eta, &ec));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &phi));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), les, &es));
  GF_PETSC(DMRestoreLocalVector(g_.dm_cell(), &les));
}

// kappa (eqs. 18-19) from phi^{n+1} and p^n, and the wall yield kappa_b (eq. 22).
void Stepper::update_yield(State& s) {
  if (cfg_.rheo.yield == rheology::Yield::Hydrostatic) {
    // Granular fraction 1 - H_eps(phi) of each cell, weighed by eq. 15.
    const Box& b = g_.box();
    const PetscScalar** ph;
    PetscScalar** c;
    GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), s.phi, &ph));
    GF_PETSC(DMDAVecGetArray(g_.dm_cell(), gran_, &c));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i)
        c[j][i] = cfg_.levelset ? 1.0 - levelset::heaviside(ph[j][i], cfg_.eps) : 1.0;
    GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), gran_, &c));
    GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), s.phi, &ph));
    const double gabs = std::hypot(cfg_.gravity[0], cfg_.gravity[1]);
    // The weight of the column above acts along the vertical axis: its y-component.
    rheology::hydrostatic_pressure(g_, gran_, cfg_.rho_gran, std::abs(cfg_.gravity[1]) > 0 ? std::abs(cfg_.gravity[1]) : gabs, p_hyd_);
  }
  rheology::yield_stress(g_, cfg_.rheo, s.phi, s.p, p_hyd_, kappa_);
  // The wall yield from the state at t^n; refreshed in every fixed-point iteration.
  predictor_->strain_rate(s.vel, s.eta, D_);
  predictor_->wall_yield(s.p, s.S, kappa_, D_, s.eta, kappa_b_);
}

std::vector<std::vector<PetscInt>> Stepper::anderson_active(bool node) const {
  const Box& b = g_.box();
  std::vector<std::vector<PetscInt>> idx(node ? 3 : 2);
  const PetscScalar *k, *sn, *wn;
  GF_PETSC(VecGetArrayRead(kappa_, &k));
  GF_PETSC(VecGetArrayRead(S_n_, &sn));
  GF_PETSC(VecGetArrayRead(sw_n_, &wn));
  for (PetscInt j = b.ys, c = 0; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i, ++c) {
      if (k[c] > 0 || sn[3 * c] != 0 || sn[3 * c + 1] != 0 || sn[3 * c + 2] != 0)
        for (PetscInt q = 0; q < 3; ++q) idx[0].push_back(3 * c + q);
      // s_t: u on the bottom and top faces, v on the left and right ones (update_wall).
      if (((j == 0 || j == b.ny - 1) && !b.wall_u(i)) || wn[2 * c] != 0) idx[1].push_back(2 * c);
      if ((!b.periodic_x && (i == 0 || i == b.nx - 1) && j >= 1) || wn[2 * c + 1] != 0)
        idx[1].push_back(2 * c + 1);
    }
  GF_PETSC(VecRestoreArrayRead(sw_n_, &wn));
  GF_PETSC(VecRestoreArrayRead(S_n_, &sn));
  GF_PETSC(VecRestoreArrayRead(kappa_, &k));
  if (node) {
    PetscInt len;
    GF_PETSC(VecGetLocalSize(gSn_, &len));
    idx[2].resize(len);
    for (PetscInt q = 0; q < len; ++q) idx[2][q] = q;
  }
  return idx;
}

void Stepper::set_plastic_region(const State& s) {
  const Box& b = g_.box();
  // -min and max of i and j over the cells with kappa > 0 or phi < 0: one MPI_MAX reduction.
  PetscInt ext[4] = {-b.nx, -b.ny, -1, -1};
  const PetscScalar *k, *ph;
  GF_PETSC(VecGetArrayRead(kappa_, &k));
  GF_PETSC(VecGetArrayRead(s.phi, &ph));
  for (PetscInt j = b.ys, c = 0; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i, ++c)
      if (k[c] > 0 || ph[c] < 0) {
        ext[0] = std::max(ext[0], -i);
        ext[1] = std::max(ext[1], -j);
        ext[2] = std::max(ext[2], i);
        ext[3] = std::max(ext[3], j);
      }
  GF_PETSC(VecRestoreArrayRead(s.phi, &ph));
  GF_PETSC(VecRestoreArrayRead(kappa_, &k));
  PetscInt e[4];
  MPI_Allreduce(ext, e, 4, MPIU_INT, MPI_MAX, g_.comm());
  using P = momentum::Predictor;
  if (e[2] < 0)
    predictor_->set_plastic_region(0, 0, 0, 0);  // no granular cell: no plastic term
  else if (b.periodic_x)  // the region may wrap around the seam: all columns
    predictor_->set_plastic_region(-P::kUnbounded, P::kUnbounded, -e[1] - 2, e[3] + 3);
  else
    predictor_->set_plastic_region(-e[0] - 2, e[2] + 3, -e[1] - 2, e[3] + 3);
}

std::vector<PetscInt> Stepper::local_rows(const State& s, int margin) const {
  Vec m;
  GF_PETSC(DMGetGlobalVector(g_.dm_cell(), &m));
  {
    const PetscScalar *k, *ph;
    PetscScalar* o;
    GF_PETSC(VecGetArrayRead(kappa_, &k));
    GF_PETSC(VecGetArrayRead(s.phi, &ph));
    GF_PETSC(VecGetArray(m, &o));
    PetscInt len;
    GF_PETSC(VecGetLocalSize(m, &len));
    for (PetscInt c = 0; c < len; ++c) o[c] = (k[c] > 0 || ph[c] < 0) ? -1.0 : 0.0;
    GF_PETSC(VecRestoreArray(m, &o));
    GF_PETSC(VecRestoreArrayRead(s.phi, &ph));
    GF_PETSC(VecRestoreArrayRead(kappa_, &k));
  }
  // Box dilation by margin cells: the mask is -1 on the granular cells, and each pass takes the
  // minimum over a cell and its 8 neighbours.
  for (int pass = 0; pass < margin; ++pass) rheology::neighbourhood_min(g_, m, m);
  std::vector<PetscInt> rows;
  const PetscScalar* o;
  PetscInt len;
  GF_PETSC(VecGetLocalSize(m, &len));
  GF_PETSC(VecGetArrayRead(m, &o));
  for (PetscInt c = 0; c < len; ++c)
    if (o[c] < 0) {  // the u and v rows of the cell: its left and bottom faces
      rows.push_back(2 * c);
      rows.push_back(2 * c + 1);
    }
  GF_PETSC(VecRestoreArrayRead(m, &o));
  GF_PETSC(DMRestoreGlobalVector(g_.dm_cell(), &m));
  return rows;
}

momentum::Predictor::WallContact Stepper::wall_contact(const State& s) const {
  if (!predictor_ || !predictor_->has_wall_friction()) return {};
  return predictor_->wall_contact(s.s_wall, kappa_b_);
}

void Stepper::derived_fields(State& s, Vec Dnorm, Vec Snorm, Vec yielded) {
  if (predictor_) {
    predictor_->strain_rate(s.vel, s.eta, D_);
    rheology::tensor_norm(g_, D_, Dnorm);
  } else {
    GF_PETSC(VecSet(Dnorm, 0.0));
  }
  rheology::tensor_norm(g_, s.S, Snorm);
  const Box& b = g_.box();
  const PetscScalar **sn, **k;
  PetscScalar** y;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), Snorm, &sn));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), yielded, &y));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      y[j][i] = (k[j][i] <= 0 || sn[j][i] >= 1.0 - 1e-9) ? 1.0 : 0.0;
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), yielded, &y));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kappa_, &k));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), Snorm, &sn));
}

void Stepper::prescribe_velocity(State& s, double t) {
  if (cfg_.prescribed == PrescribedFlow::Rotation)
    levelset::rotation_velocity(g_, s.vel, cfg_.omega, cfg_.cx, cfg_.cy);
  else if (cfg_.prescribed == PrescribedFlow::SingleVortex)
    levelset::single_vortex_velocity(g_, s.vel, t, cfg_.period);
}

void Stepper::initialize(State& s) {
  if (predictor_) predictor_->set_phase(s.phi);
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
  if (predictor_) predictor_->set_phase(s.phi);
  // rho and eta come from the checkpoint as the last step left them (for a prescribed flow,
  // those of the initial phi; with mu(I), those of that step's start): recomputing them here
  // would change the diagnostics of a restart that takes no step. What else the stepper keeps
  // between steps is rebuilt: the nodal viscosity of a one-phase run (constant; mu(I) rewrites
  // the interior nodes every step), the pressure matrix (assembled only at the first step of
  // a one-phase run), and the viscous matrix at the next step since assembled_a0dt_ is unset.
  if (!cfg_.levelset) GF_PETSC(VecSet(eta_node_, cfg_.eta_gran));
  if (projector_) projector_->assemble(s.rho);
  assembled_a0dt_ = -1;
}

std::pair<int, double> Stepper::equilibrate(State& s, double dt, int max_steps, double tol,
                                            const std::function<double(const State&)>& measure) {
  Vec phi0;
  GF_PETSC(VecDuplicate(s.phi, &phi0));
  GF_PETSC(VecCopy(s.phi, phi0));
  double speed = std::numeric_limits<double>::infinity();
  int k = 0;
  // The pseudo-steps keep the case's relaxation theta of eq. 31. At the equilibrium S = S^n and
  // theta (S^n - S) vanishes, so theta does not choose it, but it sets the way there: the
  // granular speed after a pseudo-step falls by about 1 - theta per step (0.99 at theta =
  // 10 dt, dt = 1e-3 s); with theta = 0.5 the speeds are larger and do not fall steadily
  // (measured on cases/verify/dp_pile.toml).
  try {
    for (k = 1; k <= max_steps; ++k) {
      step(s, dt);
      speed = measure(s);
      // From rest (u^n = 0) the transport leaves phi as it was; a redistancing would not.
      GF_PETSC(VecCopy(phi0, s.phi));
      GF_PETSC(VecSet(s.vel, 0.0));
      GF_PETSC(VecSet(s.vel_old, 0.0));
      s.t = 0;
      s.dt = s.dt_old = 0;
      s.step = 0;
      if (speed < tol) break;
    }
  } catch (...) {
    VecDestroy(&phi0);
    throw;
  }
  VecDestroy(&phi0);
  update_properties(s);
  return {std::min(k, max_steps), speed};
}

bool Stepper::redistance_due(const State& s, double dt) const {
  if (cfg_.redistance_interval > 0) {
    // The step from t to t + dt redistances if it reaches the next multiple of the interval
    // (k I with t < k I <= t + dt; the relative slack absorbs the round-off of summed dts, so a
    // dt that divides the interval gives every (interval / dt)-th step, like redistance_every).
    const double slack = 1e-9 * cfg_.redistance_interval;
    const auto k_before = std::floor((s.t + slack) / cfg_.redistance_interval);
    const auto k_after = std::floor((s.t + dt + slack) / cfg_.redistance_interval);
    return k_after > k_before;
  }
  return cfg_.redistance_every > 0 && (s.step + 1) % cfg_.redistance_every == 0;
}

StepStats Stepper::step(State& s, double dt) {
  StepStats st;
  const bool first = (s.step == 0);
  // 1. Level set, eq. 26, advected by the solenoidal u^n.
  if (cfg_.prescribed != PrescribedFlow::None) prescribe_velocity(s, s.t + 0.5 * dt);
  if (cfg_.levelset) {
    {
      prof::Scope ps(prof::Advect);
      advector_->step(s.phi, s.vel, dt);
    }
    if (redistance_due(s, dt)) {
      prof::Scope ps(prof::Redistance);
      // levelset.redistance_tol: only when transport has made phi drift from a distance. Each
      // redistancing moves the zero level a little (most where it meets a wall at a shallow
      // angle); a deposit at rest, whose phi does not change, should not be eroded by it.
      if (cfg_.redistance_tol <= 0 || redistancer_->distance_defect(s.phi) > cfg_.redistance_tol) {
        redistancer_->run(s.phi);
        st.redistanced = true;
      }
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
  const bool props_change =
      cfg_.levelset || first || cfg_.rheo.viscosity == rheology::Viscosity::MuI;
  if (props_change) {
    prof::Scope ps(prof::Properties);
    update_properties(s);
    predictor_->set_phase(s.phi);
  }
  // 3. Prediction, eq. 31 (kappa = 0: Newtonian phases).
  const auto c = momentum::TimeCoeffs::make(dt, s.dt, first);
  if (props_change || c.a0 / dt != assembled_a0dt_) {
    prof::Scope ps(prof::Assemble);
    predictor_->assemble(s.rho, s.eta, eta_node_, c.a0 / dt);
    assembled_a0dt_ = c.a0 / dt;
  }
  predictor_->explicit_rhs(s.vel, s.vel_old, s.p, s.rho, c, dt, cfg_.gravity, rhs0_);
  GF_PETSC(VecCopy(s.vel, u_tilde_));  // initial guess
  if (prof::Scope pfp(prof::FixedPoint); !plastic_) {
    prof::Scope ps(prof::ViscousSolve);
    st.visc_its = predictor_->solve(rhs0_, u_tilde_);
  } else {
    // The fixed point of eq. 31: viscous solve with the current S and s_t, then
    //   S   <- P  (S   + r   kappa   D(u~) + theta (S^n   - S)),
    //   s_t <- P_b(s_t + r_b kappa_b u~_t  + theta (s_t^n - s_t)),
    // until the change is below fp_tol. theta = theta_per_dt dt ("theta = 10 dt", 4.1.3)
    // makes it contract geometrically with ratio (1 - theta) or better; the matrix and its
    // preconditioner are the same in every iteration, only the right-hand side changes.
    update_yield(s);
    GF_PETSC(VecCopy(s.S, S_n_));
    GF_PETSC(VecCopy(s.s_wall, sw_n_));
    const bool node = cfg_.rheo.node_copy;
    if (node) GF_PETSC(VecCopy(s.S_node, Sn_n_));
    const double theta = std::min(0.5, cfg_.rheo.theta_per_dt * dt);
    if (anderson_) anderson_->set_active(anderson_active(node));
    // The plastic terms and D(u~) only where the granular phase is (kappa > 0 or phi < 0),
    // widened by 2 cells for the stencils of the faces, nodes and wall extrapolations around
    // it: in case A that is 20-50 % of the domain.
    struct RegionGuard {
      momentum::Predictor* p;
      ~RegionGuard() { p->clear_plastic_region(); }
    } region_guard{predictor_.get()};
    if (predictor_->has_wall_friction()) predictor_->cache_wall_inputs(s.p, kappa_, s.eta);
    set_plastic_region(s);
    double last_ch = std::numeric_limits<double>::infinity();
    for (int k = 1; k <= cfg_.rheo.fp_max_iter; ++k) {
      GF_PETSC(VecCopy(rhs0_, rhs_));
      {
        prof::Scope ps(prof::Plastic);
        predictor_->add_plastic(kappa_, s.S, kappa_b_, s.s_wall, rhs_,
                                node ? s.S_node.vec() : nullptr);
      }
      const bool track_u = fp_monitor_ || cfg_.rheo.fp_tol_u > 0;
      if (track_u) GF_PETSC(VecCopy(u_tilde_, rhs0_mon_));
      {
        prof::Scope ps(prof::ViscousSolve);
        // From the second iteration on, only the plastic terms change the right-hand side.
        if (k == 2 && cfg_.viscous_local_margin > 0) {
          // Not worth it when R is most of the domain (a one-phase run: all of it).
          std::vector<PetscInt> rows = local_rows(s, cfg_.viscous_local_margin);
          PetscInt n[2] = {static_cast<PetscInt>(rows.size()), 0}, tot[2];
          GF_PETSC(VecGetLocalSize(u_tilde_, &n[1]));
          MPI_Allreduce(n, tot, 2, MPIU_INT, MPI_SUM, g_.comm());
          if (tot[0] < 0.7 * tot[1]) predictor_->begin_local(rows, rhs_, u_tilde_);
        }
        st.visc_its += predictor_->local_active() ? predictor_->solve_local(rhs_, u_tilde_)
                                                  : predictor_->solve(rhs_, u_tilde_);
      }
      PetscReal du = 0, un = 0;
      if (track_u) {
        GF_PETSC(VecAXPY(rhs0_mon_, -1.0, u_tilde_));
        GF_PETSC(VecNorm(rhs0_mon_, NORM_INFINITY, &du));
        GF_PETSC(VecNorm(u_tilde_, NORM_INFINITY, &un));
      }
      double ch;
      {
        prof::Scope ps(prof::Plastic);
        predictor_->strain_rate(u_tilde_, s.eta, D_, node ? Dn_ : nullptr);
        // G(x): the projections of eq. 31 applied to the current iterate x = (S, s_t).
        GF_PETSC(VecCopy(s.S, gS_));
        GF_PETSC(VecCopy(s.s_wall, gW_));
        ch = rheology::update_plastic(g_, cfg_.rheo, gS_, S_n_, kappa_, D_, rho_r_, eta_r_,
                                      c.a0 / dt, theta);
        if (node) {
          GF_PETSC(VecCopy(s.S_node, gSn_));
          ch = std::max(ch, rheology::update_plastic_node(g_, cfg_.rheo, gSn_, Sn_n_, kappa_, Dn_,
                                                          rho_r_, eta_r_, c.a0 / dt, theta));
        }
        if (predictor_->has_wall_friction()) {
          predictor_->wall_yield(s.p, gS_, kappa_, D_, s.eta, kappa_b_);
          ch = std::max(ch, predictor_->update_wall(u_tilde_, kappa_b_, gW_, sw_n_, s.rho, s.eta,
                                                    c.a0 / dt, theta, cfg_.rheo.r_factor));
        }
      }
      st.fp_iters = k;
      st.fp_change = ch;
      if (fp_monitor_) {
        // Also the root-mean-square change of S over the cells where it changed by more than
        // 1e-12 and how many they are (is the max norm carried by a few cells?).
        const PetscScalar* a;
        const PetscScalar* b;
        PetscInt len;
        GF_PETSC(VecGetLocalSize(gS_, &len));
        GF_PETSC(VecGetArrayRead(gS_, &a));
        GF_PETSC(VecGetArrayRead(s.S, &b));
        double loc[3] = {0, 0, 0}, glob[3];
        for (PetscInt q = 0; q < len; ++q) {
          const double d = std::abs(a[q] - b[q]);
          if (d > 1e-12) { loc[0] += d * d; loc[1] += 1; }
          if (d > 0.1 * ch) loc[2] += 1;
        }
        GF_PETSC(VecRestoreArrayRead(s.S, &b));
        GF_PETSC(VecRestoreArrayRead(gS_, &a));
        MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, g_.comm());
        PetscPrintf(g_.comm(), "  fixed point step %lld iteration %d change %.6e  |du~| %.3e m/s (max |u~| %.3e)  rms %.3e over %.0f values, %.0f above max/10\n",
                    s.step + 1, k, ch, (double)du, (double)un,
                    std::sqrt(glob[0] / std::max(glob[1], 1.0)), glob[1], glob[2]);
      }
      // Safeguard: the projections make the map non-smooth (active sets change); when the
      // residual grows, the extrapolation is dropped (history reset) and the plain step taken.
      const bool grew = ch > reset_ratio_ * last_ch;
      last_ch = ch;
      // k > 1: the first solve's change is from the previous step's velocity.
      const bool done = ch < cfg_.rheo.fp_tol ||
                        (cfg_.rheo.fp_tol_u > 0 && k > 1 && du < cfg_.rheo.fp_tol_u);
      if (done || !anderson_ || grew) {
        if (anderson_ && grew) anderson_->reset();
        GF_PETSC(VecCopy(gS_, s.S));
        GF_PETSC(VecCopy(gW_, s.s_wall));
        if (node) GF_PETSC(VecCopy(gSn_, s.S_node));
        if (done) {
          st.fp_converged = true;
          break;
        }
        continue;
      }
      // Anderson mixing of the last iterates, then back into |S| <= 1, |s_t| <= 1.
      prof::Scope ps(prof::Anderson);
      if (node) {
        anderson_->update({s.S, s.s_wall, s.S_node}, {gS_, gW_, gSn_});
        rheology::project_field_node(g_, s.S_node, kappa_);
      } else {
        anderson_->update({s.S, s.s_wall}, {gS_, gW_});
      }
      rheology::project_field(g_, s.S, kappa_);
      {
        PetscInt n;
        PetscScalar* w;
        GF_PETSC(VecGetLocalSize(s.s_wall, &n));
        GF_PETSC(VecGetArray(s.s_wall, &w));
        for (PetscInt q = 0; q < n; ++q) w[q] = rheology::project_b(w[q]);
        GF_PETSC(VecRestoreArray(s.s_wall, &w));
      }
    }
    st.fp_capped = !st.fp_converged;
    if (predictor_->local_active()) {
      // The full system for the last S and s_t: what the frozen rows missed (a residual below
      // the tolerance when the margin is wide enough; then this solve takes no iteration).
      prof::Scope ps(prof::ViscousSolve);
      predictor_->end_local();
      st.visc_polish_its = predictor_->solve(rhs_, u_tilde_);
      st.visc_its += st.visc_polish_its;
    }
    st.mu_i_floor_cells = mu_i_floor_cells_;
    st.mu_i_cap_cells = mu_i_cap_cells_;
  }
  // 4. Projection, eq. 32.
  {
    prof::Scope ps(prof::Assemble);
    if (props_change) projector_->assemble(s.rho);
  }
  {
    prof::Scope ps(prof::Pressure);
    st.pres_its = projector_->project(u_tilde_, s.p, s.rho, c.a0, dt);
    st.pres_fallback = projector_->fell_back();
  }
  GF_PETSC(VecCopy(s.vel, s.vel_old));
  GF_PETSC(VecCopy(u_tilde_, s.vel));
  s.dt_old = s.dt;
  s.dt = dt;
  s.t += dt;
  ++s.step;
  return st;
}

}  // namespace gf
