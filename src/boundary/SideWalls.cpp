#include "boundary/SideWalls.hpp"

#include <algorithm>
#include <cmath>

#include "core/Error.hpp"
#include "grid/Local.hpp"

namespace gf::boundary {

void SideWalls::yield(Vec frac, Vec support, Vec p, Vec kv) const {
  const Box& b = g_.box();
  const PetscScalar **c, **w, **pa;
  PetscScalar** k;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), frac, &c));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), support, &w));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), p, &pa));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), kv, &k));
  const double coef = active() ? 2.0 / p_.width * p_.tan_w * p_.earth_pressure : 0.0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i)
      k[j][i] = w[j][i] >= 0 ? coef * std::max(pa[j][i], 0.0) * std::clamp(c[j][i], 0.0, 1.0)
                             : 0.0;
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), kv, &k));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), p, &pa));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), support, &w));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), frac, &c));
}

void SideWalls::drag(Vec frac, Vec out) const {
  const Box& b = g_.box();
  const PetscScalar** c;
  PetscScalar** d;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), frac, &c));
  GF_PETSC(DMDAVecGetArray(g_.dm_cell(), out, &d));
  const double W = p_.width, ea = p_.eta_air, eb = p_.eta_b;
  const double coef = air_drag() ? 2.0 / W * ea * eb / (ea + eb * W / 6.0) : 0.0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) d[j][i] = coef * (1.0 - std::clamp(c[j][i], 0.0, 1.0));
  GF_PETSC(DMDAVecRestoreArray(g_.dm_cell(), out, &d));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), frac, &c));
}

void SideWalls::add_force(Vec kv, Vec sv, Vec rhs) const {
  const Box& b = g_.box();
  const LocalCells k(g_.dm_cell(), kv);
  const LocalArray<Vel> s(g_.dm_vel(), sv);
  Vel** out;
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), rhs, &out));
  // The face's share of the force of its two cells (the transpose of the cell-centre mean).
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (!b.wall_u(i))  // periodic x: cell -1 is the wrapped ghost
        out[j][i].u -= 0.5 * (k[j][i - 1] * s[j][i - 1].u + k[j][i] * s[j][i].u);
      if (j >= 1) out[j][i].v -= 0.5 * (k[j - 1][i] * s[j - 1][i].v + k[j][i] * s[j][i].v);
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), rhs, &out));
}

double SideWalls::update(Vec u, Vec kv, Vec sv, Vec s_n, Vec rho, Vec eta, double a0dt,
                         double theta, double r_factor, double k_ref) const {
  const Box& b = g_.box();
  const LocalVelocity v(g_, u);
  const PetscScalar **k, **r, **e;
  const Vel** sn;
  Vel** s;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kv, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), s_n, &sn));
  GF_PETSC(DMDAVecGetArray(g_.dm_vel(), sv, &s));
  const double h2 = b.hx * b.hy;
  double change = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double kc = k[j][i];
      if (kc <= 0) {
        s[j][i].u = s[j][i].v = 0.0;
        continue;
      }
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      const double rk = r_factor * (r[j][i] * a0dt + 2.0 * e[j][i] / h2) / kc;  // r k
      double sx = s[j][i].u + rk * uc + theta * (sn[j][i].u - s[j][i].u);
      double sy = s[j][i].v + rk * vc + theta * (sn[j][i].v - s[j][i].v);
      project_disc(sx, sy);
      change = std::max(change, kc / k_ref * std::max(std::abs(sx - s[j][i].u), std::abs(sy - s[j][i].v)));
      s[j][i].u = sx;
      s[j][i].v = sy;
    }
  GF_PETSC(DMDAVecRestoreArray(g_.dm_vel(), sv, &s));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), s_n, &sn));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), eta, &e));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), rho, &r));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kv, &k));
  return g_.max(change);
}

double SideWalls::power(Vec u, Vec kv, Vec sv) const {
  const Box& b = g_.box();
  const LocalVelocity v(g_, u);
  const PetscScalar** k;
  const Vel** s;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kv, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), sv, &s));
  double w = 0;
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      if (k[j][i] <= 0) continue;
      double uc, vc;
      cell_centre_velocity(v, i, j, uc, vc);
      w -= k[j][i] * (s[j][i].u * uc + s[j][i].v * vc);
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), sv, &s));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kv, &k));
  return g_.sum(w) * b.hx * b.hy;
}

SideContact SideWalls::contact(Vec kv, Vec sv, Vec frac) const {
  const Box& b = g_.box();
  const PetscScalar **k, **c;
  const Vel** s;
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), kv, &k));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_cell(), frac, &c));
  GF_PETSC(DMDAVecGetArrayRead(g_.dm_vel(), sv, &s));
  const double h2 = b.hx * b.hy;
  double loc[5] = {}, glob[5];
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const double kc = k[j][i];
      if (kc <= 0) continue;
      const bool slide = std::hypot(s[j][i].u, s[j][i].v) >= 1.0 - 1e-9;
      loc[slide ? 1 : 0] += std::clamp(c[j][i], 0.0, 1.0) * h2;
      loc[2] += kc / p_.tan_w * h2;
      loc[3] -= kc * s[j][i].u * h2;
      loc[4] -= kc * s[j][i].v * h2;
    }
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_vel(), sv, &s));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), frac, &c));
  GF_PETSC(DMDAVecRestoreArrayRead(g_.dm_cell(), kv, &k));
  MPI_Allreduce(loc, glob, 5, MPI_DOUBLE, MPI_SUM, g_.comm());
  return SideContact{glob[0], glob[1], glob[2], {glob[3], glob[4]}};
}

}  // namespace gf::boundary
