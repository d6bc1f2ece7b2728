// The plastic part of the prediction step (eq. 31): the divergence of kappa S on the faces with
// the Coulomb wall tractions, and the strain rate D(u~) that drives the projections of
// eqs. 29-30. The cell projection of S lives in rheology/, the wall one in boundary/Coulomb.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/Error.hpp"
#include "grid/Local.hpp"
#include "momentum/Momentum.hpp"
#include "operators/Operators.hpp"

namespace gf::momentum {

void Predictor::add_plastic(Vec kappa, Vec S, Vec kappa_b, Vec s_wall, Vec rhs, Vec S_node) {
  const Box& b = g_.box();
  const LocalCells k(g_.dm_cell(), kappa);
  const LocalDof s(g_.dm_ten(), S);  // [j][i][c]
  // The node copy (rheology.plastic_grid = "cell_node"), ghosted; sn stays null without it.
  std::optional<LocalDof> lsn;
  if (S_node) lsn.emplace(g_.dm_node(), S_node);
  PetscScalar* const* const* sn = lsn ? lsn->array() : nullptr;
  const double wc = S_node ? 0.5 : 1.0;  // the cell copy's share of the plastic stress
  const boundary::CoulombWalls::Phase phase(walls_);
  const PetscScalar* const* ph = phase.array();
  const Vel **kb, **sw;
  Vel** out;
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
        else if (walls_.coulomb_face(ph, 3, i, j)) tt = -kb[j][i].u * sw[j][i].u;
        else tt = bc_.top.type == WallType::NoSlip ? shear(wall_y(i, j, j - 1), i, j + 1) : 0.0;
        // bottom node (i, j): the stress there is minus the wall traction on the fluid
        double tb;
        if (j >= 1) tb = shear(node(i, j), i, j);
        else if (walls_.coulomb_face(ph, 2, i, j)) tb = kb[j][i].u * sw[j][i].u;
        else tb = bc_.bottom.type == WallType::NoSlip ? shear(wall_y(i, j, j + 1), i, j) : 0.0;
        out[j][i].u += f + (tt - tb) / b.hy;
      }
      if (j >= 1) {  // y-momentum on the face (i, j)
        double f = (cell_n(i, j, 2) - cell_n(i, j - 1, 2)) / b.hy;
        // On the gate's covered nodes (boundary/Gate.hpp) the Coulomb traction of the plate on
        // the grains, or nothing, instead of the shear across the plate.
        double tr;
        if (gate_node(i + 1, j)) tr = walls_.gate_face(ph, i, j) ? -kb[j][i].v * sw[j][i].v : 0.0;
        else if (!b.wall_u(i + 1)) tr = shear(node(i + 1, j), i + 1, j);  // periodic x: node nx is node 0
        else if (walls_.coulomb_face(ph, 1, i, j)) tr = -kb[j][i].v * sw[j][i].v;
        else tr = bc_.right.type == WallType::NoSlip ? shear(wall_x(i, i - 1, j), i + 1, j) : 0.0;
        double tl;
        if (gate_node(i, j)) tl = walls_.gate_face(ph, i, j) ? kb[j][i].v * sw[j][i].v : 0.0;
        else if (!b.wall_u(i)) tl = shear(node(i, j), i, j);
        else if (walls_.coulomb_face(ph, 0, i, j)) tl = kb[j][i].v * sw[j][i].v;
        else tl = bc_.left.type == WallType::NoSlip ? shear(wall_x(i, i + 1, j), i, j) : 0.0;
        out[j][i].v += f + (tr - tl) / b.hx;
      }
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), rhs, &out));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_wall, &sw));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), kappa_b, &kb));
}

void Predictor::strain_rate(Vec vel, Vec eta, Vec D, Vec D_node) {
  const Box& b = g_.box();
  to_local(g_.dm_vel(), vel, lvel_);
  const LocalCells e(g_.dm_cell(), eta);
  Vel** v;
  const boundary::CoulombWalls::Phase phase(walls_);
  const PetscScalar* const* ph = phase.array();
  PetscScalar*** d;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), lvel_, &v));
  fill_velocity_ghosts(g_, v);
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
    // A node on the gate: no shear across the plate; its own traction is the Coulomb one (or
    // none), as on a Coulomb wall (zero shear rate there).
    if (gate_node(i, j)) return 0.0;
    if (!wx && !wy)
      return (v[j][i].u - v[j - 1][i].u) / b.hy + (v[j][i].v - v[j][i - 1].v) / b.hx;
    if (wy) {  // bottom or top wall: v = 0 along it, du/dy from the wall velocity
      const bool bottom = (j == 0);
      const PetscInt jc = bottom ? 0 : ny - 1;
      const double uc = v[jc][i].u;
      const double ew = 0.5 * (e[jc][i - 1] + e[jc][i]);
      const double uw = wall_u(bottom ? bc_.bottom : bc_.top, uc, ew, 0.5 * b.hy,
                               walls_.coulomb_face(ph, bottom ? 2 : 3, i, jc));
      return bottom ? (uc - uw) / (0.5 * b.hy) : (uw - uc) / (0.5 * b.hy);
    }
    const bool left = (i == 0);  // left or right wall: dv/dx from the wall velocity
    const PetscInt ic = left ? 0 : nx - 1;
    const double vc = v[j][ic].v;
    const double ew = 0.5 * (e[j - 1][ic] + e[j][ic]);
    const double vw = wall_u(left ? bc_.left : bc_.right, vc, ew, 0.5 * b.hx,
                             walls_.coulomb_face(ph, left ? 0 : 1, ic, j));
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
          const bool coul = wy ? walls_.coulomb_face(ph, side, i, j == 0 ? 0 : ny - 1)
                               : walls_.coulomb_face(ph, side, i == 0 ? 0 : nx - 1, j);
          if (w.type == WallType::NoSlip && !coul) gm = gamma(i, j);
        }
        const double xx = cnt ? sum / cnt : 0.0;
        dn[j][i][0] = xx;
        dn[j][i][1] = 0.5 * gm;
        dn[j][i][2] = -xx;
      }
    GF_PETSC(DMDAVecRestoreArrayDOF(g_.dm_node(), D_node, &dn));
  }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), lvel_, &v));
}

}  // namespace gf::momentum
