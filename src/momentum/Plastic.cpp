// The plastic part of the prediction step (eq. 31): the divergence of kappa S on the faces, the
// Coulomb wall tractions, the strain rate D(u~) that drives the projections of eqs. 29-30, and
// the wall projection. The cell projection of S lives in rheology/.
#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "momentum/Momentum.hpp"
#include "operators/Operators.hpp"
#include "rheology/Rheology.hpp"

namespace gf::momentum {

namespace {
// Ghosted copy of a global Vec for the duration of a scope, from the DM's pool of local vectors
// (DMGetLocalVector: no allocation after the first use, as these run in every fixed-point
// iteration).
struct Local {
  DM dm;
  Vec v = nullptr;
  Local(DM d, Vec global) : dm(d) {
    GF_PETSC(DMGetLocalVector(dm, &v));
    to_local(dm, global, v);
  }
  ~Local() { DMRestoreLocalVector(dm, &v); }
};
}  // namespace

bool Predictor::has_wall_friction() const {
  return std::any_of(tan_b_.begin(), tan_b_.end(), [](double t) { return t > 0; });
}

void Predictor::set_phase(Vec phi) {
  to_local(g_.dm_cell(), phi, lphi_);
  have_phase_ = true;
}

bool Predictor::coulomb_face(const PetscScalar* const* ph, int side, PetscInt i, PetscInt j) const {
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

void Predictor::add_plastic(Vec kappa, Vec S, Vec kappa_b, Vec s_wall, Vec rhs, Vec S_node) {
  const Box& b = g_.box();
  Local lk(g_.dm_cell(), kappa), ls(g_.dm_ten(), S);
  // The node copy: its ghosted values (a dummy zero field's layout is not needed: sn stays null).
  Vec lsn = nullptr;
  const PetscScalar*** sn = nullptr;
  if (S_node) {
    GF_PETSC(DMGetLocalVector(g_.dm_node(), &lsn));
    to_local(g_.dm_node(), S_node, lsn);
    GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_node(), lsn, &sn));
  }
  const double wc = S_node ? 0.5 : 1.0;  // the cell copy's share of the plastic stress
  const PetscScalar** k;
  const PetscScalar*** s;  // [j][i][c]
  const PetscScalar** ph = nullptr;
  const Vel **kb, **sw;
  Vel** out;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lk.v, &k));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), ls.v, &s));
  if (have_phase_) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), rhs, &out));
  const PetscInt ny = b.ny;
  auto kS = [&](PetscInt i, PetscInt j, int c) { return k[j][i] * s[j][i][c]; };
  // kappa at the node (i, j): mean over the cells around it that exist.
  auto k_node = [&](PetscInt i, PetscInt j) {
    double sum = 0;
    int cnt = 0;
    for (PetscInt jj = j - 1; jj <= j; ++jj)
      for (PetscInt ii = i - 1; ii <= i; ++ii)
        if (jj >= 0 && jj < b.ny && b.has_cell_x(ii)) {
          sum += k[jj][ii];
          ++cnt;
        }
    return cnt ? sum / cnt : 0.0;
  };
  auto kSn = [&](PetscInt i, PetscInt j, int c) { return k_node(i, j) * sn[j][i][c]; };
  // The normal stress of the cell (i, j) (c = 0: xx, 2: yy): the cell copy's share, plus the
  // node copy's as the mean of the cell's four corners (the adjoint of the node normal rate).
  auto cell_n = [&](PetscInt i, PetscInt j, int c) {
    double v = wc * kS(i, j, c);
    if (sn)
      v += (1 - wc) * 0.25 * (kSn(i, j, c) + kSn(i + 1, j, c) + kSn(i, j + 1, c) + kSn(i + 1, j + 1, c));
    return v;
  };
  // kappa Sxy at the node (i, j) = (i hx, j hy): mean of the four cells around an interior node.
  auto node = [&](PetscInt i, PetscInt j) {
    return 0.25 * (kS(i - 1, j - 1, 1) + kS(i, j - 1, 1) + kS(i - 1, j, 1) + kS(i, j, 1));
  };
  // kappa Sxy on a no-slip wall: linear extrapolation from the first two cells off the wall
  // (jn = the second row / in = the second column), averaged over the two cells along the wall.
  // Taking the first cells' value instead would put a stress that is half a cell too low on the
  // wall and make the viscous part carry the difference: an O(h^2) offset of the whole velocity
  // profile of a layer on a rough bed (measured on the Bagnold profile).
  auto wall_y = [&](PetscInt i, PetscInt j, PetscInt jn) {
    return 0.5 * (1.5 * (kS(i - 1, j, 1) + kS(i, j, 1)) - 0.5 * (kS(i - 1, jn, 1) + kS(i, jn, 1)));
  };
  auto wall_x = [&](PetscInt i, PetscInt in, PetscInt j) {
    return 0.5 * (1.5 * (kS(i, j - 1, 1) + kS(i, j, 1)) - 0.5 * (kS(in, j - 1, 1) + kS(in, j, 1)));
  };
  // Shear stress at a node from the two copies: the cell copy's value there (cell_part) and,
  // with the node copy, the node's own kappa Sxy (interior and no-slip wall nodes).
  auto shear = [&](double cell_part, PetscInt i, PetscInt j) {
    return sn ? wc * cell_part + (1 - wc) * kSn(i, j, 1) : cell_part;
  };
  const bool whole = S_node != nullptr;  // the node copy spreads kappa to every node
  const PetscInt ja = whole ? b.ys : std::max(b.ys, reg_.j0), jb = whole ? b.ye() : std::min(b.ye(), reg_.j1);
  const PetscInt ia = whole ? b.xs : std::max(b.xs, reg_.i0), ib = whole ? b.xe() : std::min(b.xe(), reg_.i1);
  for (PetscInt j = ja; j < jb; ++j)
    for (PetscInt i = ia; i < ib; ++i) {
      if (!b.wall_u(i)) {  // x-momentum on the face (i, j)
        double f = (cell_n(i, j, 0) - cell_n(i - 1, j, 0)) / b.hx;
        // top node (i, j+1)
        double tt;
        if (j + 1 < ny) tt = shear(node(i, j + 1), i, j + 1);
        else if (coulomb_face(ph, 3, i, j)) tt = -kb[j][i].u * sw[j][i].u;
        else tt = bc_.top.type == WallType::NoSlip ? shear(wall_y(i, j, j - 1), i, j + 1) : 0.0;
        // bottom node (i, j): the stress there is minus the wall traction on the fluid
        double tb;
        if (j >= 1) tb = shear(node(i, j), i, j);
        else if (coulomb_face(ph, 2, i, j)) tb = kb[j][i].u * sw[j][i].u;
        else tb = bc_.bottom.type == WallType::NoSlip ? shear(wall_y(i, j, j + 1), i, j) : 0.0;
        out[j][i].u += f + (tt - tb) / b.hy;
      }
      if (j >= 1) {  // y-momentum on the face (i, j)
        double f = (cell_n(i, j, 2) - cell_n(i, j - 1, 2)) / b.hy;
        double tr;
        if (!b.wall_u(i + 1)) tr = shear(node(i + 1, j), i + 1, j);  // periodic x: node nx is node 0
        else if (coulomb_face(ph, 1, i, j)) tr = -kb[j][i].v * sw[j][i].v;
        else tr = bc_.right.type == WallType::NoSlip ? shear(wall_x(i, i - 1, j), i + 1, j) : 0.0;
        double tl;
        if (!b.wall_u(i)) tl = shear(node(i, j), i, j);
        else if (coulomb_face(ph, 0, i, j)) tl = kb[j][i].v * sw[j][i].v;
        else tl = bc_.left.type == WallType::NoSlip ? shear(wall_x(i, i + 1, j), i, j) : 0.0;
        out[j][i].v += f + (tr - tl) / b.hx;
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), rhs, &out));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
  if (have_phase_) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), ls.v, &s));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lk.v, &k));
  if (lsn) {
    GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_node(), lsn, &sn));
    GF_PETSC(DMRestoreLocalVector(g_.dm_node(), &lsn));
  }
}

void Predictor::strain_rate(Vec vel, Vec eta, Vec D, Vec D_node) {
  const Box& b = g_.box();
  to_local(g_.dm_vel(), vel, lvel_);
  Local le(g_.dm_cell(), eta);
  Vel** v;
  const PetscScalar** e;
  const PetscScalar** ph = nullptr;
  PetscScalar*** d;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &v));
  fill_velocity_ghosts(g_, v);
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), le.v, &e));
  if (have_phase_) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(DMDAVecGetArrayDOF(g_.dm_ten(), D, &d));
  const PetscInt nx = b.nx, ny = b.ny;
  // Wall velocity seen by the first face at distance d from a wall (see boundary/Boundary.hpp).
  auto wall_u = [&](const WallBC& w, double uc, double eta_w, double dist, bool coulomb) {
    if (coulomb || w.type == WallType::FreeSlip) return uc;
    if (w.type == WallType::NoSlip) return w.velocity;
    return eta_w * uc / (eta_w + w.eta_b * dist);
  };
  // Engineering shear rate du/dy + dv/dx at the node (i, j).
  auto gamma = [&](PetscInt i, PetscInt j) -> double {
    const bool wx = b.wall_u(i), wy = (j == 0 || j == ny);  // nodes on the walls
    if (wx && wy) return 0.0;  // corner
    if (!wx && !wy)
      return (v[j][i].u - v[j - 1][i].u) / b.hy + (v[j][i].v - v[j][i - 1].v) / b.hx;
    if (wy) {  // bottom or top wall: v = 0 along it, du/dy from the wall velocity
      const bool bottom = (j == 0);
      const PetscInt jc = bottom ? 0 : ny - 1;
      const double uc = v[jc][i].u;
      const double ew = 0.5 * (e[jc][i - 1] + e[jc][i]);
      const double uw = wall_u(bottom ? bc_.bottom : bc_.top, uc, ew, 0.5 * b.hy,
                               coulomb_face(ph, bottom ? 2 : 3, i, jc));
      return bottom ? (uc - uw) / (0.5 * b.hy) : (uw - uc) / (0.5 * b.hy);
    }
    const bool left = (i == 0);  // left or right wall: dv/dx from the wall velocity
    const PetscInt ic = left ? 0 : nx - 1;
    const double vc = v[j][ic].v;
    const double ew = 0.5 * (e[j - 1][ic] + e[j][ic]);
    const double vw = wall_u(left ? bc_.left : bc_.right, vc, ew, 0.5 * b.hx,
                             coulomb_face(ph, left ? 0 : 1, ic, j));
    return left ? (vc - vw) / (0.5 * b.hx) : (vw - vc) / (0.5 * b.hx);
  };
  const PetscInt ja = std::max(b.ys, reg_.j0), jb = std::min(b.ye(), reg_.j1);
  const PetscInt ia = std::max(b.xs, reg_.i0), ib = std::min(b.xe(), reg_.i1);
  for (PetscInt j = ja; j < jb; ++j)
    for (PetscInt i = ia; i < ib; ++i) {
      const double dxx = (v[j][i + 1].u - v[j][i].u) / b.hx;
      const double dyy = (v[j + 1][i].v - v[j][i].v) / b.hy;
      const double dxy =
          0.125 * (gamma(i, j) + gamma(i + 1, j) + gamma(i, j + 1) + gamma(i + 1, j + 1));
      d[j][i][0] = dxx;
      d[j][i][1] = dxy;
      d[j][i][2] = dyy;
    }
  GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_ten(), D, &d));
  if (D_node) {
    // The node copy: the node shear rate itself (wall nodes: only on no-slip walls, where the
    // node copy's shear stress is the wall stress, see add_plastic), and the mean normal rate
    // of the node's cells.
    PetscInt xs, ys, xm, ym;
    GF_PETSC(DMDAGetCorners(g_.dm_node(), &xs, &ys, nullptr, &xm, &ym, nullptr));
    PetscScalar*** dn;
    GF_PETSC(DMDAVecGetArrayDOF(g_.dm_node(), D_node, &dn));
    auto cell_xx = [&](PetscInt i, PetscInt j) {
      return 0.5 * ((v[j][i + 1].u - v[j][i].u) / b.hx - (v[j + 1][i].v - v[j][i].v) / b.hy);
    };
    for (PetscInt j = ys; j < ys + ym; ++j)
      for (PetscInt i = xs; i < xs + xm; ++i) {
        double sum = 0;
        int cnt = 0;
        for (PetscInt jj = j - 1; jj <= j; ++jj)
          for (PetscInt ii = i - 1; ii <= i; ++ii)
            if (jj >= 0 && jj < ny && b.has_cell_x(ii)) {
              sum += cell_xx(ii, jj);
              ++cnt;
            }
        const bool wx = b.wall_u(i), wy = (j == 0 || j == ny);
        double gm = 0;
        if (!wx && !wy) gm = gamma(i, j);
        else if (!(wx && wy)) {
          const WallBC& w = wy ? (j == 0 ? bc_.bottom : bc_.top) : (i == 0 ? bc_.left : bc_.right);
          const int side = wy ? (j == 0 ? 2 : 3) : (i == 0 ? 0 : 1);
          const bool coul = wy ? coulomb_face(ph, side, i, j == 0 ? 0 : ny - 1)
                               : coulomb_face(ph, side, i == 0 ? 0 : nx - 1, j);
          if (w.type == WallType::NoSlip && !coul) gm = gamma(i, j);
        }
        const double xx = cnt ? sum / cnt : 0.0;
        dn[j][i][0] = xx;
        dn[j][i][1] = 0.5 * gm;
        dn[j][i][2] = -xx;
      }
    GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_node(), D_node, &dn));
  }
  if (have_phase_) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), le.v, &e));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &v));
}

void Predictor::cache_wall_inputs(Vec p, Vec kappa, Vec eta) {
  for (Vec* v : {&lwp_, &lwk_, &lwe_})
    if (!*v) GF_PETSC(DMCreateLocalVector(g_.dm_cell(), v));
  to_local(g_.dm_cell(), p, lwp_);
  to_local(g_.dm_cell(), kappa, lwk_);
  to_local(g_.dm_cell(), eta, lwe_);
  wall_cached_ = true;
}

void Predictor::wall_yield(Vec p, Vec S, Vec kappa, Vec D, Vec eta, Vec kappa_b) {
  const Box& b = g_.box();
  const PetscScalar** ph = nullptr;
  Vel** kb;
  if (!wall_cached_) {  // outside the fixed point: ghost them for this call only
    cache_wall_inputs(p, kappa, eta);
    wall_cached_ = false;
  }
  Local ls(g_.dm_ten(), S), ld(g_.dm_ten(), D);
  const PetscScalar **pa, **k, **e;
  const PetscScalar ***sa, ***da;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwp_, &pa));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwk_, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lwe_, &e));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), ls.v, &sa));
  GF_PETSC(DMDAVecGetArrayDOFRead(g_.dm_ten(), ld.v, &da));
  if (have_phase_) GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(VecSet(kappa_b, 0.0));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), kappa_b, &kb));
  // -T_n = p - T'_nn with T'_nn = 2 eta D_nn + kappa S_nn, the deviatoric normal stress along
  // the wall normal (yy at the bottom and top, xx at the left and right), at a cell next to
  // the wall. In a rigid zone p alone is not the normal load: S carries part of it.
  auto mT = [&](PetscInt i, PetscInt j, int c) {
    return pa[j][i] - 2.0 * e[j][i] * da[j][i][c] - k[j][i] * sa[j][i][c];
  };
  auto pos = [](double x) { return x > 0 ? x : 0.0; };
  // The normal stress ON the wall: linear extrapolation from the first two cells off it, mean
  // of the two cells along the wall. The first cells' value alone is half a cell of weight
  // short (hydrostatic increment rho g h/2): 5 % of the friction of a 10-cell-high block at
  // n = 30, which made it slide 8 % too fast.
  auto wall_y = [&](PetscInt i, PetscInt j, PetscInt jn) {
    return 0.5 * (1.5 * (mT(i - 1, j, 2) + mT(i, j, 2)) - 0.5 * (mT(i - 1, jn, 2) + mT(i, jn, 2)));
  };
  auto wall_x = [&](PetscInt i, PetscInt in, PetscInt j) {
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
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), kappa_b, &kb));
  if (have_phase_) GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lphi_, &ph));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), ld.v, &da));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g_.dm_ten(), ls.v, &sa));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwe_, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwk_, &k));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), lwp_, &pa));
}

double Predictor::update_wall(Vec u_tilde, Vec kappa_b, Vec s_wall, Vec s_wall_n, Vec rho, Vec eta,
                              double a0dt, double theta, double r_factor) {
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
    const double rb = r_factor * (rc * a0dt * h + 2.0 * ec / h) / (k * k);
    const double snew = rheology::project_b(s + rb * k * ut + theta * (s_n - s));
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
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall_n, &sn));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), u_tilde, &u));
  return g_.max(change);
}

Predictor::WallContact Predictor::wall_contact(Vec s_wall, Vec kappa_b) const {
  const Box& b = g_.box();
  const Vel **sw, **kb;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), kappa_b, &kb));
  double loc[16] = {}, glob[16];
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
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall, &sw));
  MPI_Allreduce(loc, glob, 16, MPI_DOUBLE, MPI_SUM, g_.comm());
  WallContact wc;
  for (int k = 0; k < 4; ++k) {
    wc.stick_m[k] = glob[k];
    wc.slide_m[k] = glob[k + 4];
    wc.normal_N[k] = glob[k + 8];
    wc.friction_N[k] = glob[k + 12];
  }
  return wc;
}

}  // namespace gf::momentum
