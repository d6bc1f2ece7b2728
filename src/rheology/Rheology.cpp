#include "rheology/Rheology.hpp"

#include <vector>

#include "core/Error.hpp"
#include "grid/Local.hpp"

namespace gf::rheology {

void hydrostatic_pressure(const Grid& g, Vec c, double rho_s, double g_abs, Vec out) {
  const Box& b = g.box();
  const PetscScalar** ca;
  PetscScalar** pa;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), c, &ca));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), out, &pa));
  // Local column sums of this rank's rows.
  std::vector<double> local(b.xm, 0.0), above(b.xm, 0.0);
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) local[i - b.xs] += ca[j][i] * b.hy;
  // The thickness held by the ranks above: an exclusive prefix sum over the process column,
  // whose ranks are ordered from the top down (Grid::comm_column).
  MPI_Exscan(local.data(), above.data(), static_cast<int>(b.xm), MPI_DOUBLE, MPI_SUM,
             g.comm_column());
  int crank = 0;
  MPI_Comm_rank(g.comm_column(), &crank);
  if (crank == 0) std::fill(above.begin(), above.end(), 0.0);  // Exscan leaves rank 0 undefined
  for (PetscInt i = b.xs; i < b.xe(); ++i) {
    double acc = above[i - b.xs];  // thickness above the top of this rank's rows
    for (PetscInt j = b.ye() - 1; j >= b.ys; --j) {
      const double own = ca[j][i] * b.hy;
      pa[j][i] = rho_s * g_abs * (acc + 0.5 * own);  // to the cell centre
      acc += own;
    }
  }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), out, &pa));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), c, &ca));
}

}  // namespace gf::rheology

namespace gf::rheology {

double update_plastic(const Grid& g, const Params& pr, Vec S, Vec S_n, Vec kappa, Vec D, Vec rho,
                      Vec eta, double a0dt, double theta) {
  const Box& b = g.box();
  PetscScalar*** s;
  const PetscScalar ***sn, ***d;
  const PetscScalar **k, **r, **e;
  GF_PETSC(DMDAVecGetArrayDOF(g.dm_ten(), S, &s));
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_ten(), S_n, &sn));
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_ten(), D, &d));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), kappa, &k));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), eta, &e));
  const double h2 = std::min(b.hx, b.hy) * std::min(b.hx, b.hy);
  double change = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double* sc = s[j][i];
      if (k[j][i] <= 0) {
        sc[0] = sc[1] = sc[2] = 0.0;
        continue;
      }
      const double rk = r_local(pr, k[j][i], e[j][i], r[j][i] * a0dt * h2) * k[j][i];
      // The deviatoric part of D: in the plane, incompressibility makes D traceless only up
      // to the solver tolerance; the projection acts on the traceless part.
      const double dxx = 0.5 * (d[j][i][0] - d[j][i][2]);
      double sxx = sc[0] + rk * dxx + theta * (sn[j][i][0] - sc[0]);
      double sxy = sc[1] + rk * d[j][i][1] + theta * (sn[j][i][1] - sc[1]);
      project(sxx, sxy);
      change = std::max(change, std::hypot(sxx - sc[0], sxy - sc[1]));
      sc[0] = sxx;
      sc[1] = sxy;
      sc[2] = -sxx;
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), kappa, &k));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_ten(), D, &d));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_ten(), S_n, &sn));
  GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_ten(), S, &s));
  return g.max(change);
}

void neighbourhood_min(const Grid& g, Vec in, Vec out) {
  const Box& b = g.box();
  Vec loc;
  GF_PETSC(DMGetLocalVector(g.dm_cell(), &loc));
  GF_PETSC(DMGlobalToLocalBegin(g.dm_cell(), in, INSERT_VALUES, loc));
  GF_PETSC(DMGlobalToLocalEnd(g.dm_cell(), in, INSERT_VALUES, loc));
  const PetscScalar** a;
  PetscScalar** o;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), loc, &a));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), out, &o));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double m = a[j][i];
      for (PetscInt dj = -1; dj <= 1; ++dj)
        for (PetscInt di = -1; di <= 1; ++di) {
          const PetscInt jj = j + dj, ii = i + di;
          if (jj < 0 || jj >= b.ny || !b.has_cell_x(ii)) continue;  // beyond a wall
          m = std::min(m, static_cast<double>(a[jj][ii]));
        }
      o[j][i] = m;
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), out, &o));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), loc, &a));
  GF_PETSC(DMRestoreLocalVector(g.dm_cell(), &loc));
}

namespace {
// Mean over the cells around the node (i, j) that exist, of a ghosted dm_cell array.
double node_mean(const Box& b, const PetscScalar* const* a, PetscInt i, PetscInt j) {
  double sum = 0;
  int cnt = 0;
  for (PetscInt jj = j - 1; jj <= j; ++jj)
    for (PetscInt ii = i - 1; ii <= i; ++ii)
      if (jj >= 0 && jj < b.ny && b.has_cell_x(ii)) {
        sum += a[jj][ii];
        ++cnt;
      }
  return cnt ? sum / cnt : 0.0;
}
}  // namespace

double update_plastic_node(const Grid& g, const Params& pr, Vec S, Vec S_n, Vec kappa, Vec D,
                           Vec rho, Vec eta, double a0dt, double theta) {
  const Box& b = g.box();
  const LocalCells lk(g.dm_cell(), kappa), lr(g.dm_cell(), rho), le(g.dm_cell(), eta);
  PetscScalar*** s;
  const PetscScalar ***sn, ***d;
  GF_PETSC(DMDAVecGetArrayDOF(g.dm_node(), S, &s));
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_node(), S_n, &sn));
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_node(), D, &d));
  PetscInt xs, ys, xm, ym;
  GF_PETSC(DMDAGetCorners(g.dm_node(), &xs, &ys, nullptr, &xm, &ym, nullptr));
  const double h2 = std::min(b.hx, b.hy) * std::min(b.hx, b.hy);
  double change = 0;
  for (PetscInt j = ys; j < ys + ym; ++j)
    for (PetscInt i = xs; i < xs + xm; ++i) {
      double* sc = s[j][i];
      const double k = node_mean(b, lk.array(), i, j);
      if (k <= 0) {
        sc[0] = sc[1] = sc[2] = 0.0;
        continue;
      }
      const double rk =
          r_local(pr, k, node_mean(b, le.array(), i, j), node_mean(b, lr.array(), i, j) * a0dt * h2) * k;
      const double dxx = 0.5 * (d[j][i][0] - d[j][i][2]);
      double sxx = sc[0] + rk * dxx + theta * (sn[j][i][0] - sc[0]);
      double sxy = sc[1] + rk * d[j][i][1] + theta * (sn[j][i][1] - sc[1]);
      project(sxx, sxy);
      change = std::max(change, std::hypot(sxx - sc[0], sxy - sc[1]));
      sc[0] = sxx;
      sc[1] = sxy;
      sc[2] = -sxx;
    }
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_node(), D, &d));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_node(), S_n, &sn));
  GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_node(), S, &s));
  return g.max(change);
}

void project_field_node(const Grid& g, Vec S, Vec kappa) {
  const Box& b = g.box();
  const LocalCells lk(g.dm_cell(), kappa);
  PetscScalar*** s;
  GF_PETSC(DMDAVecGetArrayDOF(g.dm_node(), S, &s));
  PetscInt xs, ys, xm, ym;
  GF_PETSC(DMDAGetCorners(g.dm_node(), &xs, &ys, nullptr, &xm, &ym, nullptr));
  for (PetscInt j = ys; j < ys + ym; ++j)
    for (PetscInt i = xs; i < xs + xm; ++i) {
      double* c = s[j][i];
      if (node_mean(b, lk.array(), i, j) <= 0) {
        c[0] = c[1] = c[2] = 0.0;
        continue;
      }
      project(c[0], c[1]);
      c[2] = -c[0];
    }
  GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_node(), S, &s));
}

void yield_stress(const Grid& g, const Params& pr, Vec support, Vec p, Vec p_hyd, Vec kappa) {
  const Box& b = g.box();
  const PetscScalar **w, **pa, **ph_hyd = nullptr;
  PetscScalar** k;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), support, &w));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), p, &pa));
  if (pr.yield == Yield::Hydrostatic) GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), p_hyd, &ph_hyd));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), kappa, &k));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double kv = 0;
      if (w[j][i] >= 0) {
        switch (pr.yield) {
          case Yield::None: kv = 0; break;
          case Yield::Bingham: {
            // "mass" support: a constant yield stress scaled by the cell's granular volume
            // fraction 1 - H_eps(phi) (eq. 25's weight), so that it goes to zero with the
            // granular mass at phi = eps instead of jumping there. With the step, cells that are
            // air to round-off (a block face 1.5 h from their centres) carried the full tau_y
            // next to air faces 1000 times lighter, and switched it on and off row by row as phi
            // moved by 1e-10 m: a holding Bingham block (cases/verify/coulomb_block.toml tilted
            // to 15 deg) drove the air at its corners to 7e-3 m/s in one step and crept at
            // 1e-5 m/s. Fractions below 1e-9 count as none (r ~ 1/kappa^2). The
            // pressure-proportional yield stresses below need no weight: they vanish with the
            // overburden at a free surface (for DP, down to tan(alpha) times the air's
            // pressure), and the band's pressure carries its dilution; weighting them as well
            // let a Drucker-Prager pile's toes slide (cases/verify/dp_pile.toml: 4.6e-4 m/s).
            const double frac = w[j][i];
            kv = frac > 1e-9 ? pr.tau_y * frac : 0.0;
            break;
          }
          case Yield::DruckerPrager: kv = pr.tan_alpha * std::max(pa[j][i], 0.0); break;
          case Yield::Hydrostatic: kv = pr.tan_alpha * std::max(ph_hyd[j][i], 0.0); break;
        }
      }
      k[j][i] = kv;
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), kappa, &k));
  if (ph_hyd) GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), p_hyd, &ph_hyd));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), p, &pa));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), support, &w));
}

void mu_i_viscosity(const Grid& g, const Params& pr, Vec D, Vec p, double rho_s, Vec eta_s) {
  const Box& b = g.box();
  const PetscScalar*** d;
  const PetscScalar** pa;
  PetscScalar** es;
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_ten(), D, &d));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), p, &pa));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), eta_s, &es));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double dxx = 0.5 * (d[j][i][0] - d[j][i][2]), dxy = d[j][i][1];
      es[j][i] = mu_i_viscosity(pr, std::hypot(dxx, dxy), pa[j][i], rho_s);
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), eta_s, &es));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), p, &pa));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_ten(), D, &d));
}

void project_field(const Grid& g, Vec S, Vec kappa) {
  const Box& b = g.box();
  PetscScalar*** s;
  const PetscScalar** k;
  GF_PETSC(DMDAVecGetArrayDOF(g.dm_ten(), S, &s));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), kappa, &k));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      double* c = s[j][i];
      if (k[j][i] <= 0) {
        c[0] = c[1] = c[2] = 0.0;
        continue;
      }
      project(c[0], c[1]);
      c[2] = -c[0];
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), kappa, &k));
  GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_ten(), S, &s));
}

void tensor_norm(const Grid& g, Vec L, Vec out) {
  const Box& b = g.box();
  const PetscScalar*** l;
  PetscScalar** o;
  GF_PETSC(DMDAVecGetArrayDOFRead(g.dm_ten(), L, &l));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), out, &o));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double* c = l[j][i];
      o[j][i] = std::sqrt(0.5 * (c[0] * c[0] + 2 * c[1] * c[1] + c[2] * c[2]));
    }
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), out, &o));
  GF_PETSC(DMDAVecRestoreArrayDOFRead(g.dm_ten(), L, &l));
}

void yielded_mask(const Grid& g, Vec Snorm, Vec kappa, Vec yielded) {
  const Box& b = g.box();
  const PetscScalar **sn, **k;
  PetscScalar** y;
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), Snorm, &sn));
  GF_PETSC(DMDAVecGetArrayRead(g.dm_cell(), kappa, &k));
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), yielded, &y));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      y[j][i] = (k[j][i] <= 0 || sn[j][i] >= 1.0 - 1e-9) ? 1.0 : 0.0;
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), yielded, &y));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), kappa, &k));
  GF_PETSC(DMDAVecRestoreArrayRead(g.dm_cell(), Snorm, &sn));
}

}  // namespace gf::rheology
