#include "boundary/Coulomb.hpp"

#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "grid/Local.hpp"

namespace gf::boundary {

CoulombWalls::CoulombWalls(const Grid& g, const Boundaries& bc) : g_(g), bc_(bc) {
  GF_PETSC(DMCreateLocalVector(g.dm_cell(), &lphi_));
}

CoulombWalls::~CoulombWalls() {
  for (Vec* v : {&lphi_, &lwp_, &lwk_, &lwe_, &lrho_}) VecDestroy(v);
}

bool CoulombWalls::active() const {
  return std::any_of(tan_b_.begin(), tan_b_.end(), [](double t) { return t > 0; }) ||
         (gate_ && gate_->enabled() && tan_g() > 0);
}

bool CoulombWalls::gate_face(const PetscScalar* const* ph, PetscInt i, PetscInt j) const {
  if (!ph || !gate_ || tan_g() <= 0) return false;
  const PetscInt ig = gate_->face();
  if ((i != ig - 1 && i != ig) || !gate_->node_blocked(ig, j)) return false;
  return 0.5 * (ph[j - 1][i] + ph[j][i]) < support_;
}

void CoulombWalls::set_phase(Vec phi) {
  to_local(g_.dm_cell(), phi, lphi_);
  have_phase_ = true;
}

void CoulombWalls::set_wall_weight(Vec rho, const std::array<double, 2>& gravity) {
  if (!lrho_) GF_PETSC(DMCreateLocalVector(g_.dm_cell(), &lrho_));
  to_local(g_.dm_cell(), rho, lrho_);
  grav_ = gravity;
  weight_ = true;
}

CoulombWalls::Phase::Phase(const CoulombWalls& w) : w_(w) {
  if (w_.have_phase_) GF_PETSC(DMDAVecGetArrayRead(w_.g_.dm_cell(), w_.lphi_, &a_));
}

CoulombWalls::Phase::~Phase() {
  if (a_) DMDAVecRestoreArrayRead(w_.g_.dm_cell(), w_.lphi_, &a_);
}

bool CoulombWalls::coulomb_face(const PetscScalar* const* ph, int side, PetscInt i,
                                PetscInt j) const {
  if (!ph || tan_b_[side] <= 0) return false;
  const Box& b = g_.box();
  // With periodic x there are no left/right walls, and the bottom/top u-face i = 0 is an
  // ordinary face (its left cell -1 is the wrapped ghost).
  switch (side) {
    case 0: return !b.periodic_x && j >= 1 && i == 0 && 0.5 * (ph[j - 1][0] + ph[j][0]) < support_;
    case 1:
      return !b.periodic_x && j >= 1 && i == b.nx - 1 && 0.5 * (ph[j - 1][i] + ph[j][i]) < support_;
    case 2: return !b.wall_u(i) && j == 0 && 0.5 * (ph[0][i - 1] + ph[0][i]) < support_;
    case 3: return !b.wall_u(i) && j == b.ny - 1 && 0.5 * (ph[j][i - 1] + ph[j][i]) < support_;
  }
  return false;
}

void CoulombWalls::cache_inputs(Vec p, Vec kappa, Vec eta) {
  for (Vec* v : {&lwp_, &lwk_, &lwe_})
    if (!*v) GF_PETSC(DMCreateLocalVector(g_.dm_cell(), v));
  to_local(g_.dm_cell(), p, lwp_);
  to_local(g_.dm_cell(), kappa, lwk_);
  to_local(g_.dm_cell(), eta, lwe_);
  cached_ = true;
}

void CoulombWalls::yield(Vec p, Vec S, Vec kappa, Vec D, Vec eta, Vec kappa_b) {
  const Box& b = g_.box();
  Vel** kb;
  if (!cached_) {  // outside the fixed point: ghost them for this call only
    cache_inputs(p, kappa, eta);
    cached_ = false;
  }
  LocalDof ls(g_.dm_ten(), S), ld(g_.dm_ten(), D);
  const PetscScalar **pa, **k, **e;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwp_, &pa));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwk_, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwe_, &e));
  const Phase phase(*this);
  const PetscScalar* const* ph = phase.array();
  GF_PETSC(VecSet(kappa_b, 0.0));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), kappa_b, &kb));
  // -T_n = p - T'_nn with T'_nn = 2 eta D_nn + kappa S_nn, the deviatoric normal stress along
  // the wall normal (yy at the bottom and top, xx at the left and right), at a cell next to
  // the wall. In a rigid zone p alone is not the normal load: S carries part of it.
  auto mT = [&](PetscInt i, PetscInt j, int c) {
    return pa[j][i] - 2.0 * e[j][i] * ld[j][i][c] - k[j][i] * ls[j][i][c];
  };
  auto pos = [](double x) { return x > 0 ? x : 0.0; };
  // The normal stress ON the wall: linear extrapolation from the first two cells off it, mean
  // of the two cells along the wall. The first cells' value alone is half a cell of weight
  // short (hydrostatic increment rho g h/2): 5 % of the friction of a 10-cell-high block at
  // n = 30, which made it slide 8 % too fast.
  // With set_wall_weight: the first cells' value plus the weight of the half cell below their
  // centres (see the header), gn the gravity towards the wall.
  const PetscScalar** r = nullptr;
  if (weight_) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lrho_, &r));
  auto wall_y = [&](PetscInt i, PetscInt j, PetscInt jn) {
    if (r) {
      const double gn = jn > j ? -grav_[1] : grav_[1];
      return 0.5 * (mT(i - 1, j, 2) + mT(i, j, 2)) + 0.25 * (r[j][i - 1] + r[j][i]) * gn * b.hy;
    }
    return 0.5 * (1.5 * (mT(i - 1, j, 2) + mT(i, j, 2)) - 0.5 * (mT(i - 1, jn, 2) + mT(i, jn, 2)));
  };
  auto wall_x = [&](PetscInt i, PetscInt in, PetscInt j) {
    if (r) {
      const double gn = in > i ? -grav_[0] : grav_[0];
      return 0.5 * (mT(i, j - 1, 0) + mT(i, j, 0)) + 0.25 * (r[j - 1][i] + r[j][i]) * gn * b.hx;
    }
    return 0.5 * (1.5 * (mT(i, j - 1, 0) + mT(i, j, 0)) - 0.5 * (mT(in, j - 1, 0) + mT(in, j, 0)));
  };
  // Only the cells next to a wall hold a wall face: the rows j = 0, ny-1 and the columns
  // i = 0, nx-1 (the other cells are skipped, coulomb_face is false there).
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (j != 0 && j != b.ny - 1 && i != 0 && i != b.nx - 1) {
        i = std::max(i, std::min(b.xe(), b.nx - 1) - 1);  // jump to the last column
        continue;
      }
      if (coulomb_face(ph, 2, i, j)) kb[j][i].u = tan_b_[2] * pos(wall_y(i, j, j + 1));
      if (coulomb_face(ph, 3, i, j)) kb[j][i].u = tan_b_[3] * pos(wall_y(i, j, j - 1));
      if (coulomb_face(ph, 0, i, j)) kb[j][i].v = tan_b_[0] * pos(wall_x(i, i + 1, j));
      if (coulomb_face(ph, 1, i, j)) kb[j][i].v = tan_b_[1] * pos(wall_x(i, i - 1, j));
    }
  // The gate's faces: -T_n on the plate = p - T'_xx at the mean of the face's two cells.
  if (gate_ && gate_->present() && tan_g() > 0)
    for (PetscInt i : {gate_->face() - 1, gate_->face()}) {
      if (i < b.xs || i >= b.xe()) continue;
      for (PetscInt j = std::max<PetscInt>(b.ys, 1); j < b.ye(); ++j)
        if (gate_face(ph, i, j)) kb[j][i].v = tan_g() * pos(0.5 * (mT(i, j - 1, 0) + mT(i, j, 0)));
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), kappa_b, &kb));
  if (r) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lrho_, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwe_, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwk_, &k));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwp_, &pa));
}

double CoulombWalls::update(Vec u_tilde, Vec kappa_b, Vec s_wall, Vec s_wall_n, Vec rho, Vec eta,
                            double a0dt, double theta, double r_factor) const {
  const Box& b = g_.box();
  const Vel **u, **kb, **sn;
  Vel** sw;
  const PetscScalar **r, **e;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), u_tilde, &u));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), s_wall_n, &sn));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), eta, &e));
  double change = 0;
  // eq. 31, wall line: s <- P_b(s + r_b kappa_b u_t + theta (s^n - s)); r_b from the compliance
  // of the first face velocity to a wall traction (inertia rho a0 h/dt and viscosity 2 eta/h).
  auto upd = [&](double& s, double s_n, double k, double ut, double rc, double ec, double h) {
    if (k <= 0) {
      s = 0.0;
      return;
    }
    const double rb = r_factor * stiffness(rc, ec, a0dt, h) / (k * k);
    const double snew = project_b(s + rb * k * ut + theta * (s_n - s));
    change = std::max(change, std::abs(snew - s));
    s = snew;
  };
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if ((j == 0 || j == b.ny - 1) && !b.wall_u(i))
        upd(sw[j][i].u, sn[j][i].u, kb[j][i].u, u[j][i].u, r[j][i], e[j][i], b.hy);
      if (!b.periodic_x && (i == 0 || i == b.nx - 1) && j >= 1)
        upd(sw[j][i].v, sn[j][i].v, kb[j][i].v, u[j][i].v, r[j][i], e[j][i], b.hx);
    }
  // The gate's faces: the slip is the grains' velocity relative to the plate, v - V. Where the
  // plate has left (kappa_b = 0) s is reset to 0 by upd.
  if (gate_ && gate_->enabled())
    for (PetscInt i : {gate_->face() - 1, gate_->face()}) {
      if (i < b.xs || i >= b.xe()) continue;
      for (PetscInt j = std::max<PetscInt>(b.ys, 1); j < b.ye(); ++j)
        upd(sw[j][i].v, sn[j][i].v, kb[j][i].v, u[j][i].v - gate_->velocity(), r[j][i], e[j][i],
            b.hx);
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall_n, &sn));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), u_tilde, &u));
  return g_.max(change);
}

WallContact CoulombWalls::contact(Vec s_wall, Vec kappa_b) const {
  const Box& b = g_.box();
  const Vel **sw, **kb;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), kappa_b, &kb));
  double loc[18] = {}, glob[18];
  // A face counts when it carries a Coulomb stress (kappa_b > 0: granular and frictional).
  // Per side: stick length, slide length, the normal load sum kappa_b / tan(alpha_b) len and
  // the tangential force sum kappa_b s_t len (N/m; the sign of s_t is along +x or +y).
  auto add = [&](int side, double s, double k, double len) {
    if (k <= 0) return;
    const bool slide = std::abs(s) >= 1.0 - 1e-9;
    loc[side + (slide ? 4 : 0)] += len;
    loc[8 + side] += k / tan_b_[side] * len;
    loc[12 + side] += k * s * len;
  };
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (j == 0 && !b.wall_u(i) && tan_b_[2] > 0) add(2, sw[j][i].u, kb[j][i].u, b.hx);
      if (j == b.ny - 1 && !b.wall_u(i) && tan_b_[3] > 0) add(3, sw[j][i].u, kb[j][i].u, b.hx);
      if (!b.periodic_x && i == 0 && j >= 1 && tan_b_[0] > 0) add(0, sw[j][i].v, kb[j][i].v, b.hy);
      if (!b.periodic_x && i == b.nx - 1 && j >= 1 && tan_b_[1] > 0) add(1, sw[j][i].v, kb[j][i].v, b.hy);
    }
  if (gate_ && gate_->enabled() && tan_g() > 0)
    for (PetscInt i : {gate_->face() - 1, gate_->face()}) {
      if (i < b.xs || i >= b.xe()) continue;
      for (PetscInt j = std::max<PetscInt>(b.ys, 1); j < b.ye(); ++j) {
        if (kb[j][i].v <= 0) continue;
        loc[16] += kb[j][i].v / tan_g() * b.hy;
        // The traction on the grains, on either side: -kappa s (add_plastic), s the direction
        // of their velocity relative to the plate.
        loc[17] -= kb[j][i].v * sw[j][i].v * b.hy;
      }
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall, &sw));
  MPI_Allreduce(loc, glob, 18, MPI_DOUBLE, MPI_SUM, g_.comm());
  WallContact wc;
  for (int k = 0; k < 4; ++k) {
    wc.stick_m[k] = glob[k];
    wc.slide_m[k] = glob[k + 4];
    wc.normal_N[k] = glob[k + 8];
    wc.friction_N[k] = glob[k + 12];
  }
  wc.gate_normal_N = glob[16];
  wc.gate_friction_N = glob[17];
  return wc;
}

}  // namespace gf::boundary
