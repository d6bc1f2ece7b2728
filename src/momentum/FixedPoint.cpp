#include "momentum/FixedPoint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "boundary/Coulomb.hpp"
#include "boundary/SideWalls.hpp"
#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Profile.hpp"

namespace gf::momentum {

FixedPoint::FixedPoint(const Grid& g, Predictor& pred, const rheology::Params& rheo,
                       const FixedPointOptions& opt)
    : g_(g), pred_(pred), rheo_(rheo), opt_(opt) {
  if (opt_.anderson_depth > 0)
    anderson_ = std::make_unique<linsolve::Anderson>(opt_.anderson_depth, g.comm());
  for (Vec* v : {&S_n_, &gS_, &D_}) GF_PETSC(DMCreateGlobalVector(g.dm_ten(), v));
  for (Vec* v : {&sw_n_, &gW_, &rhs_}) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
  if (rheo_.node_copy)
    for (Vec* v : {&Dn_, &Sn_n_, &gSn_}) GF_PETSC(DMCreateGlobalVector(g.dm_node(), v));
  if (opt_.monitor || rheo_.fp_tol_u > 0) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), &u_prev_));
  if (pred.side_walls().active())
    for (Vec* v : {&sd_n_, &gSd_, &zx_, &zg_}) GF_PETSC(DMCreateGlobalVector(g.dm_vel(), v));
}

FixedPoint::~FixedPoint() {
  for (Vec* v : {&S_n_, &sw_n_, &gS_, &gW_, &Dn_, &Sn_n_, &gSn_, &D_, &rhs_, &u_prev_, &sd_n_,
                 &gSd_, &zx_, &zg_})
    VecDestroy(v);
}

FixedPointStats FixedPoint::solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde,
                                  double a0dt, double theta, long long step) {
  FixedPointStats st;
  GF_PETSC(VecCopy(s.S, S_n_));
  GF_PETSC(VecCopy(s.s_wall, sw_n_));
  if (rheo_.node_copy) GF_PETSC(VecCopy(s.S_node, Sn_n_));
  if (side()) {
    GF_PETSC(VecCopy(s.s_side, sd_n_));
    PetscReal km;
    GF_PETSC(VecMax(in.kappa_side, nullptr, &km));
    k_max_ = km;
  }
  if (anderson_) anderson_->set_active(anderson_active(in.kappa, in.kappa_side));
  // The plastic terms and D(u~) only where the granular phase is (kappa > 0 or phi < 0),
  // widened by 2 cells for the stencils of the faces, nodes and wall extrapolations around
  // it: in case A that is 20-50 % of the domain.
  struct RegionGuard {
    Predictor& p;
    ~RegionGuard() { p.clear_plastic_region(); }
  } region_guard{pred_};
  if (pred_.walls().active()) pred_.walls().cache_inputs(s.p, in.kappa, s.eta);
  set_plastic_region(in.granular);
  double last_ch = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= rheo_.fp_max_iter; ++k) {
    // 1. The viscous solve with the current S and s_t.
    double du = 0, umax = 0;
    st.visc_its += viscous_solve(s, in, rhs0, u_tilde, k, du, umax);
    // 2. G(x): the projections of eq. 31 applied to the current iterate x = (S, s_t).
    const double ch = project(s, in, u_tilde, a0dt, theta);
    st.iters = k;
    st.change = ch;
    if (opt_.monitor) report(step, k, ch, du, umax, s.S);
    // 3. Converged? Safeguard: the projections make the map non-smooth (active sets change);
    // when the residual grows, the extrapolation is dropped (history reset) and the plain step
    // taken.
    const bool grew = ch > opt_.anderson_reset_ratio * last_ch;
    last_ch = ch;
    // k > 1: the first solve's change is from the previous step's velocity.
    const bool done = ch < rheo_.fp_tol || (rheo_.fp_tol_u > 0 && k > 1 && du < rheo_.fp_tol_u);
    if (done || !anderson_ || grew) {
      if (anderson_ && grew) anderson_->reset();
      GF_PETSC(VecCopy(gS_, s.S));
      GF_PETSC(VecCopy(gW_, s.s_wall));
      if (rheo_.node_copy) GF_PETSC(VecCopy(gSn_, s.S_node));
      if (side()) GF_PETSC(VecCopy(gSd_, s.s_side));
      if (done) {
        st.converged = true;
        break;
      }
      continue;
    }
    // 4. The next iterate from the last ones.
    accelerate(s, in);
  }
  if (pred_.local_active()) {
    // The full system for the last S and s_t: what the frozen rows missed (a residual below
    // the tolerance when the margin is wide enough; then this solve takes no iteration).
    prof::Scope ps(prof::ViscousSolve);
    pred_.end_local();
    st.visc_polish_its = pred_.solve(rhs_, u_tilde);
    st.visc_its += st.visc_polish_its;
  }
  return st;
}

int FixedPoint::viscous_solve(State& s, const PlasticInputs& in, Vec rhs0, Vec u_tilde, int k,
                              double& du, double& umax) {
  const bool node = rheo_.node_copy;
  GF_PETSC(VecCopy(rhs0, rhs_));
  {
    prof::Scope ps(prof::Plastic);
    pred_.add_plastic(in.kappa, s.S, in.kappa_b, s.s_wall, rhs_, node ? s.S_node.vec() : nullptr);
    if (side()) pred_.side_walls().add_force(in.kappa_side, s.s_side, rhs_);
  }
  const bool track_u = opt_.monitor || rheo_.fp_tol_u > 0;
  if (track_u) GF_PETSC(VecCopy(u_tilde, u_prev_));
  int its;
  {
    prof::Scope ps(prof::ViscousSolve);
    // From the second iteration on, only the plastic terms change the right-hand side.
    if (k == 2 && opt_.local_margin > 0) {
      // Not worth it when R is most of the domain (a one-phase run: all of it).
      std::vector<PetscInt> rows = local_rows(in.granular, opt_.local_margin);
      PetscInt n[2] = {static_cast<PetscInt>(rows.size()), 0}, tot[2];
      GF_PETSC(VecGetLocalSize(u_tilde, &n[1]));
      MPI_Allreduce(n, tot, 2, MPIU_INT, MPI_SUM, g_.comm());
      if (tot[0] < 0.7 * tot[1]) pred_.begin_local(rows, rhs_, u_tilde);
    }
    its = pred_.local_active() ? pred_.solve_local(rhs_, u_tilde) : pred_.solve(rhs_, u_tilde);
  }
  if (track_u) {
    PetscReal d, u;
    GF_PETSC(VecAXPY(u_prev_, -1.0, u_tilde));
    GF_PETSC(VecNorm(u_prev_, NORM_INFINITY, &d));
    GF_PETSC(VecNorm(u_tilde, NORM_INFINITY, &u));
    du = d;
    umax = u;
  }
  return its;
}

double FixedPoint::project(State& s, const PlasticInputs& in, Vec u_tilde, double a0dt,
                           double theta) {
  prof::Scope ps(prof::Plastic);
  const bool node = rheo_.node_copy;
  pred_.strain_rate(u_tilde, s.eta, D_, node ? Dn_ : nullptr);
  GF_PETSC(VecCopy(s.S, gS_));
  GF_PETSC(VecCopy(s.s_wall, gW_));
  double ch = rheology::update_plastic(g_, rheo_, gS_, S_n_, in.kappa, D_, in.rho_r, in.eta_r,
                                       a0dt, theta);
  if (node) {
    GF_PETSC(VecCopy(s.S_node, gSn_));
    ch = std::max(ch, rheology::update_plastic_node(g_, rheo_, gSn_, Sn_n_, in.kappa, Dn_,
                                                    in.rho_r, in.eta_r, a0dt, theta));
  }
  boundary::CoulombWalls& walls = pred_.walls();
  if (walls.active()) {
    walls.yield(s.p, gS_, in.kappa, D_, s.eta, in.kappa_b);
    ch = std::max(ch, walls.update(u_tilde, in.kappa_b, gW_, sw_n_, s.rho, s.eta, a0dt, theta,
                                   rheo_.r_factor));
  }
  if (side()) {
    GF_PETSC(VecCopy(s.s_side, gSd_));
    if (k_max_ > 0)
      ch = std::max(ch, pred_.side_walls().update(u_tilde, in.kappa_side, gSd_, sd_n_, s.rho,
                                                  s.eta, a0dt, theta, rheo_.r_factor, k_max_));
  }
  return ch;
}

void FixedPoint::accelerate(State& s, const PlasticInputs& in) {
  // Anderson mixing of the last iterates, then back into |S| <= 1, |s_t| <= 1.
  prof::Scope ps(prof::Anderson);
  std::vector<Vec> x, gx;
  blocks(s, x, gx);
  if (side()) to_force(in.kappa_side, s.s_side, gSd_);
  anderson_->update(x, gx);
  if (side()) from_force(in.kappa_side, s.s_side);
  if (rheo_.node_copy) rheology::project_field_node(g_, s.S_node, in.kappa);
  rheology::project_field(g_, s.S, in.kappa);
  PetscInt n;
  PetscScalar* w;
  GF_PETSC(VecGetLocalSize(s.s_wall, &n));
  GF_PETSC(VecGetArray(s.s_wall, &w));
  for (PetscInt q = 0; q < n; ++q) w[q] = boundary::project_b(w[q]);
  GF_PETSC(VecRestoreArray(s.s_wall, &w));
  if (side()) {  // each cell's (s_x, s_y) back into the unit disc
    GF_PETSC(VecGetLocalSize(s.s_side, &n));
    GF_PETSC(VecGetArray(s.s_side, &w));
    for (PetscInt q = 0; q + 1 < n; q += 2) boundary::project_disc(w[q], w[q + 1]);
    GF_PETSC(VecRestoreArray(s.s_side, &w));
  }
}

void FixedPoint::blocks(State& s, std::vector<Vec>& x, std::vector<Vec>& gx) {
  x = {s.S, s.s_wall};
  gx = {gS_, gW_};
  if (rheo_.node_copy) {
    x.push_back(s.S_node);
    gx.push_back(gSn_);
  }
  if (side()) {
    x.push_back(zx_);
    gx.push_back(zg_);
  }
}

void FixedPoint::to_force(Vec k, Vec sx, Vec sg) {
  const PetscScalar *kc, *a, *b;
  PetscScalar *zx, *zg;
  PetscInt len;
  GF_PETSC(VecGetLocalSize(k, &len));
  GF_PETSC(VecGetArrayRead(k, &kc));
  GF_PETSC(VecGetArrayRead(sx, &a));
  GF_PETSC(VecGetArrayRead(sg, &b));
  GF_PETSC(VecGetArray(zx_, &zx));
  GF_PETSC(VecGetArray(zg_, &zg));
  for (PetscInt c = 0; c < len; ++c) {
    const double w = k_max_ > 0 ? kc[c] / k_max_ : 0.0;
    for (PetscInt q = 2 * c; q < 2 * c + 2; ++q) {
      zx[q] = w * a[q];
      zg[q] = w * b[q];
    }
  }
  GF_PETSC(VecRestoreArray(zg_, &zg));
  GF_PETSC(VecRestoreArray(zx_, &zx));
  GF_PETSC(VecRestoreArrayRead(sg, &b));
  GF_PETSC(VecRestoreArrayRead(sx, &a));
  GF_PETSC(VecRestoreArrayRead(k, &kc));
}

void FixedPoint::from_force(Vec k, Vec sx) {
  const PetscScalar *kc, *zx;
  PetscScalar* a;
  PetscInt len;
  GF_PETSC(VecGetLocalSize(k, &len));
  GF_PETSC(VecGetArrayRead(k, &kc));
  GF_PETSC(VecGetArrayRead(zx_, &zx));
  GF_PETSC(VecGetArray(sx, &a));
  for (PetscInt c = 0; c < len; ++c) {
    const double w = k_max_ > 0 ? kc[c] / k_max_ : 0.0;
    a[2 * c] = w > 0 ? zx[2 * c] / w : 0.0;
    a[2 * c + 1] = w > 0 ? zx[2 * c + 1] / w : 0.0;
  }
  GF_PETSC(VecRestoreArray(sx, &a));
  GF_PETSC(VecRestoreArrayRead(zx_, &zx));
  GF_PETSC(VecRestoreArrayRead(k, &kc));
}

void FixedPoint::report(long long step, int k, double ch, double du, double un, Vec S) const {
  const PetscScalar* a;
  const PetscScalar* b;
  PetscInt len;
  GF_PETSC(VecGetLocalSize(gS_, &len));
  GF_PETSC(VecGetArrayRead(gS_, &a));
  GF_PETSC(VecGetArrayRead(S, &b));
  double loc[3] = {0, 0, 0}, glob[3];
  for (PetscInt q = 0; q < len; ++q) {
    const double d = std::abs(a[q] - b[q]);
    if (d > 1e-12) {
      loc[0] += d * d;
      loc[1] += 1;
    }
    if (d > 0.1 * ch) loc[2] += 1;
  }
  GF_PETSC(VecRestoreArrayRead(S, &b));
  GF_PETSC(VecRestoreArrayRead(gS_, &a));
  MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, g_.comm());
  if (g_.rank() != 0) return;
  char line[256];
  std::snprintf(line, sizeof line,
                "  fixed point step %lld iteration %d change %.6e  |du~| %.3e m/s (max |u~| %.3e)"
                "  rms %.3e over %.0f values, %.0f above max/10",
                step, k, ch, du, un, std::sqrt(glob[0] / std::max(glob[1], 1.0)), glob[1],
                glob[2]);
  log::message(line);
}

std::vector<std::vector<PetscInt>> FixedPoint::anderson_active(Vec kappa, Vec kappa_side) const {
  const Box& b = g_.box();
  const bool node = rheo_.node_copy;
  std::vector<std::vector<PetscInt>> idx((node ? 3 : 2) + (side() ? 1 : 0));
  const PetscScalar *k, *sn, *wn;
  GF_PETSC(VecGetArrayRead(kappa, &k));
  GF_PETSC(VecGetArrayRead(S_n_, &sn));
  GF_PETSC(VecGetArrayRead(sw_n_, &wn));
  const PetscInt ig = pred_.gate() && pred_.gate()->enabled() ? pred_.gate()->face() : 0;
  for (PetscInt j = b.ys, c = 0; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i, ++c) {
      if (k[c] > 0 || sn[3 * c] != 0 || sn[3 * c + 1] != 0 || sn[3 * c + 2] != 0)
        for (PetscInt q = 0; q < 3; ++q) idx[0].push_back(3 * c + q);
      // s_t: u on the bottom and top faces, v on the left and right ones (CoulombWalls::update).
      if (((j == 0 || j == b.ny - 1) && !b.wall_u(i)) || wn[2 * c] != 0) idx[1].push_back(2 * c);
      // ... and the v-faces on either side of the gate (boundary/Gate.hpp).
      const bool gate = ig > 0 && (i == ig - 1 || i == ig) && j >= 1;
      if ((!b.periodic_x && (i == 0 || i == b.nx - 1) && j >= 1) || gate || wn[2 * c + 1] != 0)
        idx[1].push_back(2 * c + 1);
    }
  GF_PETSC(VecRestoreArrayRead(sw_n_, &wn));
  GF_PETSC(VecRestoreArrayRead(S_n_, &sn));
  GF_PETSC(VecRestoreArrayRead(kappa, &k));
  if (node) {
    PetscInt len;
    GF_PETSC(VecGetLocalSize(gSn_, &len));
    idx[2].resize(len);
    for (PetscInt q = 0; q < len; ++q) idx[2][q] = q;
  }
  if (side()) {  // s_side where the side walls' friction acts or s_side^n is not zero
    const PetscScalar *ks, *dn;
    PetscInt len;
    GF_PETSC(VecGetLocalSize(kappa_side, &len));
    GF_PETSC(VecGetArrayRead(kappa_side, &ks));
    GF_PETSC(VecGetArrayRead(sd_n_, &dn));
    std::vector<PetscInt>& d = idx.back();
    for (PetscInt c = 0; c < len; ++c)
      if (ks[c] > 0 || dn[2 * c] != 0 || dn[2 * c + 1] != 0) {
        d.push_back(2 * c);
        d.push_back(2 * c + 1);
      }
    GF_PETSC(VecRestoreArrayRead(sd_n_, &dn));
    GF_PETSC(VecRestoreArrayRead(kappa_side, &ks));
  }
  return idx;
}

void FixedPoint::set_plastic_region(Vec granular) {
  const Box& b = g_.box();
  // -min and max of i and j over the granular cells: one MPI_MAX reduction.
  PetscInt ext[4] = {-b.nx, -b.ny, -1, -1};
  const PetscScalar* m;
  GF_PETSC(VecGetArrayRead(granular, &m));
  for (PetscInt j = b.ys, c = 0; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i, ++c)
      if (m[c] < 0) {
        ext[0] = std::max(ext[0], -i);
        ext[1] = std::max(ext[1], -j);
        ext[2] = std::max(ext[2], i);
        ext[3] = std::max(ext[3], j);
      }
  GF_PETSC(VecRestoreArrayRead(granular, &m));
  PetscInt e[4];
  MPI_Allreduce(ext, e, 4, MPIU_INT, MPI_MAX, g_.comm());
  using P = Predictor;
  if (e[2] < 0)
    pred_.set_plastic_region(0, 0, 0, 0);  // no granular cell: no plastic term
  else if (b.periodic_x)  // the region may wrap around the seam: all columns
    pred_.set_plastic_region(-P::kUnbounded, P::kUnbounded, -e[1] - 2, e[3] + 3);
  else
    pred_.set_plastic_region(-e[0] - 2, e[2] + 3, -e[1] - 2, e[3] + 3);
}

std::vector<PetscInt> FixedPoint::local_rows(Vec granular, int margin) const {
  return granular_rows(g_, granular, margin);
}

std::vector<PetscInt> granular_rows(const Grid& g, Vec granular, int margin) {
  Vec m;
  GF_PETSC(DMGetGlobalVector(g.dm_cell(), &m));
  GF_PETSC(VecCopy(granular, m));
  // Box dilation by margin cells: the mask is -1 on the granular cells, and each pass takes the
  // minimum over a cell and its 8 neighbours.
  for (int pass = 0; pass < margin; ++pass) rheology::neighbourhood_min(g, m, m);
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
  GF_PETSC(DMRestoreGlobalVector(g.dm_cell(), &m));
  return rows;
}

}  // namespace gf::momentum
